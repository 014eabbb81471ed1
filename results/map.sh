#!/usr/bin/env bash
# One committed map from its spec: `bash results/map.sh SPEC HERE [OUT]` sweeps SPEC into OUT
# (default: the spec's own output) on all cores, timed from start to finish (elapsed.txt; a
# resumed sweep times its last leg only, summary.json's run_time_s counts every run), then
# draws the exact boundaries onto it and copies into HERE its tables, picture, summary,
# per-level status and boundaries, with the audit of every label (audit.json) and the
# per-level summary (summary.md, crates/sweep/examples/map_summary.rs). Run from the
# repository root after `cargo build --release`, with nothing else running:
#   bash results/map.sh sweeps/fig2a-map.yaml results/fig2a-map
#   bash results/map.sh sweeps/fig2a-modes.yaml results/fig2a-modes/map
set -euo pipefail
spec=${1:?usage: results/map.sh SPEC HERE [OUT]}
here=${2:?usage: results/map.sh SPEC HERE [OUT]}
bin=${BIN:-./target/release/droplet}
out=${3:-$(sed -n 's/^output: *//p' "$spec")}
[ -n "$out" ] || { echo "$spec has no output: give OUT" >&2; exit 2; }
mkdir -p "$here"
start=$(date +%s)
$bin sweep "$spec" --out "$out" --json > "$here/summary.json"
end=$(date +%s)
{
  echo "# droplet sweep $spec, $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), commit $(git rev-parse --short HEAD)"
  echo "start $(date -u -d @$start '+%F %T') UTC, end $(date -u -d @$end '+%F %T') UTC"
  echo "wall_s $(( end - start ))"
} > "$here/elapsed.txt"
$bin status "$out" --json > "$here/status.json"
$bin boundaries --out "$out" --json > "$here/boundaries.json"
for f in points.parquet runs.parquet phase_map.png phase_map.svg boundaries.parquet; do
  cp "$out/$f" "$here/"
done
$bin audit "$here" --json > "$here/audit.json" || true
cargo run --release -q -p droplet-sweep --example map_summary -- "$here" > "$here/summary.md"
