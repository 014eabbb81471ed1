#!/usr/bin/env bash
# The refined Fig. 2(a) map (issue 15): sweeps/fig2a-adaptive.yaml at N = 192 on all cores,
# then its tables, picture, summary and per-level status copied here. Run from the repository
# root after `cargo build --release`. (levels-0-4/: the same runs swept with levels: 4, see
# levels-0-4/spec.yaml: `droplet sweep levels-0-4/spec.yaml` in a copy of OUT's runs/.) The sweep resumes if OUT already holds some of its runs
# (this map's sweep was interrupted once and resumed: README, "Adaptive refinement").
set -euo pipefail
out=${1:-out/fig2a-adaptive}
here=results/fig2a-adaptive
bin=./target/release/droplet
start=$(date +%s)
$bin sweep sweeps/fig2a-adaptive.yaml --out "$out" --json > $here/summary.json
echo "wall_s $(( $(date +%s) - start ))" > $here/elapsed.txt
$bin status "$out" --json > $here/status.json
for f in points.parquet runs.parquet phase_map.png phase_map.svg; do cp "$out/$f" $here/; done
