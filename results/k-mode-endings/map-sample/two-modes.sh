#!/bin/bash
# The 2-mode runs at the (point, initial condition) of the K = 4 map sample
# (map-sample/after/map_profile.parquet): the spec's settings are the defaults, so each run is
# `droplet simulate --eta-t X --kappa2 Y --ic IC --json`; two at a time, as `droplet bench
# --map` runs them. Writes map-sample/two-modes.json: the runs' summed and per-run wall time.
#   two-modes.sh BINARY
set -euo pipefail
bin=$1
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
python3 -c "
import polars as pl
for r in pl.read_parquet('$here/after/map_profile.parquet').iter_rows(named=True):
    print(r['x'], r['y'], r['ic'])
" | xargs -P2 -L1 bash -c "\"$bin\" simulate --eta-t \$0 --kappa2 \$1 --ic \$2 --json > $tmp/\$0_\$1_\$2.json"
python3 -c "
import json, glob
runs = sorted(glob.glob('$tmp/*.json'))
rows = [json.load(open(f)) for f in runs]
out = {'runs': len(rows), 'wall_s': sum(r['wall_s'] for r in rows),
       'classes': {c: sum(1 for r in rows if r['class'] == c) for c in ('IC', 'ID', 'MD', 'MC', None)}}
json.dump(out, open('$here/two-modes.json', 'w'), indent=1)
print(out)
"
rm -rf "$tmp"
