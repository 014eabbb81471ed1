"""What a map's slow runs do: a seeded sample of its stepped runs with 800 < t_end < 10000,
each run again by `droplet simulate` with its series (every 25 time units), printed under the
map's class, ending and t_end as ten
samples of (t, v, s, direction of motion, long axis), the angles in degrees.
  python3 slow_runs.py BIN MAP_DIR [N] [SEED]"""
import math, subprocess, sys, tempfile, os
import polars as pl

binary, path = sys.argv[1], sys.argv[2]
n = int(sys.argv[3]) if len(sys.argv) > 3 else 12
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 5
runs = pl.read_parquet(f"{path}/runs.parquet").filter(
    (pl.col("t_end") > 800) & (pl.col("t_end") < 10000) & (pl.col("steps") > 0)).sample(n, seed=seed)
with tempfile.TemporaryDirectory() as tmp:
    series = os.path.join(tmp, "s.parquet")
    for r in runs.rows(named=True):
        subprocess.run([binary, "simulate", "--eta-t", str(r["eta_t"]), "--kappa2", str(r["kappa2"]),
                        "--ic", r["ic"], "--series", series, "--every", "25"], check=True,
                       stdout=subprocess.DEVNULL)
        rows = pl.read_parquet(series).rows(named=True)
        print(f"({r['eta_t']}, {r['kappa2']}) from {r['ic']}: {r['class']}, {r['ended_by']} at t = {r['t_end']:.0f}")
        for q in rows[::max(1, len(rows) // 10)]:
            motion = math.degrees(math.atan2(q["vy"], q["vx"]))
            axis = 0.5 * math.degrees(math.atan2(q["b2"], q["a2"]))
            print(f"  t {q['t']:7.0f}  v {q['v']:.2e}  s {q['s']:.2e}  motion {motion:6.1f}  long axis {axis:6.1f}")
