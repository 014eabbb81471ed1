"""The labels of the paper's 2-mode map that change with shape modes 2..4, point by point.

Usage (from the repository root): python3 results/fig2a-modes/map/changes.py > results/fig2a-modes/map/label_changes.csv
Joins results/fig2a-map/points.parquet and results/fig2a-modes/map/points.parquet on
(eta_t, kappa2) and writes one CSV row per point whose label differs, with the boundary whose
move explains that kind of change (README.md, "What changes and why", gives the boundaries'
positions at both K from results/fig2a-modes/boundaries.parquet and results/truncation).
"""
import sys

import polars as pl

WHY = {
    ("IC/MD", "IC"): "the MD fold moves left: no moving state here",
    ("ID", "MD"): "ID's onset of motion moves right (mode 4): the resting deformed droplet moves",
    ("ID/MD", "MD"): "ID's onset of motion moves right (mode 4): the resting deformed droplet moves",
    ("ID/MD", "ID"): "the MD fold near ID moves left: no moving state here",
    ("IC/MD", "IC/MC"): "a slow, nearly round moving state (s below the MC threshold) at the disk's onset of motion (eta_t ~ 0.0765)",
    ("MD", "MC"): "a slow, nearly round moving state (s below the MC threshold) at the disk's onset of motion (eta_t ~ 0.0765)",
}

key = ["eta_t", "kappa2"]
two = pl.read_parquet("results/fig2a-map/points.parquet").select(key + ["class"])
four = pl.read_parquet("results/fig2a-modes/map/points.parquet").select(key + ["class"])
both = two.join(four, on=key, suffix="_4").sort(key)
changed = both.filter(pl.col("class") != pl.col("class_4"))
unexplained = {(a, b) for a, b in changed.select(["class", "class_4"]).iter_rows()} - set(WHY)
if unexplained:
    sys.exit(f"changes without a reason: {sorted(unexplained)}")
out = changed.with_columns(
    pl.struct(["class", "class_4"])
    .map_elements(lambda r: WHY[(r["class"], r["class_4"])], return_dtype=pl.String)
    .alias("why")
).rename({"class": "two_modes", "class_4": "modes_2_4"})
sys.stdout.write(out.write_csv())
print(f"# {changed.height} of {both.height} common points change", file=sys.stderr)
