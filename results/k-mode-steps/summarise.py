"""The runs of compare.sh as one JSON object: per run its binary, K, IC, status, ending, class,
v, s, heading of the velocity (degrees), a_3, t_end, steps and wall time (s)."""
import json, math, os, sys

out = sys.argv[1]
rows = []
for name in sorted(os.listdir(out)):
    if not name.endswith(".json"):
        continue
    tag, k, ic = name[:-5].rsplit("-", 2)
    j = json.load(open(os.path.join(out, name)))
    wall = float(open(os.path.join(out, name[:-5] + ".time")).read().split()[-1])
    rows.append({
        "binary": tag, "modes": int(k), "ic": ic, "status": j["status"],
        "ended_by": j["ended_by"], "class": j["class"], "v": j["v"], "s": j["s"],
        "heading_deg": math.degrees(math.atan2(j["vy"], j["vx"])),
        "a3": j["a_k"][1], "t_end": j["t_end"], "steps": j["steps"], "wall_s": wall,
    })
json.dump({"runs": rows}, sys.stdout, indent=1)
