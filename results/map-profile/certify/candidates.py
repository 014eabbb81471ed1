"""The points of a committed refined map that `refine.certify_midpoints` would consider.

    python3 results/map-profile/certify/candidates.py MAP_DIR [MAP_DIR ...]

A point of level l >= 1 is a candidate when it lies midway, along one axis, between two points
of lower levels whose labels are one single state (IC, ID or MD) with every run settled
(crates/sweep/src/map/refine.rs, `midway`; crates/sweep/src/map/certify.rs). Reads the map's
points.parquet and runs.parquet (polars) and prints one JSON object per map: the candidates,
their runs' share of the map's run time (`wall_s` as recorded), by level, and how many of them
the map labels like their two neighbours. The certificate's own checks at the point (Newton
from the neighbours' ends, the stability of every named state) are not made here: they can
only refuse candidates.
"""
import json
import sys

import polars as pl


def candidates(m):
    p = pl.read_parquet(f"{m}/points.parquet")
    r = pl.read_parquet(f"{m}/runs.parquet")
    p = p.join(r.group_by("point").agg(pl.col("wall_s").sum()), on="point")
    finest = p["level"].max()
    fine = p.filter(pl.col("level") == finest)
    de, dk = fine["d_eta_t"][0], fine["d_kappa2"][0]
    e0, k0 = p["eta_t"].min(), p["kappa2"].min()
    at = {(round((x["eta_t"] - e0) / de), round((x["kappa2"] - k0) / dk)): x for x in p.iter_rows(named=True)}
    single = {"IC", "ID", "MD"}
    out = {"map": m, "points": len(at), "run_time_s": round(p["wall_s"].sum(), 1), "candidates": 0,
           "candidate_run_time_s": 0.0, "by_level": {}, "same_label": 0}
    for (i, j), x in at.items():
        level = x["level"]
        if level == 0:
            continue
        d = 2 ** (finest - level)
        for a, b in [((i - d, j), (i + d, j)), ((i, j - d), (i, j + d))]:
            if a in at and b in at and at[a]["level"] < level and at[b]["level"] < level:
                A, B = at[a], at[b]
                if A["class"] == B["class"] and A["class"] in single and A["settled"] and B["settled"]:
                    out["candidates"] += 1
                    out["candidate_run_time_s"] += x["wall_s"]
                    out["by_level"][str(level)] = out["by_level"].get(str(level), 0) + 1
                    out["same_label"] += x["class"] == A["class"]
                    break
    out["candidate_run_time_s"] = round(out["candidate_run_time_s"], 1)
    out["share"] = round(out["candidate_run_time_s"] / out["run_time_s"], 3)
    return out


for m in sys.argv[1:]:
    print(json.dumps(candidates(m)))
