"""Run time of two droplet binaries on the same runs of a committed map, measured together.

Draws the runs that `droplet bench --map MAP --sample SAMPLE --seed SEED` draws (the smallest
SHA-256 of seed, point and initial condition), and runs each with both binaries through
`droplet simulate --eta-t E --kappa2 K --ic IC --json` (the map's settings are simulate's
defaults), two processes at a time in the order (run 1, A), (run 1, B), (run 2, A), ... so
that both binaries see the same machine at the same moments. Prints one JSON object: each
binary's summed run time (the runs' own `wall_s`), their ratio B/A, how many runs end on the
same state both ways (the same class, v and s within 1e-6), the runs that do not, and each
run's two times (`runs`: eta_t, kappa2, ic, A's wall_s, B's wall_s).

    python3 results/map-profile/compare.py OLD_BIN NEW_BIN   # from the repository root
MAP (default results/fig2a-map), SAMPLE (default 200), SEED (default 1), JOBS (default 2).
"""
import hashlib
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import polars as pl

MAP = os.environ.get("MAP", "results/fig2a-map")
SAMPLE = int(os.environ.get("SAMPLE", "200"))
SEED = int(os.environ.get("SEED", "1"))
JOBS = int(os.environ.get("JOBS", "2"))
old_bin, new_bin = sys.argv[1], sys.argv[2]

runs = pl.read_parquet(f"{MAP}/runs.parquet").select(["point", "eta_t", "kappa2", "ic"])


def rank(r):
    h = hashlib.sha256()
    h.update(SEED.to_bytes(8, "little"))
    h.update(int(r["point"]).to_bytes(4, "little"))
    h.update(r["ic"].encode())
    return h.digest()


sample = sorted(runs.to_dicts(), key=rank)[:SAMPLE]


def simulate(task):
    r, binary = task
    out = subprocess.check_output(
        [binary, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
         "--ic", r["ic"], "--json"])
    return json.loads(out)


tasks = [(r, b) for r in sample for b in (old_bin, new_bin)]
started = time.time()
with ThreadPoolExecutor(JOBS) as pool:
    done = list(pool.map(simulate, tasks))
old, new = done[0::2], done[1::2]
same = [
    a["class"] == b["class"] and abs(a["v"] - b["v"]) <= 1e-6 and abs(a["s"] - b["s"]) <= 1e-6
    for a, b in zip(old, new)
]
t_old = sum(a["wall_s"] for a in old)
t_new = sum(b["wall_s"] for b in new)
print(json.dumps({
    "map": MAP, "sample": SAMPLE, "seed": SEED, "jobs": JOBS,
    "old": old_bin, "new": new_bin,
    "old_run_time_s": round(t_old, 2), "new_run_time_s": round(t_new, 2),
    "ratio": round(t_new / t_old, 4),
    "same_end": sum(same),
    "max_dv": max(abs(a["v"] - b["v"]) for a, b in zip(old, new)),
    "max_ds": max(abs(a["s"] - b["s"]) for a, b in zip(old, new)),
    "differ": [
        {"eta_t": r["eta_t"], "kappa2": r["kappa2"], "ic": r["ic"],
         "old": [a["class"], a["v"], a["s"]], "new": [b["class"], b["v"], b["s"]]}
        for r, a, b, s in zip(sample, old, new, same) if not s
    ],
    "runs": [[r["eta_t"], r["kappa2"], r["ic"], a["wall_s"], b["wall_s"]]
             for r, a, b in zip(sample, old, new)],
    "machine": subprocess.check_output(
        ["sh", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"]).decode().strip(),
    "wall_s": round(time.time() - started, 1),
}, indent=1))
