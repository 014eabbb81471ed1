"""Level 0 of the Fig. 2a window with two models, point by point.

Usage: python3 compare.py TWO_MODE_DIR K_MODE_DIR [NAME NAME] > compare.json
Each DIR is a sweep's output (points.parquet, runs.parquet) of the same grid and initial
conditions; NAME NAME (default two_modes k_modes) name the two models in the output (for
two K-mode models: modes4 modes6). Prints one JSON object: per model the point classes, how the runs ended and their
run time (the sum of the runs' wall_s, one machine); the points whose class differs; and per
initial condition the runs whose class differs.
"""
import json
import sys

import polars as pl


def model(d):
    pts = pl.read_parquet(f"{d}/points.parquet").sort(["eta_t", "kappa2"])
    runs = pl.read_parquet(f"{d}/runs.parquet")
    ended = runs.group_by("ended_by").len().sort("ended_by")
    return pts, runs, {
        "points": pts.height,
        "runs": runs.height,
        "point_classes": dict(pts.group_by("class").len().sort("class").iter_rows()),
        "run_statuses": dict(runs.group_by("status").len().sort("status").iter_rows()),
        "ended_by": {str(k): v for k, v in ended.iter_rows()},
        "run_time_s": round(runs["wall_s"].sum(), 1),
        "median_run_s": round(runs["wall_s"].median(), 3),
        "slowest_run_s": round(runs["wall_s"].max(), 1),
    }


first, second = sys.argv[3:5] if len(sys.argv) > 4 else ("two_modes", "k_modes")
two_pts, two_runs, two = model(sys.argv[1])
k_pts, k_runs, k = model(sys.argv[2])
key = ["eta_t", "kappa2"]
both = two_pts.select(key + ["class"]).join(
    k_pts.select(key + ["class"]), on=key, suffix="_k"
)
changed = both.filter(pl.col("class") != pl.col("class_k"))
runs = two_runs.select(key + ["ic", "class", "v"]).join(
    k_runs.select(key + ["ic", "class", "v"]), on=key + ["ic"], suffix="_k"
)
run_changes = runs.filter(pl.col("class").ne_missing(pl.col("class_k")))
out = {
    first: two,
    second: k,
    "run_time_ratio": round(k["run_time_s"] / two["run_time_s"], 3),
    "points_compared": both.height,
    "points_changed": changed.height,
    "changes": [
        {"eta_t": e, "kappa2": q, first: a, second: b}
        for e, q, a, b in changed.iter_rows()
    ],
    "run_class_changes": dict(
        run_changes.group_by(["class", "class_k"]).len().sort("len", descending=True)
        .select(pl.concat_str([pl.col("class").fill_null("none"), pl.lit(" -> "),
                               pl.col("class_k").fill_null("none")]), "len").iter_rows()
    ),
}
json.dump(out, sys.stdout, indent=1)
print()
