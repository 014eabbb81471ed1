#!/usr/bin/env bash
# Fig. 2a with the Newton finish (the default) and with the paper's test alone, one after the
# other on the same machine, from empty directories; then the comparison table.
# Run from the repository root after `cargo build --release`.
set -euo pipefail
d=./target/release/droplet
out=${1:-/tmp/fig2a-bench}
rm -rf "$out"; mkdir -p "$out"
for m in newton test; do
  spec=sweeps/fig2a.yaml; [ $m = test ] && spec=sweeps/fig2a-test.yaml
  start=$(date +%s.%N)
  $d sweep $spec --out "$out/$m" --json > "$out/$m.json"
  end=$(date +%s.%N)
  echo "$m $(echo "$end - $start" | bc)" >> "$out/elapsed.txt"
done
cargo run --release -q -p droplet-sweep --example map_compare -- "$out/test" "$out/newton" "$out/elapsed.txt" > results/bench/newton_finish/fig2a.md
