#!/usr/bin/env bash
# Landing (issue 24) checked against long, accurate time stepping on the same runs: each run
# with the defaults (the slow flow's landing on) and again with --no-landing --tol 1e-6
# (plain time stepping, 100x tighter steps, run on to 64 t_max = 128 000 at most; the Newton
# finish ends it once it is beside a stable root and approaching it). Same class, |dv|, |ds|.
# (Until numerics 6 the long runs were --tol 1e-5 --no-run-on --t-max 8000: at (0.09, 0.104)
# from i that tolerance alone ends on another MD orientation than 1e-4, 1e-6 and 1e-7 do.) The points: both sides of the onset of motion at kappa2 =
# 0.16 (the issue's run), the IC/MD band, the deformation onsets, the turning runs of the map.
# Run from the repository root after `cargo build --release`; writes results/landing/table.md.
set -euo pipefail
bin=${BIN:-./target/release/droplet}
here=results/landing
points=("0.0763 0.16" "0.0765 0.16" "0.07625 0.16" "0.078 0.13" "0.085 0.112" "0.0875 0.11875" "0.09 0.1186" "0.0805 0.118" "0.09 0.104" "0.092 0.102")
{
  echo "# Landing against long accurate time stepping"
  echo
  echo "\`bash results/landing/run.sh\`, commit $(git rev-parse --short HEAD), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs). N = 192."
  echo "Default: the defaults (\`steady: newton\`, landing on, tol 1e-4, t_max 2000)."
  echo "Long: \`--no-landing --tol 1e-6\` (plain time stepping, run on to t = 128 000 at most)."
  echo
  echo "| eta_t | kappa2 | ic | default: ended by | class | v | s | t_end | wall s | long: status | class | v | s | t_end | wall s | dv | ds |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > $here/table.md
for p in "${points[@]}"; do
  set -- $p
  for ic in i ii iii iv; do
    a=$($bin simulate --eta-t $1 --kappa2 $2 --ic $ic --json)
    b=$($bin simulate --eta-t $1 --kappa2 $2 --ic $ic --no-landing --tol 1e-6 --json)
    python3 - "$1" "$2" "$ic" "$a" "$b" >> $here/table.md <<'PY'
import json, sys
e, k, ic, a, b = sys.argv[1], sys.argv[2], sys.argv[3], json.loads(sys.argv[4]), json.loads(sys.argv[5])
f = lambda x: "-" if x is None else x
print(f"| {e} | {k} | {ic} | {f(a['ended_by'] or a['unsettled'])} | {f(a['class'])} | {a['v']:.6f} | {a['s']:.6f} | {a['t_end']:.0f} | {a['wall_s']:.2f} "
      f"| {b['status']} | {f(b['class'])} | {b['v']:.6f} | {b['s']:.6f} | {b['t_end']:.0f} | {b['wall_s']:.1f} | {abs(a['v']-b['v']):.1e} | {abs(a['s']-b['s']):.1e} |")
PY
  done
done
