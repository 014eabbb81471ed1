#!/bin/bash
# Where K-mode runs end: the Newton finish (the defaults) against pure time stepping (the
# paper's test alone, steady_tol 1e-9, t_max 20000), at three points of the Fig. 2a window,
# every initial condition.
#   endings.sh BINARY TAG K N [pure]
#   RUNS="0.076,0.14175,ii 0.0765,0.16425,i" endings.sh ...   # these runs instead
#   T_MAX=100000 endings.sh ... pure                           # pure stepping further
# writes runs/TAG-kK-nN.json: one object per run (point, ic, status, class, ended_by, v, s,
# orientation in degrees, t_end, steps, wall_s). With `pure` the runs are pure time stepping.
set -euo pipefail
bin=$1 tag=$2 k=$3 n=$4 mode=${5:-newton}
runs=${RUNS:-}
if [ -z "$runs" ]; then
  for pt in 0.085,0.112 0.078,0.13 0.088,0.1095; do
    for ic in i ii iii iv; do runs="$runs $pt,$ic"; done
  done
fi
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$here/runs"
extra=()
[ "$mode" = pure ] && extra=(--steady test --steady-tol 1e-9 --t-max "${T_MAX:-20000}")
out="$here/runs/$tag-k$k-n$n.json"
echo "[" > "$out.tmp"
first=1
for run in $runs; do
  IFS=, read -r eta kappa ic <<< "$run"
  set -- "$eta" "$kappa"
  {
    json=$("$bin" simulate --eta-t "$1" --kappa2 "$2" --ic "$ic" --n "$n" --modes "$k" "${extra[@]}" --json)
    line=$(python3 -c '
import json, math, sys
d = json.loads(sys.argv[1])
moving = d["v"] > 1e-9
ak, bk = d.get("a_k") or [0.0], d.get("b_k") or [0.0]
ang = math.degrees(math.atan2(d["vy"], d["vx"])) if moving else 0.5 * math.degrees(math.atan2(bk[0], ak[0]))
print(json.dumps({"eta_t": float(sys.argv[2]), "kappa2": float(sys.argv[3]), "ic": sys.argv[4],
  "status": d["status"], "class": d["class"], "ended_by": d["ended_by"], "v": d["v"], "s": d["s"],
  "orientation_deg": ang, "t_end": d["t_end"], "steps": d["steps"], "wall_s": d["wall_s"]}))
' "$json" "$1" "$2" "$ic")
    [ $first = 1 ] || echo "," >> "$out.tmp"
    echo "$line" >> "$out.tmp"
    first=0
  }
done
echo "]" >> "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
