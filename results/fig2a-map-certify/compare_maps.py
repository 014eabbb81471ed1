"""The map made with refine.certify_midpoints against the committed map, point by point and
run by run, and its run time against the committed binary's on the same machine:

    python3 results/fig2a-map-certify/compare_maps.py results/fig2a-map results/fig2a-map-certify COMPARE.json

COMPARE.json is `results/map-profile/compare.py COMMITTED_BIN NEW_BIN` on a sample of the
committed map's runs (both binaries on this machine, one run after the other). The committed
binary's whole map on this machine is its recorded run time scaled by what the sample took
here against what the same runs took in the committed map. When COMPARE.json lists each run's
times (`runs`), the certified map is scaled the same way, by what the new binary took on the
sample's runs that the certified map stepped against what they took in it, so that both maps
are compared at the machine's speed during the sample (`drift_corrected`): a VM's speed drifts
by 10-30 % over an hour. Prints one JSON object.
"""
import hashlib
import json
import sys

import polars as pl

old_dir, new_dir, compare_path = sys.argv[1:4]
old_runs = pl.read_parquet(f"{old_dir}/runs.parquet")
new_runs = pl.read_parquet(f"{new_dir}/runs.parquet")
old_pts = pl.read_parquet(f"{old_dir}/points.parquet")
new_pts = pl.read_parquet(f"{new_dir}/points.parquet")
compare = json.load(open(compare_path))

# Points: the same points and labels.
keyp = ["eta_t", "kappa2"]
p = old_pts.select(keyp + ["class"]).join(
    new_pts.select(keyp + ["class"]), on=keyp, how="full", suffix="_new", coalesce=True)
label_diff = p.filter(pl.col("class").is_null() | pl.col("class_new").is_null()
                      | (pl.col("class") != pl.col("class_new")))

# Runs: by (point, initial condition).
keyr = ["eta_t", "kappa2", "ic"]
cols = keyr + ["class", "v", "s", "ended_by", "wall_s", "status"]
r = old_runs.select(cols).join(new_runs.select(cols), on=keyr, how="inner", suffix="_new")
r = r.with_columns(
    same_class=(pl.col("class") == pl.col("class_new")) & (pl.col("status") == pl.col("status_new")),
    dv=(pl.col("v") - pl.col("v_new")).abs(),
    ds=(pl.col("s") - pl.col("s_new")).abs(),
    certified=pl.col("ended_by_new") == "certified_midway",
)
r = r.with_columns(same_root=pl.col("same_class") & (pl.col("dv") <= 1e-6) & (pl.col("ds") <= 1e-6))


def group(d):
    return {
        "runs": d.height,
        "same_class": int(d["same_class"].sum()),
        "same_root": int(d["same_root"].sum()),
        "max_dv": float(d["dv"].max() or 0.0),
        "max_ds": float(d["ds"].max() or 0.0),
        "committed_run_time_s": round(float(d["wall_s"].sum()), 1),
        "run_time_s": round(float(d["wall_s_new"].sum()), 1),
    }


# The sample of compare.py (the smallest SHA-256 of seed, point and initial condition).
def rank(row):
    h = hashlib.sha256()
    h.update(int(compare["seed"]).to_bytes(8, "little"))
    h.update(int(row["point"]).to_bytes(4, "little"))
    h.update(row["ic"].encode())
    return h.digest()


sample = sorted(old_runs.select(["point", "ic", "wall_s"]).to_dicts(), key=rank)[: compare["sample"]]
sample_recorded = sum(x["wall_s"] for x in sample)
factor = compare["old_run_time_s"] / sample_recorded
committed_total = float(old_runs["wall_s"].sum())
committed_here = committed_total * factor
new_total = float(new_runs["wall_s"].sum())
drift_corrected = None
if "runs" in compare:
    timed = pl.DataFrame(compare["runs"], schema=["eta_t", "kappa2", "ic", "old_s", "new_s"],
                         orient="row")
    stepped = timed.join(new_runs.select(keyr + ["ended_by", "wall_s"]), on=keyr).filter(
        pl.col("ended_by") != "certified_midway")
    drift = float(stepped["new_s"].sum()) / float(stepped["wall_s"].sum())
    drift_corrected = {
        "sample_runs_stepped_in_certified_map": stepped.height,
        "their_time_here_s": round(float(stepped["new_s"].sum()), 2),
        "their_time_in_certified_map_s": round(float(stepped["wall_s"].sum()), 2),
        "certified_map_here_s": round(new_total * drift, 1),
        "ratio": round(new_total * drift / committed_here, 4),
    }
print(json.dumps({
    "committed": old_dir, "certified_map": new_dir,
    "points": {"committed": old_pts.height, "certified_map": new_pts.height,
               "label_differences": label_diff.height,
               "differ": label_diff.to_dicts()},
    "runs": {"committed": old_runs.height, "certified_map": new_runs.height,
             "certified": group(r.filter(pl.col("certified"))),
             "stepped": group(r.filter(~pl.col("certified"))),
             "stepped_differ": r.filter(~pl.col("certified") & ~pl.col("same_root"))
             .select(keyr + ["class", "class_new", "v", "v_new", "s", "s_new", "ended_by", "ended_by_new"])
             .to_dicts()},
    "run_time": {
        "committed_recorded_s": round(committed_total, 1),
        "sample_runs": compare["sample"], "sample_seed": compare["seed"],
        "sample_recorded_s": round(sample_recorded, 2),
        "sample_committed_binary_here_s": compare["old_run_time_s"],
        "sample_new_binary_here_s": compare["new_run_time_s"],
        "per_run_ratio": compare["ratio"],
        "machine_factor": round(factor, 4),
        "committed_here_s": round(committed_here, 1),
        "certified_map_s": round(new_total, 1),
        "ratio": round(new_total / committed_here, 4),
        "drift_corrected": drift_corrected,
    },
}, indent=1))
