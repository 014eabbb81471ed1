"""A map made with `refine.certify_midpoints` against the same spec made without it.

    python3 results/map-profile/certify/compare.py PLAIN_DIR CERTIFIED_DIR

Prints one JSON object: points and label differences; the certified runs (`ended_by`
`certified_midway`) against the same runs stepped in the plain map (same keys): class
differences, how many end on another root (`v` or `s` more than 1e-6 apart) and by how much,
and the largest difference of the others; the certificates' time against those runs' time.
"""
import json
import sys

import polars as pl

plain, cert = sys.argv[1], sys.argv[2]
a = pl.read_parquet(f"{plain}/points.parquet")
b = pl.read_parquet(f"{cert}/points.parquet")
j = a.join(b, on=["eta_t", "kappa2"], suffix="_c")
ra = pl.read_parquet(f"{plain}/runs.parquet")
rb = pl.read_parquet(f"{cert}/runs.parquet")
c = (
    rb.filter(pl.col("ended_by") == "certified_midway")
    .join(ra, on="key", suffix="_p")
    .with_columns(
        (pl.col("v") - pl.col("v_p")).abs().alias("dv"),
        (pl.col("s") - pl.col("s_p")).abs().alias("ds"),
    )
)
off = c.filter((pl.col("dv") > 1e-6) | (pl.col("ds") > 1e-6))
on = c.filter((pl.col("dv") <= 1e-6) & (pl.col("ds") <= 1e-6))
print(json.dumps({
    "plain": plain,
    "certified": cert,
    "points": [a.height, b.height],
    "label_differences": j.filter(pl.col("class") != pl.col("class_c")).height,
    "certified_runs": c.height,
    "certified_by_class": dict(sorted(c.group_by("class").len().iter_rows())),
    "class_differences": c.filter(pl.col("class") != pl.col("class_p")).height,
    "other_root": off.height,
    "other_root_classes": off["class"].to_list(),
    "other_root_max_dv": off["dv"].max(),
    "other_root_max_ds": off["ds"].max(),
    "same_root_max_dv": on["dv"].max(),
    "same_root_max_ds": on["ds"].max(),
    "certificates_s": round(c["wall_s"].sum(), 2),
    "their_runs_s": round(c["wall_s_p"].sum(), 2),
}))
