"""Compares the reruns of results/orientation-n/runs at N and 1.5 N (the off-mirror sample of
K = 2 also at 2 N), and the reruns at N = 192 with the map; the samples of the refined 4-mode
map (k4map, k4map-off) where their files exist.

    python3 results/orientation-n/summarise.py > results/orientation-n/summary.json

A moving state's orientation is the direction of its velocity folded by the box's symmetry
(the square's eight) into [0, 45] degrees: 0 on an axis, 45 on a diagonal.
"""
import json
import math
import os

here = os.path.dirname(os.path.abspath(__file__))


def folded(vx, vy):
    a = abs(math.degrees(math.atan2(vy, vx))) % 90.0
    return min(a, 90.0 - a)


def load(tag, n):
    with open(os.path.join(here, "runs", f"{tag}-n{n}.json")) as f:
        return json.load(f)["runs"]


def compare(tag, k, n0, n1):
    a, b = load(tag, n0), load(tag, n1)
    rows = []
    for ra, rb in zip(a, b):
        assert (ra["eta_t"], ra["kappa2"], ra["ic"]) == (rb["eta_t"], rb["kappa2"], rb["ic"])
        x, y = ra["rerun"], rb["rerun"]
        row = {"eta_t": ra["eta_t"], "kappa2": ra["kappa2"], "ic": ra["ic"],
               "class": [x.get("class"), y.get("class")],
               "v": [x.get("v"), y.get("v")], "s": [x.get("s"), y.get("s")],
               "ended_by": [x.get("ended_by"), y.get("ended_by")],
               "map_same_as_n0": x.get("class") == ra["map"]["class"]
               and abs(x["v"] - ra["map"]["v"]) < 1e-6 and abs(x["s"] - ra["map"]["s"]) < 1e-6}
        if x.get("class") in ("MD", "MC") and y.get("class") in ("MD", "MC"):
            row["orientation"] = [folded(x["vx"], x["vy"]), folded(y["vx"], y["vy"])]
        rows.append(row)
    moving = [r for r in rows if "orientation" in r]
    same_class = sum(r["class"][0] == r["class"][1] for r in rows)
    dv = [abs(r["v"][0] - r["v"][1]) for r in rows if r["class"][0] == r["class"][1]]
    ds = [abs(r["s"][0] - r["s"][1]) for r in rows if r["class"][0] == r["class"][1]]
    dori = [abs(r["orientation"][0] - r["orientation"][1]) for r in moving]
    on_mirror = lambda o: o < 0.1 or o > 44.9
    return {
        "modes": k, "n": [n0, n1], "runs": len(rows), "same_class": same_class,
        "rerun_at_n0_equals_map": sum(r["map_same_as_n0"] for r in rows),
        "moving_both": len(moving),
        "moving_off_mirror_lines": [sum(not on_mirror(r["orientation"][i]) for r in moving)
                                    for i in (0, 1)],
        "orientation_changed_over_0.1_deg": sum(d > 0.1 for d in dori),
        "largest_dv": max(dv), "largest_ds": max(ds),
        "largest_dv_moving": max([abs(r["v"][0] - r["v"][1]) for r in moving], default=0.0),
        "median_dv_moving": sorted(abs(r["v"][0] - r["v"][1]) for r in moving)[len(moving) // 2]
        if moving else 0.0,
        "rows": rows,
    }


out = {"k2": compare("k2", 2, 192, 288), "k4": compare("k4", 4, 192, 288)}
# The refined 4-mode map (results/fig2a-modes/map), random and off the mirror lines.
for tag, k, ns in (("k2-off", 2, (192, 288, 384)), ("k4-off", 4, (192, 288)),
                   ("k4map", 4, (192, 288)), ("k4map-off", 4, (192, 288))):
    for n0, n1 in zip(ns, ns[1:]):
        if os.path.exists(os.path.join(here, "runs", f"{tag}-n{n1}.json")):
            out[f"{tag}-{n0}-{n1}"] = compare(tag, k, n0, n1)
print(json.dumps(out, indent=1))
for key in out:
    s = {k: v for k, v in out[key].items() if k != "rows"}
    print(key, s, file=__import__("sys").stderr)
