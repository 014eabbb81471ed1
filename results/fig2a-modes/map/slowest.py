"""Reruns the slowest runs of this map with another binary, one at a time, and compares ends.

    python3 results/fig2a-modes/map/slowest.py BINARY START COUNT OUT.jsonl

Takes the runs of runs.parquet in order of their wall time, slowest first, from START on, and
runs each with `BINARY simulate --modes 4 --json` (the map's settings are the defaults; at most
150 s each, else `timeout`). Appends one line per run to OUT.jsonl: the point, the initial
condition, the committed end (class, v, s, vx, vy, ended_by, t_end, wall_s) and the rerun's.
"""
import json
import os
import subprocess
import sys

import polars as pl

binary, start, count, out_path = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
here = os.path.dirname(os.path.abspath(__file__))
runs = pl.read_parquet(os.path.join(here, "runs.parquet")).sort("wall_s", descending=True)
keys = ("class", "v", "s", "vx", "vy", "ended_by", "t_end", "wall_s")
with open(out_path, "a") as out:
    for r in runs.slice(start, count).iter_rows(named=True):
        args = [binary, "simulate", "--eta-t", str(r["eta_t"]), "--kappa2", str(r["kappa2"]),
                "--ic", r["ic"], "--modes", "4", "--json"]
        try:
            p = subprocess.run(args, capture_output=True, text=True, timeout=150)
            j = json.loads(p.stdout)
            new = {k: j[k] for k in ("status",) + keys}
        except subprocess.TimeoutExpired:
            new = {"status": "timeout"}
        row = {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"],
               "map": {k: r[k] for k in keys}, "rerun": new}
        out.write(json.dumps(row) + "\n")
        out.flush()
