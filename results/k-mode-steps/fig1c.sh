#!/bin/bash
# K = 2 and K = 4 runs at Fig. 1c from each IC, with two binaries, one after the other.
for bin in "$@"; do
  for k in 2 4; do
    for ic in i ii iii iv; do
      $bin simulate --eta-t 0.085 --kappa2 0.112 --ic $ic --modes $k --json | python3 -c '
import json,sys,math
d=json.load(sys.stdin)
print(json.dumps({"bin":sys.argv[1],"k":int(sys.argv[2]),"ic":sys.argv[3],"class":d["class"],"ended_by":d["ended_by"],"v":d["v"],"s":d["s"],"heading_deg":math.degrees(math.atan2(d["vy"],d["vx"])),"t_end":d["t_end"],"steps":d["steps"],"wall_s":d["wall_s"],"stepping_s":d["profile"]["stepping_s"]}))' $(basename $bin) $k $ic
    done
  done
done
