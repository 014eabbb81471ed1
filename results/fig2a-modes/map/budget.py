"""The 4-mode map's run time against the 2-mode map's, from a map's long runs rerun whole
(`tail.py`) and a `droplet bench --map` sample of the rest, as this README's budget does:

    python3 results/fig2a-modes/map/budget.py TAIL4.jsonl SAMPLE4.parquet TAIL2.jsonl SAMPLE2.parquet

Each map's total is its tail's run time plus every other run counted by the mean of the
sample's runs that are not in the tail (class not IC and t_end > 5000 in the map's record):
8912 runs in the 4-mode map, 9232 in the 2-mode one.
"""
import json
import sys

import polars as pl


def total(tail_path, sample_path, n_map):
    tail = [json.loads(line) for line in open(tail_path)]
    t = sum(r["rerun"]["wall_s"] for r in tail)
    d = pl.read_parquet(sample_path)
    rest = d.filter(~((pl.col("map_t_end") > 5000) & (pl.col("map_class") != "IC")))
    mean = rest["wall_s"].mean()
    return t, len(tail), rest.height, mean, t + (n_map - len(tail)) * mean, d["same_end"].sum(), d.height


f4 = total(sys.argv[1], sys.argv[2], 8912)
f2 = total(sys.argv[3], sys.argv[4], 9232)
line = "tail %.1f s (%d runs), the sample's %d others %.4f s each -> %.0f s; same end %d of %d"
print("4 modes: " + line % f4)
print("2 modes: " + line % f2)
print("ratio %.3f" % (f4[4] / f2[4]))
