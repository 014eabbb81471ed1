"""The events of the six Fig. 2b lines with shape modes 2..4 (this folder) beside the same
lines with two modes (results/continuation), both at N = 192: writes events.md. Run from the
repository root: python3 results/fig2b-modes/summarise.py"""
import polars as pl

LINES = [("eta_t", "0.082", "kappa2"), ("eta_t", "0.09", "kappa2"), ("kappa2", "0.16", "eta_t"),
         ("kappa2", "0.13", "eta_t"), ("kappa2", "0.117", "eta_t"), ("kappa2", "0.1", "eta_t")]


def events(path, varied):
    e = pl.read_parquet(path)
    return [f"{r['branch']} {r['kind']} {r[varied]:.7f}" + (f" (v {r['v']:.3f})" if r["v"] > 0 else "")
            for r in e.iter_rows(named=True)]


def stable(path):
    d = pl.read_parquet(path)
    return ", ".join(f"{b} {g['stable'].sum()}/{g.height}"
                     for b, g in sorted(d.group_by("branch"), key=lambda x: x[0][0]) for b in [b[0]])


out = ["| line | K | stable states per branch | events (branch, kind, where) |", "|---|---|---|---|"]
for fixed, value, varied in LINES:
    for k, folder, stem in [(2, "results/continuation", f"continuation_{fixed}_{value}"),
                            (4, "results/fig2b-modes", f"continuation_modes4_{fixed}_{value}")]:
        ev = "; ".join(events(f"{folder}/{stem}_events.parquet", varied))
        out.append(f"| {fixed} = {value} | {k} | {stable(f'{folder}/{stem}.parquet')} | {ev} |")
open("results/fig2b-modes/events.md", "w").write("\n".join(out) + "\n")
print("\n".join(out))
