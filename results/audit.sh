#!/usr/bin/env bash
# The full audit of every committed map of the PDE model: `droplet audit DIR --json` on each
# folder of results/ (one or two levels deep) with a runs.parquet, written to DIR/audit.json,
# with its wall time. The reduced model's maps (audit refuses them, exit 2) are skipped. The
# test suite audits a seeded sample of each map's points (tests/suite/attractors.rs) and checks that
# this record says 0 contradictions; rerun this after recomputing a map. Run from the
# repository root after `cargo build --release`.
set -uo pipefail
bin=./target/release/droplet
for runs in results/*/runs.parquet results/*/*/runs.parquet; do
  dir=$(dirname "$runs")
  start=$(date +%s%N)
  $bin audit "$dir" --json > "$dir/audit.json.tmp"
  code=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  if [ "$code" -eq 2 ]; then
    rm -f "$dir/audit.json.tmp"
    echo "$dir: not a PDE map, skipped"
    continue
  fi
  mv "$dir/audit.json.tmp" "$dir/audit.json"
  echo "$dir: exit $code in $ms ms: $(grep -o '"contradictions": *[0-9]*' "$dir/audit.json" | head -1), $(grep -o '"points": *[0-9]*' "$dir/audit.json" | head -1)"
done
