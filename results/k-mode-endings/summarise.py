"""Compares the runs of runs/*.json: each Newton-finished set against pure time stepping at the
same K and N (modes16 to modes7 against pure-*.json, stepped by the scheme of numerics modes-7, and
modes16 also against pure16-*.json, the scheme of modes-16, where those exist; the older
sets against pure6-*.json, the scheme of modes-3 to modes-6) (class; |dv|, |ds|; the orientation's difference in degrees; t_end and wall time).
Writes summary.json and prints a table.  python3 summarise.py"""
import json, glob, os

here = os.path.dirname(os.path.abspath(__file__))
def load(name):
    return json.load(open(os.path.join(here, "runs", name + ".json")))

def turn(a, b):
    return (a - b + 180.0) % 360.0 - 180.0

summary = {}
for path in sorted(glob.glob(os.path.join(here, "runs", "pure-*.json"))):
    kn = os.path.basename(path)[len("pure-"):-len(".json")]
    for tag, ref in [("modes16", "pure"), ("modes16", "pure16")] + [
        (t, "pure") for t in ["modes15", "modes14", "modes13", "modes12", "modes11", "modes10", "modes8", "modes7"]
    ] + [(t, "pure6") for t in ["modes6", "newton", "before"]]:
        p = os.path.join(here, "runs", f"{tag}-{kn}.json")
        if not os.path.exists(p) or not os.path.exists(os.path.join(here, "runs", f"{ref}-{kn}.json")):
            continue
        pure = load(f"{ref}-{kn}")
        runs = load(f"{tag}-{kn}")
        if ref == "pure16":
            tag = "modes16/pure16"
        rows = []
        for a, b in zip(pure, runs):
            assert (a["eta_t"], a["kappa2"], a["ic"]) == (b["eta_t"], b["kappa2"], b["ic"])
            moving = a["v"] > 1e-4
            rows.append({
                "eta_t": a["eta_t"], "kappa2": a["kappa2"], "ic": a["ic"],
                "pure_class": a["class"], "class": b["class"], "ended_by": b["ended_by"],
                "pure_v": a["v"], "dv": b["v"] - a["v"], "ds": b["s"] - a["s"],
                "pure_orientation_deg": a["orientation_deg"],
                "d_orientation_deg": turn(b["orientation_deg"], a["orientation_deg"]) if moving else None,
                "pure_t_end": a["t_end"], "t_end": b["t_end"], "pure_wall_s": a["wall_s"], "wall_s": b["wall_s"],
            })
        same = [r["class"] == r["pure_class"] and abs(r["dv"]) < 1e-4 and abs(r["ds"]) < 1e-4
                and (r["d_orientation_deg"] is None or abs(r["d_orientation_deg"]) < 0.1) for r in rows]
        summary[f"{tag}-{kn}"] = {
            "runs": len(rows), "same_end": sum(same),
            "max_abs_dv": max(abs(r["dv"]) for r in rows), "max_abs_ds": max(abs(r["ds"]) for r in rows),
            "max_abs_d_orientation_deg": max(abs(r["d_orientation_deg"] or 0.0) for r in rows),
            "wall_s": sum(r["wall_s"] for r in rows), "pure_wall_s": sum(r["pure_wall_s"] for r in rows),
            "rows": rows,
        }
        print(f"{tag}-{kn}: {sum(same)}/{len(rows)} end where pure stepping ends; "
              f"wall {summary[f'{tag}-{kn}']['wall_s']:.1f} s (pure {summary[f'{tag}-{kn}']['pure_wall_s']:.1f} s)")
        for r, ok in zip(rows, same):
            o = "-" if r["d_orientation_deg"] is None else f"{r['d_orientation_deg']:+.4f}"
            print(f"  ({r['eta_t']}, {r['kappa2']}) {r['ic']:3s} {r['pure_class']}->{r['class']} {r['ended_by'] or '-':17s}"
                  f" v*={r['pure_v']:.6f} dv={r['dv']:+.1e} ds={r['ds']:+.1e} phi*={r['pure_orientation_deg']:8.3f} dphi={o:>8s}"
                  f" t={r['t_end']:8.1f} (pure {r['pure_t_end']:8.1f}) {'' if ok else 'DIFFERENT'}")
json.dump(summary, open(os.path.join(here, "summary.json"), "w"), indent=1)
