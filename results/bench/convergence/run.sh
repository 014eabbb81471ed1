#!/usr/bin/env bash
# Issue 14's benchmark: Fig. 2a before (the paper's steady test with the step of commit
# e90a0a9b, the state before the step-cost and stability-speed work) and after (the Newton
# finish, the default, with this commit's binary), one after the other on the same machine
# from empty directories; then the comparison table, and the step cost of both commits.
# Run from the repository root. BEFORE is a binary built from e90a0a9b:
#   git worktree add /tmp/before e90a0a9b && (cd /tmp/before && cargo build --release)
# (with CARGO_TARGET_DIR set to a copy of target/ only the workspace crates are rebuilt).
set -euo pipefail
before=${BEFORE:-/tmp/before/target/release/droplet}
after=./target/release/droplet
out=${1:-/tmp/fig2a-convergence}
here=results/bench/convergence
rm -rf "$out"; mkdir -p "$out"
for m in before after; do
  if [ $m = before ]; then bin=$before; spec=sweeps/fig2a-test.yaml; else bin=$after; spec=sweeps/fig2a.yaml; fi
  start=$(date +%s.%N)
  $bin sweep $spec --out "$out/$m" --json > "$out/$m.json"
  end=$(date +%s.%N)
  echo "$m $(echo "$end - $start" | bc)" >> "$out/elapsed.txt"
done
cargo run --release -q -p droplet-sweep --example map_compare -- "$out/before" "$out/after" "$out/elapsed.txt" > $here/fig2a.md
for m in before after; do
  cp "$out/$m/runs.parquet" $here/${m}_runs.parquet
  cp "$out/$m/points.parquet" $here/${m}_points.parquet
done
