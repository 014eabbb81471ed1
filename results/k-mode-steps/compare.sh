#!/bin/bash
# K-mode runs at the Fig. 1c point (eta_t = 0.085, kappa2 = 0.112), default N = 192, K = 3 and 4,
# from each of the paper's four initial conditions, with two binaries one after the other:
#   OLD: exponential Euler at the fixed step dt = 0.02 (numerics modes-2)
#   NEW: ETD2RK on the run's clock, adaptive steps (numerics modes-3)
# Usage: compare.sh OLD_BINARY NEW_BINARY OUT_DIR; then summarise.py OUT_DIR > runs.json
set -euo pipefail
old=$1 new=$2 out=$3
mkdir -p "$out"
for k in 3 4; do for ic in i ii iii iv; do for b in old new; do
  bin=$old; [ "$b" = new ] && bin=$new
  /usr/bin/time -f "%e" -o "$out/$b-$k-$ic.time" \
    "$bin" simulate --eta-t 0.085 --kappa2 0.112 --ic "$ic" --modes "$k" --json > "$out/$b-$k-$ic.json"
done; done; done
# The new binary at tighter step tolerances, where K = 3 runs ended on different roots.
for ic in i iv; do for tol in 1e-5 1e-6; do
  /usr/bin/time -f "%e" -o "$out/tol$tol-3-$ic.time" \
    "$new" simulate --eta-t 0.085 --kappa2 0.112 --ic "$ic" --modes 3 --tol "$tol" --json > "$out/tol$tol-3-$ic.json"
done; done
