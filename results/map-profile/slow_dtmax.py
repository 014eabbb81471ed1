"""A map's slow runs again with another step cap: a seeded sample of its stepped runs with
t_end > 500, each run by `droplet simulate ... --dt-max DT_MAX --json`, two at a time, and
compared with the map's run (the same class, v and s within 1e-6). One JSON line per run.
  python3 slow_dtmax.py BIN MAP_DIR DT_MAX [N] [SEED] > out.jsonl"""
import json, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
import polars as pl

binary, path, dt_max = sys.argv[1], sys.argv[2], sys.argv[3]
n = int(sys.argv[4]) if len(sys.argv) > 4 else 80
seed = int(sys.argv[5]) if len(sys.argv) > 5 else 7
runs = pl.read_parquet(f"{path}/runs.parquet").filter(
    (pl.col("t_end") > 500) & (pl.col("steps") > 0)).sample(n, seed=seed).rows(named=True)

def one(r):
    out = subprocess.run([binary, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
                          "--ic", r["ic"], "--dt-max", dt_max, "--json"],
                         check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    same = d["class"] == r["class"] and abs(d["v"] - r["v"]) < 1e-6 and abs(d["s"] - r["s"]) < 1e-6
    return {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"], "dt_max": float(dt_max),
            "map_class": r["class"], "class": d["class"], "dv": d["v"] - r["v"], "ds": d["s"] - r["s"],
            "map_t_end": r["t_end"], "t_end": d["t_end"], "steps": d["steps"], "wall_s": d["wall_s"],
            "ended_by": d["ended_by"], "same": same}

with ThreadPoolExecutor(2) as pool:
    for row in pool.map(one, runs):
        print(json.dumps(row), flush=True)
