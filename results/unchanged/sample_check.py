# Recomputes a sample of the committed fig2a-map runs with the present binary and compares them
# with the committed rows (run from the repository root; needs Python with polars).
import polars as pl, json, subprocess, random
r = pl.read_parquet('results/fig2a-map/runs.parquet')
random.seed(7)
idx = random.sample(range(r.height), 16)
# plus the slowest-to-settle ones: a landing run and an unsettled one
idx += r.with_row_index().filter(pl.col('ended_by') == 'steady_by_landing')['index'].to_list()[:2]
idx += r.with_row_index().filter(pl.col('status') == 't_max')['index'].to_list()[:1]
same = 0; rows = []
for i in idx:
    row = r.row(i, named=True)
    args = ['./target/release/droplet', 'simulate', '--eta-t', repr(row['eta_t']), '--kappa2', repr(row['kappa2']), '--ic', row['ic'], '--json']
    d = json.loads(subprocess.run(args, capture_output=True, text=True).stdout)
    keys = [('status','status'),('class','class'),('v','v'),('s','s'),('t_end','t_end'),('steps','steps'),('ended_by','ended_by'),('unsettled','unsettled')]
    diff = {a: (row[a], d[b]) for a, b in keys if row[a] != d[b]}
    same += not diff
    rows.append(f"| {row['eta_t']} | {row['kappa2']} | {row['ic']} | {row['status']} | {row['class']} | {row['ended_by']} | {'equal' if not diff else diff} |")
print(f"{same} of {len(idx)} runs equal in status, class, v, s, t_end, steps, ended_by, unsettled")
print("\n".join(rows))
