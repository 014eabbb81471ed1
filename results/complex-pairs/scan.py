"""The complex eigenvalue pairs of the steady states of the model with shape modes 2..K over
the points of a map: where a Hopf bifurcation (a periodic attractor's birth) could be.

    python3 results/complex-pairs/scan.py BINARY POINTS_PARQUET MODES > results/complex-pairs/scan.json

At every point of POINTS_PARQUET (eta_t, kappa2) and for each named state (IC; ID and MD on the
x axis and on the diagonal) that Newton finds there, `droplet stability --state S --axis A
--modes MODES --json` (N = 192): the state's eigenvalues with Re > -1 (the 2K x 2K problem
with the field). Writes every state's speed, verdict, largest real part and its complex pairs
(|Im| > 1e-8), one line per state, and a summary.
"""
import json
import subprocess
import sys

import polars as pl

binary, points, modes = sys.argv[1:4]
pts = pl.read_parquet(points).select(["eta_t", "kappa2"]).unique().sort(["eta_t", "kappa2"])
states = [("ic", "x"), ("id", "x"), ("id", "diagonal"), ("md", "x"), ("md", "diagonal")]
rows = []
for eta_t, kappa2 in pts.iter_rows():
    for state, axis in states:
        out = subprocess.run(
            [binary, "stability", "--eta-t", str(eta_t), "--kappa2", str(kappa2), "--state",
             state, "--axis", axis, "--modes", modes, "--json"],
            capture_output=True, text=True)
        if out.returncode != 0:
            continue
        d = json.loads(out.stdout)
        if state != "ic" and d["s"] < 1e-4:
            continue  # Newton fell onto the disk: no such state here
        if state == "md" and d["v"] < 1e-4:
            continue
        pairs = [e for e in d["eigenvalues"] if abs(e["im"]) > 1e-8]
        rows.append({
            "eta_t": eta_t, "kappa2": kappa2, "state": state, "axis": axis, "v": d["v"],
            "s": d["s"], "stable": d["stable"], "rotation": d["rotation"],
            "max_re": max(e["re"] for e in d["eigenvalues"]),
            "pairs": [[e["re"], e["im"]] for e in pairs if e["im"] > 0],
        })
        print(eta_t, kappa2, state, axis, len(pairs), file=sys.stderr, flush=True)
with_pairs = [r for r in rows if r["pairs"]]
stable_with_pairs = [r for r in with_pairs if r["stable"]]
top = max(with_pairs, key=lambda r: max(p[0] for p in r["pairs"]), default=None)
top_stable = max(stable_with_pairs, key=lambda r: max(p[0] for p in r["pairs"]), default=None)
summary = {
    "points": len(pts), "states": len(rows), "states_with_complex_pairs": len(with_pairs),
    "stable_states_with_complex_pairs": len(stable_with_pairs),
    "largest_re_of_a_pair": top and {**{k: top[k] for k in ("eta_t", "kappa2", "state", "axis", "stable")},
                                     "re": max(p[0] for p in top["pairs"])},
    "largest_re_of_a_pair_of_a_stable_state": top_stable and {
        **{k: top_stable[k] for k in ("eta_t", "kappa2", "state", "axis")},
        "re": max(p[0] for p in top_stable["pairs"])},
    "pairs_with_positive_re": sum(1 for r in with_pairs for p in r["pairs"] if p[0] > 0),
}
print(json.dumps({"binary_args": sys.argv[2:], "summary": summary, "states": rows}, indent=1))
