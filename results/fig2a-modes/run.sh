#!/usr/bin/env bash
# The Fig. 2(a) window with shape modes 2..4 refined to a finest step of 2.4e-4 with the
# defaults (issue 46): sweeps/fig2a-modes.yaml at N = 192 on all cores, timed from start to
# finish (a resumed sweep: the last leg only; summary.json's run_time_s counts every run), then
# its tables, picture, per-level status, exact boundaries, audit and per-level summary copied
# into results/fig2a-modes/map. Run from the repository root after `cargo build --release`,
# with nothing else running.
set -euo pipefail
out=${1:-out/fig2a-modes}
here=results/fig2a-modes/map
bin=./target/release/droplet
mkdir -p $here
start=$(date +%s)
$bin sweep sweeps/fig2a-modes.yaml --out "$out" --json > $here/summary.json
end=$(date +%s)
{
  echo "# droplet sweep sweeps/fig2a-modes.yaml, $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), commit $(git rev-parse --short HEAD)"
  echo "start $(date -u -d @$start '+%F %T') UTC, end $(date -u -d @$end '+%F %T') UTC"
  echo "wall_s $(( end - start ))"
} > $here/elapsed.txt
$bin status "$out" --json > $here/status.json
$bin boundaries --out "$out" --json > $here/boundaries.json
for f in points.parquet runs.parquet phase_map.png phase_map.svg boundaries.parquet; do cp "$out/$f" $here/; done
$bin audit $here --json > $here/audit.json || true
cargo run --release -q -p droplet-sweep --example map_summary -- $here > $here/summary.md
