#!/usr/bin/env bash
# The Fig. 2(a) map at a finest step of 2.5e-4 with the defaults (issue 24): sweeps/fig2a-map.yaml
# at N = 192 on all cores, timed from start to finish, then its tables, picture, summary and
# per-level status copied here. Run from the repository root after `cargo build --release`,
# with nothing else running (elapsed.txt is the wall time the budget is about).
set -euo pipefail
out=${1:-out/fig2a-map}
here=results/fig2a-map
bin=./target/release/droplet
start=$(date +%s)
$bin sweep sweeps/fig2a-map.yaml --out "$out" --json > $here/summary.json
end=$(date +%s)
{
  echo "# droplet sweep sweeps/fig2a-map.yaml, $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), commit $(git rev-parse --short HEAD)"
  echo "start $(date -u -d @$start '+%F %T') UTC, end $(date -u -d @$end '+%F %T') UTC"
  echo "wall_s $(( end - start ))"
} > $here/elapsed.txt
$bin status "$out" --json > $here/status.json
for f in points.parquet runs.parquet phase_map.png phase_map.svg; do cp "$out/$f" $here/; done
# The exact boundaries drawn onto the map (boundaries.parquet, redrawn picture), the audit of
# every label, and the per-level summary (crates/sweep/examples/map_summary.rs).
$bin boundaries --out "$out" --json > /dev/null
for f in phase_map.png phase_map.svg boundaries.parquet; do cp "$out/$f" $here/; done
$bin audit $here --json > $here/audit.json || true
cargo run --release -q -p droplet-sweep --example map_summary -- $here > $here/summary.md
