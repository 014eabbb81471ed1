#!/usr/bin/env python3
"""The numbers of the README's "refined Fig. 2(a) map" section, from this folder's tables.

    python3 results/fig2a-adaptive/analyse.py [FOLDER]     (needs pandas and pyarrow)

FOLDER defaults to this one; results/fig2a-adaptive-fast is the other map it reads.

Prints the per-level cost table, where the run time goes, where each point class lies, the
class edges along kappa2 = 0.13 and eta_t = 0.085, the MC runs by how they ended, and how the
point classes would change if runs stopped beside an unstable steady state were left
out of them (the same points, without re-planning the levels).
"""
import sys
from pathlib import Path

import pandas as pd

folder = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent)
points = pd.read_parquet(folder / "points.parquet")
runs = pd.read_parquet(folder / "runs.parquet").merge(points[["point", "level"]], on="point")
diagnosis = runs.diagnosis.fillna("")
# Unfinished runs: t_max, step_limit, and those stopped beside a saddle they could not leave
# (status saddle, solver.stop_beside_saddle).
tmax = runs.status.isin(["t_max", "step_limit", "saddle"])
saddle = runs.status == "saddle"
creep = tmax & diagnosis.str.startswith("near an unstable")
turn = tmax & diagnosis.str.endswith("v and s are settled")
total = runs.wall_s.sum()

print(f"{len(points)} points, {len(runs)} runs, {total:.0f} s of run time")
print("\nlevel  points  runs  run_s  s_per_run  t_max  t_max_s  creep_s  (t_max: all unfinished runs)")
for level, r in runs.groupby("level"):
    t, c = tmax[r.index], creep[r.index]
    print(
        f"{level:5d} {r.point.nunique():7d} {len(r):5d} {r.wall_s.sum():6.0f} "
        f"{r.wall_s.mean():10.2f} {t.sum():6d} {r.wall_s[t].sum():8.0f} {r.wall_s[c].sum():8.0f}"
    )

slow = (runs.status == "steady") & (runs.t_end > 800)
print(f"\nt_max runs: {tmax.sum()} ({tmax.mean():.0%}), {runs.wall_s[tmax].sum() / total:.0%} of run time")
print(f"beside an unstable steady state: {creep.sum()} runs, {runs.wall_s[creep].sum():.0f} s")
if saddle.any():
    print(f"  of which stopped early (status saddle): {saddle.sum()} runs, {runs.wall_s[saddle].sum():.0f} s,"
          f" median t_end {runs.t_end[saddle].median():.0f}, classes {runs['class'][saddle].value_counts().to_dict()}")
growth = diagnosis[creep].str.extract(r"largest ([-+]\d\.\d+e[-+]\d+)")[0].astype(float)
print(f"  growth rates: median {growth.median():.1e}, 5-95 % {growth.quantile(0.05):.1e} .. {growth.quantile(0.95):.1e}")
print(f"only turning (v and s settled): {turn.sum()} runs, {runs.wall_s[turn].sum():.0f} s,",
      runs["class"][turn].value_counts().to_dict())
print(f"steady after t > 800: {slow.sum()} runs, {runs.wall_s[slow].sum():.0f} s,",
      runs["class"][slow].value_counts().to_dict())
if "t_leapt" in runs:
    leapt = runs.t_leapt > 0
    print(f"leapt along a departure (solver.leap_departures): {leapt.sum()} runs, {runs.wall_s[leapt].sum():.0f} s,"
          f" {runs.t_leapt.sum():.0f} time units leapt (median {runs.t_leapt[leapt].median():.0f} a run),"
          f" eta_t {runs.eta_t[leapt].min():.7g}-{runs.eta_t[leapt].max():.7g},"
          f" ICs {runs.ic[leapt].value_counts().to_dict()}")

print("\npoint classes: count, eta_t range, kappa2 range")
for name, q in points.groupby("class"):
    print(f"  {name}: {len(q)}, {q.eta_t.min():.7g}-{q.eta_t.max():.7g}, {q.kappa2.min():.7g}-{q.kappa2.max():.7g}")

for axis, value, along in (("kappa2", 0.13, "eta_t"), ("eta_t", 0.085, "kappa2")):
    line = points[(points[axis] - value).abs() < 1e-9].sort_values(along)
    pairs = zip(line.itertuples(), line.iloc[1:].itertuples())
    print(f"\nclass edges along {axis} = {value}:")
    for a, b in pairs:
        if a[7] != b[7]:
            print(f"  {a[7]} -> {b[7]} between {along} {getattr(a, along):.7f} and {getattr(b, along):.7f}")

mc = runs["class"] == "MC"
kinds = {
    "steady": runs.status == "steady",
    "beside an unstable state": creep,
    "converging slowly": diagnosis.str.startswith("slowest eigenvalue"),
}
print(f"\nMC runs: {mc.sum()}")
for name, k in kinds.items():
    sel = mc & k
    print(f"  {name}: {sel.sum()} (median v {runs.v[sel].median():.3g}, s {runs.s[sel].median():.2g})")

ORDER = {"IC": 0, "ID": 1, "MD": 2, "MC": 3}


def label(classes):
    classes = sorted(set(classes), key=ORDER.get)
    if not classes:
        return "no settled run"
    return classes[0] if len(classes) == 1 else "/".join(classes) if len(classes) == 2 else "not classified"


kept = runs[~creep & runs["class"].notna()]
relabel = points.point.map(kept.groupby("point")["class"].apply(list).apply(label)).fillna("no settled run")
changed = points["class"] != relabel
print(f"\nwithout the runs beside an unstable state: {changed.sum()} of {len(points)} points change")
print(pd.DataFrame({"from": points["class"][changed], "to": relabel[changed]}).value_counts().to_string())
