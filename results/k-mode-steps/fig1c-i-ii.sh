#!/bin/bash
# The Fig. 1c runs from i and ii, K = 2 and 4, two binaries alternating, REPS repetitions:
#   fig1c-i-ii.sh BIN_A BIN_B REPS > OUT.jsonl
for r in $(seq 1 $3); do for bin in $1 $2; do for ic in i ii; do for k in 2 4; do
  $bin simulate --eta-t 0.085 --kappa2 0.112 --ic $ic --modes $k --json | python3 -c '
import json,sys
d=json.load(sys.stdin); print(json.dumps({"bin":sys.argv[1],"k":int(sys.argv[2]),"ic":sys.argv[3],"t_end":d["t_end"],"steps":d["steps"],"wall_s":d["wall_s"]}))' $(basename $bin) $k $ic
done; done; done; done
