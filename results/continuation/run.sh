#!/usr/bin/env bash
# Regenerates results/continuation/ and results/boundaries/ (and the boundaries on
# results/fig2a-map's phase map). Run from the repository root after `cargo build --release`.
set -euo pipefail
d=./target/release/droplet
out=results/continuation
# The PDE counterparts of Fig. 3b at kappa2 = 0.13 and eta_t = 0.085, and the lines of
# Fig. 2b (i)-(vi) (kappa2 = 0.13 is line iv).
for e in 0.082 0.085 0.09; do
  $d continue --eta-t $e --from 0.100 --to 0.170 --out $out --json > $out/continuation_eta_t_$e.json
done
for k in 0.16 0.13 0.117 0.1; do
  $d continue --kappa2 $k --from 0.070 --to 0.100 --out $out --json > $out/continuation_kappa2_$k.json
done
# The same at eta_t = 0.085 on the box diagonal (the orientation ID droplets settle on).
$d continue --eta-t 0.085 --from 0.100 --to 0.170 --axis diagonal --out $out --json > $out/continuation_eta_t_0.085_diagonal.json
$d boundaries --out results/boundaries --json > results/boundaries/boundaries.json
$d boundaries --out results/fig2a-map --json > results/fig2a-map/boundaries.json
