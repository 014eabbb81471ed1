"""A finished map's stepped runs grouped by the decade of their simulated time t_end (runs
certified without steps left out): runs, their run time and steps, and each group's share of
the map's run time.  python3 duration.py MAP_DIR [MAP_DIR ...]  (prints one JSON object)"""
import json, math, sys
import polars as pl

def decade(t):
    return 1 if t < 10 else min(int(math.floor(math.log10(t))), 4) + 1

NAMES = {1: "t < 10", 2: "10 <= t < 100", 3: "100 <= t < 1000", 4: "1000 <= t < 10000", 5: "t >= 10000"}
out = {}
for path in sys.argv[1:]:
    runs = pl.read_parquet(f"{path}/runs.parquet").filter(pl.col("steps") > 0)
    total = runs["wall_s"].sum()
    runs = runs.with_columns(pl.col("t_end").map_elements(decade, return_dtype=pl.Int64).alias("decade"))
    groups = runs.group_by("decade").agg(pl.len().alias("runs"), pl.col("wall_s").sum(), pl.col("steps").sum()).sort("decade")
    out[path] = {
        "stepped_runs": runs.height, "run_time_s": total,
        "groups": [{"name": NAMES[g["decade"]], "runs": g["runs"], "run_time_s": g["wall_s"],
                    "share": g["wall_s"] / total, "steps": g["steps"]} for g in groups.rows(named=True)],
    }
print(json.dumps(out, indent=1))
