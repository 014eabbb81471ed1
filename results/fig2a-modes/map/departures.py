"""Reruns this map's runs from iii and iv that the landing ended after t = 300 (the runs that
the landing's reach for runs leaving the disk, numerics modes-14, may end sooner) with another
binary, two at a time, and compares their ends and steps.

    python3 results/fig2a-modes/map/departures.py BINARY OUT.jsonl

Each run is `BINARY simulate --eta-t E --kappa2 K --ic IC --modes 4 --json` (the map's
settings are the defaults). Writes one line per run: the point, the initial condition, the
record's class, v, s, t_end, steps, ended_by, wall_s, and the rerun's.
"""
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import polars as pl

binary, out_path = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
runs = pl.read_parquet(os.path.join(here, "runs.parquet"))
chosen = runs.filter(
    pl.col("ic").is_in(["iii", "iv"]),
    pl.col("ended_by") == "steady_by_landing",
    pl.col("t_end") > 300,
)
keys = ("class", "v", "s", "t_end", "steps", "ended_by", "wall_s")


def rerun(r):
    args = [binary, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
            "--ic", r["ic"], "--modes", "4", "--json"]
    j = json.loads(subprocess.run(args, capture_output=True, text=True, timeout=600).stdout)
    return {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"],
            "record": {k: r[k] for k in keys}, "rerun": {k: j.get(k) for k in keys}}


with ThreadPoolExecutor(2) as pool, open(out_path, "w") as out:
    for row in pool.map(rerun, chosen.iter_rows(named=True)):
        out.write(json.dumps(row) + "\n")
        out.flush()
