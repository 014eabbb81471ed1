//! Cost of one stability verdict (single-threaded, N = 192): the linearisation about a steady
//! state and every eigenvalue with `Re > -1` (`roots::linearisation`), as a run's finish pays
//! it through [`Balances::verdict`], at the Fig. 1c MD state (x axis) for K = 2 (the 2-mode
//! fast path), 3 and 4, and at the resting disk of (0.085, 0.12) with K = 4 (its double roots).
//! Run: `cargo bench --bench verdict` (add `-- --quick` for a fast pass).
use criterion::{criterion_group, criterion_main, Criterion};
use droplet_solver::model::params::ModelParams;
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::kept_jacobians::KeptJacobians;

/// The root Newton finds from `seed` (`(vx, vy, a_2..a_K, b_2..b_K)`), and its balances.
fn root(params: ModelParams, seed: &[f64]) -> (Balances, Vec<f64>) {
    let mut balances = Balances::new(params, 192).unwrap();
    let z = balances
        .root_near(seed, &mut KeptJacobians::default())
        .unwrap();
    (balances, z)
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("verdict");
    g.sample_size(20);
    // The Fig. 1c MD: v, a2 of two modes, the higher modes from 0 (Newton finds them).
    for k in [2usize, 3, 4] {
        let mut seed = vec![0.0; 2 * k];
        (seed[0], seed[2]) = (if k == 2 { 0.59 } else { 0.3 }, -0.2);
        let (mut b, z) = root(ModelParams::at(0.085, 0.112).with_modes(k), &seed);
        assert!(b.verdict(&z).stable(), "K = {k}: {z:?}");
        g.bench_function(format!("md_modes{k}_n192"), |bench| {
            bench.iter(|| b.verdict(&z))
        });
    }
    let (mut b, z) = root(ModelParams::at(0.085, 0.12).with_modes(4), &[0.0; 8]);
    g.bench_function("disk_modes4_n192", |bench| bench.iter(|| b.verdict(&z)));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
