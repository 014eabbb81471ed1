"""Points along a map's exact boundaries, for scan.py.

    python3 results/complex-pairs/boundary_points.py BOUNDARIES_PARQUET PER_CURVE OUT_PARQUET
    python3 results/complex-pairs/boundary_points.py ... OUT_PARQUET CURVE ETA_SHIFT

Takes every curve of the field model (model "pde") in BOUNDARIES_PARQUET (model, curve, eta_t,
kappa2; the reduced ODE model's curves are left out) that lies in the Fig. 2a window (eta_t 0.068-0.100, kappa2 0.100-0.172) and PER_CURVE points evenly spaced along it
(by arc length; a curve given by its two ends is a straight line), and writes them
(curve, eta_t, kappa2) to OUT_PARQUET, rounded to 1e-6. With CURVE and ETA_SHIFT: only the
curves whose name contains CURVE, every point moved by ETA_SHIFT in eta_t (off a fold, into
the region where its states exist).
"""
import math
import sys

import polars as pl

src, per_curve, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
only, shift = (sys.argv[4], float(sys.argv[5])) if len(sys.argv) > 5 else ("", 0.0)
d = pl.read_parquet(src).filter(pl.col("model") == "pde")
d = d.filter(pl.col("curve").str.contains(only, literal=True))
rows = []
for (curve,), part in d.group_by(["curve"], maintain_order=True):
    pts = [(e, k) for e, k in zip(part["eta_t"], part["kappa2"])
           if 0.068 <= e <= 0.100 and 0.100 <= k <= 0.172]
    if len(pts) < 2:
        continue
    # Scale the axes to the window so that arc length weighs both alike.
    sc = lambda p: ((p[0] - 0.068) / 0.032, (p[1] - 0.100) / 0.072)
    arc = [0.0]
    for a, b in zip(pts, pts[1:]):
        (xa, ya), (xb, yb) = sc(a), sc(b)
        arc.append(arc[-1] + math.hypot(xb - xa, yb - ya))
    total = arc[-1]
    if total == 0.0:
        continue
    j = 0
    for i in range(per_curve):
        s = total * (i + 0.5) / per_curve
        while arc[j + 1] < s:
            j += 1
        f = (s - arc[j]) / (arc[j + 1] - arc[j]) if arc[j + 1] > arc[j] else 0.0
        e = pts[j][0] + f * (pts[j + 1][0] - pts[j][0])
        k = pts[j][1] + f * (pts[j + 1][1] - pts[j][1])
        rows.append({"curve": curve, "eta_t": round(e + shift, 6), "kappa2": round(k, 6)})
pl.DataFrame(rows).write_parquet(out)
print(len(rows), "points on", len({r["curve"] for r in rows}), "curves")
