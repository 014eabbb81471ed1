"""The runs of this map whose end changed from the previous commit's map, each checked against
plain time stepping (`droplet simulate ... --no-landing`, the defaults otherwise: tol 1e-4,
the Newton finish, run on to 64 t_max). Where the new end disagrees with plain stepping, both
are checked against pure time stepping (`--no-landing --steady test --steady-tol 1e-300
--t-max 10000`: no Newton finish, no test that can fire; its class from the final v and s).
Writes results/fig2a-map/changed_runs.md.

    python3 results/fig2a-map/check_changed.py OLD_COMMIT   # from the repository root, after
                                                            # cargo build --release (one run at a time)
BIN=path/to/droplet runs another binary (default ./target/release/droplet).
"""
import subprocess, sys, json, io, os
import polars as pl

BIN = os.environ.get("BIN", "./target/release/droplet")
old_commit = sys.argv[1]
old = pl.read_parquet(io.BytesIO(subprocess.check_output(
    ["git", "show", f"{old_commit}:results/fig2a-map/runs.parquet"])))
new = pl.read_parquet("results/fig2a-map/runs.parquet")
k = ["eta_t", "kappa2", "ic"]
j = old.join(new, on=k, suffix="_new")
d = j.with_columns(pl.max_horizontal((pl.col("v") - pl.col("v_new")).abs(),
                                     (pl.col("s") - pl.col("s_new")).abs()).alias("d"))
changed = d.filter((pl.col("d") >= 1e-4) | ~pl.col("class").eq_missing(pl.col("class_new"))).sort(k)


def simulate(r, extra):
    out = subprocess.check_output([BIN, "simulate", "--eta-t", repr(r["eta_t"]), "--kappa2", repr(r["kappa2"]),
                                   "--ic", r["ic"], "--no-landing", "--json"] + extra)
    return json.loads(out)


def class_of(v, s):
    return {(False, False): "IC", (False, True): "ID", (True, True): "MD", (True, False): "MC"}[(v > 0.01, s > 0.01)]


agrees = lambda c, v, s, p: c == p["class"] and max(abs(v - p["v"]), abs(s - p["s"])) < 1e-4
f = lambda c: c or "-"
lines, pure_lines, n_new, n_old, unsettled = [], [], 0, 0, 0
n_pure_new = n_pure_plain = 0
for r in changed.iter_rows(named=True):
    p = simulate(r, [])
    a_new = agrees(r["class_new"], r["v_new"], r["s_new"], p)
    a_old = agrees(r["class"], r["v"], r["s"], p)
    n_new += a_new; n_old += a_old; unsettled += p["class"] is None
    lines.append(f"| {r['eta_t']:.5g} | {r['kappa2']:.5g} | {r['ic']} | {f(r['class'])} | {r['v']:.6f} | {r['s']:.6f} | {r['ended_by']} "
                 f"| {f(r['class_new'])} | {r['v_new']:.6f} | {r['s_new']:.6f} | {r['ended_by_new']} "
                 f"| {f(p['class'])} | {p['v']:.6f} | {p['s']:.6f} | {p['t_end']:.0f} | {'yes' if a_old else 'no'} | {'yes' if a_new else 'no'} |")
    if not a_new:
        q = simulate(r, ["--steady", "test", "--steady-tol", "1e-300", "--t-max", "10000", "--no-run-on"])
        q["class"] = class_of(q["v"], q["s"])
        pn, pp = agrees(r["class_new"], r["v_new"], r["s_new"], q), agrees(p["class"], p["v"], p["s"], q)
        n_pure_new += pn; n_pure_plain += pp
        pure_lines.append(f"| {r['eta_t']:.5g} | {r['kappa2']:.5g} | {r['ic']} | {f(r['class_new'])} | {r['v_new']:.6f} | {r['s_new']:.6f} "
                          f"| {f(p['class'])} | {p['v']:.6f} | {p['s']:.6f} | {q['class']} | {q['v']:.6f} | {q['s']:.6f} "
                          f"| {'yes' if pn else 'no'} | {'yes' if pp else 'no'} |")
with open("results/fig2a-map/changed_runs.md", "w") as out:
    out.write(f"# Runs whose end changed from {old_commit}'s map, against plain time stepping\n\n")
    out.write("`python3 results/fig2a-map/check_changed.py " + old_commit + "` (this folder's script). "
              "Changed: class differs, or `v` or `s` by 1e-4 or more. Plain: `droplet simulate ... --no-landing` "
              "(tol 1e-4, Newton finish, run on to t = 128 000). Agrees: same class, `v` and `s` within 1e-4.\n\n")
    out.write(f"**{len(lines)} runs changed; the new end agrees with plain stepping in {n_new}, the old one in {n_old}; "
              f"plain stepping did not settle {unsettled}.**\n\n")
    out.write("| eta_t | kappa2 | ic | old class | v | s | ended by | new class | v | s | ended by | plain class | v | s | t_end | old agrees | new agrees |\n")
    out.write("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    out.write("\n".join(lines) + "\n")
    if pure_lines:
        out.write(f"\n## Where the new end and plain stepping disagree: pure time stepping\n\n"
                  "`droplet simulate ... --no-landing --steady test --steady-tol 1e-300 --t-max 10000 --no-run-on`: "
                  "no Newton finish, stepped to t = 10 000; its class from its final `v` and `s`.\n\n"
                  f"**{len(pure_lines)} runs; pure stepping agrees with the new end in {n_pure_new}, with plain stepping in {n_pure_plain}.**\n\n")
        out.write("| eta_t | kappa2 | ic | new class | v | s | plain class | v | s | pure class | v | s | new agrees | plain agrees |\n")
        out.write("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
        out.write("\n".join(pure_lines) + "\n")
print(len(lines), n_new, n_old, unsettled, len(pure_lines), n_pure_new, n_pure_plain)
