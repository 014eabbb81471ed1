"""Run time of numerics 7 and of the defaults on the same machine, on runs drawn from the map.

The map's run time (the sum of its runs' `wall_s`) is measured on whatever machine ran it; the
issue's budget was measured on another. This draws SAMPLE runs at random (seed SEED) from an
older map of numerics 7 (OLD_COMMIT's results/fig2a-map/runs.parquet, with that machine's
`wall_s`), and runs each here twice, two at a time as the sweep does: with
`--no-orientation-flow` (numerics 7) and with the defaults. It prints, as one JSON object:
  * `machine_factor`: this machine's numerics-7 time over the old machine's, same runs;
  * `defaults_over_n7`: the defaults' time over numerics 7's, both here;
  * `same_end`: how many runs end on the same state (v and s within 1e-6) both ways.

    python3 results/fig2a-map/same_machine.py OLD_COMMIT   # from the repository root,
                                                           # after cargo build --release
SAMPLE (default 60), SEED (default 3), BIN (default ./target/release/droplet).
"""
import io
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import polars as pl

BIN = os.environ.get("BIN", "./target/release/droplet")
SAMPLE = int(os.environ.get("SAMPLE", "60"))
SEED = int(os.environ.get("SEED", "3"))
old = pl.read_parquet(io.BytesIO(subprocess.check_output(
    ["git", "show", f"{sys.argv[1]}:results/fig2a-map/runs.parquet"])))
runs = old.sample(n=SAMPLE, seed=SEED).to_dicts()


def simulate(r, extra):
    out = subprocess.check_output(
        [BIN, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
         "--ic", r["ic"], "--json"] + extra)
    return json.loads(out)


with ThreadPoolExecutor(2) as pool:
    n7 = list(pool.map(lambda r: simulate(r, ["--no-orientation-flow"]), runs))
    now = list(pool.map(lambda r: simulate(r, []), runs))

old_s = sum(r["wall_s"] for r in runs)
n7_s = sum(x["wall_s"] for x in n7)
now_s = sum(x["wall_s"] for x in now)
same = sum(abs(a["v"] - b["v"]) < 1e-6 and abs(a["s"] - b["s"]) < 1e-6 for a, b in zip(n7, now))
print(json.dumps({
    "runs": SAMPLE, "seed": SEED, "old_machine_n7_s": old_s, "n7_s": n7_s, "defaults_s": now_s,
    "machine_factor": n7_s / old_s, "defaults_over_n7": now_s / n7_s, "same_end": same,
}))
