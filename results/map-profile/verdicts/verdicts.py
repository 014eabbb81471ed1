"""The eigenvalues of a fixed set of steady states (`droplet stability --json`, N = 192) with
each of two binaries: K = 2, 3, 4, 6; MD on the x axis and on the diagonal, ID and the disk
where Newton finds them, at seven points of the Fig. 2a window. Writes one JSON line per state
and binary to OUT.jsonl and prints how far the eigenvalues moved (matched as multisets, state
by state) and each binary's time for the set:

    python3 verdicts.py OLD_BIN NEW_BIN OUT.jsonl
"""
import json
import subprocess
import sys
import time

POINTS = [(0.085, 0.112), (0.078, 0.13), (0.09, 0.11), (0.0765, 0.16), (0.1, 0.1), (0.08, 0.12), (0.085, 0.118)]
STATES = [("md", "x"), ("md", "diagonal"), ("id", "x"), ("ic", "x")]


def run(binary, k, eta_t, kappa2, state, axis):
    args = [binary, "stability", "--eta-t", str(eta_t), "--kappa2", str(kappa2), "--state", state,
            "--axis", axis, "--modes", str(k), "--json"]
    start = time.perf_counter()
    done = subprocess.run(args, capture_output=True, text=True)
    wall = time.perf_counter() - start
    ev = None
    if done.returncode == 0:
        ev = [[e["re"], e["im"]] for e in json.loads(done.stdout)["eigenvalues"]]
    return {"bin": binary, "modes": k, "eta_t": eta_t, "kappa2": kappa2, "state": state, "axis": axis,
            "rc": done.returncode, "wall_s": wall, "eigenvalues": ev}


def main():
    old_bin, new_bin, out = sys.argv[1:4]
    rows = [run(b, k, e, c, s, a) for b in (old_bin, new_bin) for k in (2, 3, 4, 6)
            for (e, c) in POINTS for (s, a) in STATES]
    with open(out, "w") as f:
        for r in rows:
            f.write(json.dumps(r) + "\n")
    key = lambda r: (r["modes"], r["eta_t"], r["kappa2"], r["state"], r["axis"])
    old = {key(r): r for r in rows if r["bin"] == old_bin}
    new = {key(r): r for r in rows if r["bin"] == new_bin}
    worst, compared, mismatched, neither = 0.0, 0, [], 0
    for k, a in old.items():
        ea, eb = a["eigenvalues"], new[k]["eigenvalues"]
        if ea is None and eb is None:
            neither += 1
            continue
        if ea is None or eb is None or len(ea) != len(eb):
            mismatched.append(list(k))
            continue
        compared += 1
        rest = [complex(*e) for e in eb]
        for x in (complex(*e) for e in ea):
            j = min(range(len(rest)), key=lambda i: abs(rest[i] - x))
            worst = max(worst, abs(rest[j] - x))
            rest.pop(j)
    print(json.dumps({
        "states_compared": compared,
        "not_found_by_either": neither,
        "mismatched": mismatched,
        "max_eigenvalue_change": worst,
        "wall_s": {"old": round(sum(r["wall_s"] for r in old.values()), 2),
                   "new": round(sum(r["wall_s"] for r in new.values()), 2)},
    }, indent=1))


main()
