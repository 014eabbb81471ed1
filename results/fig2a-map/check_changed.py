"""The runs of this map whose end changed from an earlier commit's map, each checked against
pure time stepping: `droplet simulate ... --no-landing --steady test --steady-tol 1e-300
--t-max 10000 --no-run-on` (no Newton finish, no landing, no test that can fire: the run is
stepped to t = 10 000 and its class taken from its final v and s). Since numerics 8 the
Newton finish itself asks the orientation's flow, so plain stepping with the Newton finish
(the check of numerics 7) is no longer independent of what it checks.
Writes results/fig2a-map/changed_runs.md.

    python3 results/fig2a-map/check_changed.py OLD_COMMIT   # from the repository root, after
                                                            # cargo build --release
BIN=path/to/droplet runs another binary (default ./target/release/droplet); JOBS=k runs k at a
time (default 2); NEW=path reads the new runs from another table (default this folder's);
pure runs already done are kept in /tmp/check_changed_pure.jsonl and not run again.
"""
import subprocess, sys, json, io, os, math
from concurrent.futures import ThreadPoolExecutor
import polars as pl

BIN = os.environ.get("BIN", "./target/release/droplet")
JOBS = int(os.environ.get("JOBS", "2"))
CACHE = "/tmp/check_changed_pure.jsonl"
old_commit = sys.argv[1]
old = pl.read_parquet(io.BytesIO(subprocess.check_output(
    ["git", "show", f"{old_commit}:results/fig2a-map/runs.parquet"])))
new = pl.read_parquet(os.environ.get("NEW", "results/fig2a-map/runs.parquet"))
k = ["eta_t", "kappa2", "ic"]
j = old.join(new, on=k, suffix="_new")
d = j.with_columns(pl.max_horizontal((pl.col("v") - pl.col("v_new")).abs(),
                                     (pl.col("s") - pl.col("s_new")).abs()).alias("d"))
changed = d.filter((pl.col("d") >= 1e-4) | ~pl.col("class").eq_missing(pl.col("class_new"))).sort(k)


def class_of(v, s):
    return {(False, False): "IC", (False, True): "ID", (True, True): "MD", (True, False): "MC"}[(v > 0.01, s > 0.01)]


def key(r):
    return f"{r['eta_t']!r} {r['kappa2']!r} {r['ic']}"


done = {}
if os.path.exists(CACHE):
    for line in open(CACHE):
        x = json.loads(line)
        done[x["key"]] = x


def pure(r):
    if key(r) in done:
        return done[key(r)]
    out = subprocess.check_output([BIN, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
                                   "--ic", r["ic"], "--no-landing", "--steady", "test", "--steady-tol", "1e-300",
                                   "--t-max", "10000", "--no-run-on", "--json"])
    p = json.loads(out)
    x = {"key": key(r), "v": p["v"], "s": p["s"], "vx": p["vx"], "vy": p["vy"], "a2": p["a2"], "b2": p["b2"],
         "wall_s": p["wall_s"], "unsettled": p.get("unsettled"), "heading": p.get("heading")}
    with open(CACHE, "a") as c:
        c.write(json.dumps(x) + "\n")
    return x


rows = list(changed.iter_rows(named=True))
with ThreadPoolExecutor(JOBS) as ex:
    results = list(ex.map(pure, rows))

agrees = lambda c, v, s, p: c == class_of(p["v"], p["s"]) and max(abs(v - p["v"]), abs(s - p["s"])) < 1e-4
f = lambda c: c or "-"


def pure_end(p):
    """What Newton from the pure run's state at t = 10 000 finds (`simulate`'s diagnosis of a run
    given up): beside an unstable root (still leaving it, or turning on it), or converging on a
    stable one; `?` for runs cached before this column existed."""
    if "unsettled" not in p:
        return "?"
    u = p["unsettled"] or "-"
    return f"{u} ({p['heading']})" if p.get("heading") else u


def angle(p):
    if p["v"] > 1e-9:
        return math.degrees(math.atan2(p["vy"], p["vx"]))
    return math.degrees(0.5 * math.atan2(p["b2"], p["a2"]))


lines, n_new, n_old, close_new = [], 0, 0, 0
for r, p in zip(rows, results):
    a_new = agrees(r["class_new"], r["v_new"], r["s_new"], p)
    a_old = agrees(r["class"], r["v"], r["s"], p)
    dn = max(abs(r["v_new"] - p["v"]), abs(r["s_new"] - p["s"]))
    do = max(abs(r["v"] - p["v"]), abs(r["s"] - p["s"]))
    n_new += a_new; n_old += a_old; close_new += dn < do
    lines.append(f"| {r['eta_t']:.5g} | {r['kappa2']:.5g} | {r['ic']} | {f(r['class'])} | {r['v']:.6f} | {r['s']:.6f} | {r['ended_by']} "
                 f"| {f(r['class_new'])} | {r['v_new']:.6f} | {r['s_new']:.6f} | {r['ended_by_new']} "
                 f"| {class_of(p['v'], p['s'])} | {p['v']:.6f} | {p['s']:.6f} | {angle(p):.2f} | {do:.1e} | {dn:.1e} "
                 f"| {pure_end(p)} | {'yes' if a_old else 'no'} | {'yes' if a_new else 'no'} |")
with open("results/fig2a-map/changed_runs.md", "w") as out:
    out.write(f"# Runs whose end changed from {old_commit}'s map, against pure time stepping\n\n")
    out.write("`python3 results/fig2a-map/check_changed.py " + old_commit + "` (this folder's script). "
              "Changed: class differs, or `v` or `s` by 1e-4 or more. Pure: `droplet simulate ... --no-landing "
              "--steady test --steady-tol 1e-300 --t-max 10000 --no-run-on` (no Newton finish: stepped to "
              "t = 10 000, class from the final `v` and `s`; angle: its direction of motion, or long axis at "
              "rest, in degrees; pure end: what Newton from its state at t = 10 000 finds, `beside_saddle` "
              "when that root is unstable, i.e. the run is still leaving or turning on it and its class is "
              "not yet its end's). Agrees: same class, `v` and `s` within 1e-4 of the pure run's at "
              "t = 10 000 (a run still turning there agrees with neither).\n\n")
    out.write(f"**{len(lines)} runs changed; the new end agrees with pure stepping in {n_new}, the old one in {n_old}; "
              f"the new end is the closer in {close_new}.**\n\n")
    out.write("| eta_t | kappa2 | ic | old class | v | s | ended by | new class | v | s | ended by "
              "| pure class | v | s | angle | old off by | new off by | pure end | old agrees | new agrees |\n")
    out.write("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    out.write("\n".join(lines) + "\n")
print(len(lines), n_new, n_old, close_new)
