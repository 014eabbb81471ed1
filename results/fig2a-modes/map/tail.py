"""Reruns this map's long moving and deformed runs (class not IC, t_end > 5000 in the record)
with another binary, two at a time, and compares their ends and steps.

    python3 results/fig2a-modes/map/tail.py BINARY OUT.jsonl [MAP_DIR [MODES]]

MAP_DIR defaults to this map (modes 4); `results/fig2a-map 2` reruns the 2-mode map's. Each
run is `BINARY simulate --eta-t E --kappa2 K --ic IC --modes M --json` (the maps' settings
are the defaults), at most 300 s. Writes one line per run: the point, the initial condition,
the record's class, v, s, t_end, steps, wall_s, and the rerun's.
"""
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import polars as pl

binary, out_path = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
map_dir = sys.argv[3] if len(sys.argv) > 3 else here
modes = sys.argv[4] if len(sys.argv) > 4 else "4"
runs = pl.read_parquet(os.path.join(map_dir, "runs.parquet"))
tail = runs.filter((pl.col("t_end") > 5000) & (pl.col("class") != "IC"))
keys = ("class", "v", "s", "t_end", "steps", "ended_by", "wall_s")


def rerun(r):
    args = [binary, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
            "--ic", r["ic"], "--modes", modes, "--json"]
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=300)
        j = json.loads(p.stdout)
        new = {k: j.get(k) for k in keys}
    except subprocess.TimeoutExpired:
        new = {"status": "timeout"}
    return {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"],
            "record": {k: r[k] for k in keys}, "rerun": new}


with ThreadPoolExecutor(2) as pool, open(out_path, "w") as out:
    for row in pool.map(rerun, tail.iter_rows(named=True)):
        out.write(json.dumps(row) + "\n")
        out.flush()
