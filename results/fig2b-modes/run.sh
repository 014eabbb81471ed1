#!/usr/bin/env bash
# The six lines of Fig. 2b (sweeps/fig2b-*.yaml) as continuation branches of the model with
# shape modes 2..4 at N = 192: every family on the x axis, the stability of every state, its
# P / SN / H / R events. Run from the repository root after `cargo build --release`; then
# `python3 results/fig2b-modes/summarise.py` writes events.md (against results/continuation,
# the same lines with two modes).
set -uo pipefail
d=${DROPLET:-./target/release/droplet}
out=results/fig2b-modes
for e in 0.082 0.090; do
  $d continue --modes 4 --n 192 --eta-t $e --from 0.100 --to 0.170 --out $out --json > $out/continue_etat$e.json
done
for k in 0.160 0.130 0.117 0.100; do
  $d continue --modes 4 --n 192 --kappa2 $k --from 0.070 --to 0.100 --out $out --json > $out/continue_kappa2$k.json
done
