"""Reruns a sample of a committed map's runs at another grid size N.

    python3 results/orientation-n/rerun.py BINARY MAP_DIR MODES SAMPLE SEED N [N ...]
    SELECT=off-mirror python3 results/orientation-n/rerun.py ...
    NAME=k4map python3 results/orientation-n/rerun.py ...   # files named k4map-n{N}.json

Draws SAMPLE runs of MAP_DIR/runs.parquet at random (SEED): two thirds of them from the
moving runs (MD, MC), the rest from the others; with SELECT=off-mirror, from the moving runs
whose direction is more than 0.1 degree off the box's mirror lines (the axes and diagonals),
all of them if SAMPLE is larger. It reruns each (point, initial condition)
with `droplet simulate --modes MODES --n N --json` (the map's settings are the defaults) at
every N given, one run at a time. Writes results/orientation-n/runs/{NAME}-n{N}.json
({NAME}-off-n{N}.json with SELECT=off-mirror; NAME defaults to k{MODES}): per
run the point, the initial condition, the committed end (class, v, s, vx, vy) and the rerun's
(status, class, v, s, vx, vy, ended_by, t_end, wall_s).
"""
import json
import math
import os
import subprocess
import sys

import polars as pl

binary, map_dir, modes, sample, seed = sys.argv[1:6]
ns = [int(n) for n in sys.argv[6:]]
runs = pl.read_parquet(os.path.join(map_dir, "runs.parquet"))
moving = runs.filter(pl.col("class").is_in(["MD", "MC"]))
other = runs.filter(~pl.col("class").is_in(["MD", "MC"]))
k = int(sample)
select = os.environ.get("SELECT", "")


def off_mirror(vx, vy):
    a = abs(math.degrees(math.atan2(vy, vx))) % 90.0
    return 0.1 < min(a, 90.0 - a) < 44.9


if select == "off-mirror":
    off = moving.filter(
        pl.Series([off_mirror(a, b) for a, b in zip(moving["vx"], moving["vy"])])
    )
    picked = off.sample(n=min(len(off), k), seed=int(seed)).sort(["eta_t", "kappa2", "ic"])
else:
    picked = pl.concat(
        [
            moving.sample(n=min(len(moving), 2 * k // 3), seed=int(seed)),
            other.sample(n=min(len(other), k - 2 * k // 3), seed=int(seed)),
        ]
    ).sort(["eta_t", "kappa2", "ic"])
here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "runs"), exist_ok=True)
for n in ns:
    rows = []
    for r in picked.iter_rows(named=True):
        args = [binary, "simulate", "--eta-t", str(r["eta_t"]), "--kappa2", str(r["kappa2"]),
                "--ic", r["ic"], "--modes", modes, "--n", str(n), "--json"]
        out = subprocess.run(args, capture_output=True, text=True)
        row = {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"],
               "map": {key: r[key] for key in ("class", "v", "s", "vx", "vy", "n")}}
        if out.returncode == 0:
            d = json.loads(out.stdout)
            row["rerun"] = {key: d[key] for key in
                            ("status", "class", "v", "s", "vx", "vy", "ended_by", "t_end",
                             "wall_s")}
        else:
            row["rerun"] = {"error": out.stderr.strip()}
        rows.append(row)
        print(n, r["eta_t"], r["kappa2"], r["ic"], row["rerun"].get("class"), flush=True)
    tag = "-off" if select == "off-mirror" else ""
    name = os.environ.get("NAME", f"k{modes}")
    path = os.path.join(here, "runs", f"{name}{tag}-n{n}.json")
    with open(path + ".tmp", "w") as f:
        json.dump({"binary_args": sys.argv[2:], "runs": rows}, f, indent=1)
    os.replace(path + ".tmp", path)
