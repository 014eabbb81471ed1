#!/usr/bin/env bash
# The refined Fig. 2(a) map with runs stopped beside an unstable steady state left out of the
# point classes (sweeps/fig2a-adaptive-strict.yaml; README, "The refined Fig. 2(a) map"). Its
# runs are those of sweeps/fig2a-adaptive.yaml (results/fig2a-adaptive/run.sh): this copies them
# (hard links) and sweeps, which plans the same points and computes nothing. Without them the
# sweep computes every run (about 3.2 h on 2 cores). Run from the repository root after
# `cargo build --release`. The committed tables were made by the binary of commit c2fe2a83
# (PDE numerics version 1): a later binary (version 2 or later) recomputes them.
set -euo pipefail
from=${1:-out/fig2a-adaptive}
out=out/fig2a-adaptive-strict
here=results/fig2a-adaptive-strict
bin=./target/release/droplet
if [ -d "$from/runs" ]; then
  mkdir -p "$out/runs"
  cp -aln "$from/runs/." "$out/runs/"
fi
$bin sweep sweeps/fig2a-adaptive-strict.yaml --out "$out" --json > $here/summary.json
$bin status "$out" --json > $here/status.json
for f in points.parquet runs.parquet phase_map.png phase_map.svg; do cp "$out/$f" $here/; done
