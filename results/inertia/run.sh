#!/usr/bin/env bash
# The inertia m decides the basins near boundaries, not the steady states: IC i against iii
# inside the paper's IC/MD band (0.078, 0.13), and IC i at the paper's ID point of Fig. 1
# (0.085, 0.116), for m = 0.001, 0.01, 0.1, 0.3, 1 (N = 192, default settings). Writes table.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${DROPLET:-target/release/droplet}
out=results/inertia/table.md
{
  echo "| (eta_t, kappa2) | IC | m | status | class | v | s | t_end | wall s |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for m in 0.001 0.01 0.1 0.3 1; do
    for case in "0.078 0.13 i" "0.078 0.13 iii" "0.085 0.116 i"; do
      set -- $case
      json=$("$bin" simulate --eta-t "$1" --kappa2 "$2" --ic "$3" --mass "$m" --json)
      echo "$json" | python3 -c "
import json, sys
d = json.load(sys.stdin)
print(f\"| ($1, $2) | $3 | $m | {d['status']} | {d['class']} | {d['v']:.6f} | {d['s']:.6f} | {d['t_end']:.0f} | {d['wall_s']:.1f} |\")"
    done
  done
} > "$out"
cat "$out"
