//! Cost of one time step (single-threaded), co-moving spectral scheme at N = 128, 192, 256 and
//! the paper's finite-difference scheme at its own resolution (N = 280, dt = 1e-4); and the
//! `K`-mode model's ETD2RK step (`stepping::comoving_etd`) at N = 192 for K = 2, 3, 4, 6, to say what
//! each shape mode adds (K = 2 through the general stepper, beside the 2-mode fast path).
//! Run: `cargo bench --bench step` (add `-- --quick` for a fast pass).
use criterion::{criterion_group, criterion_main, Criterion};
use droplet_solver::stepping::comoving_etd::ComovingEtd;
use droplet_solver::stepping::{comoving_etd::TwoModeEtd, paper_fd::TwoModeFd, Stepper};
use droplet_solver::{model::initial::InitialCondition, model::params::ModelParams};

fn warm<S: Stepper>(mut s: S, h: f64, steps: usize) -> S {
    // Past the start-up, at a moving and deformed state (MD point of Fig. 1).
    for _ in 0..steps {
        s.step(h);
    }
    s
}

fn bench(c: &mut Criterion) {
    let p = ModelParams::at(0.085, 0.112);
    let st = InitialCondition::parse("i").unwrap().state();
    let mut g = c.benchmark_group("step");
    for n in [128, 192, 256] {
        let mut s = warm(TwoModeEtd::new(p, n, st, false).unwrap(), 0.02, 500);
        g.bench_function(format!("spectral_n{n}"), |b| b.iter(|| s.step(0.02)));
    }
    let mut fd = warm(TwoModeFd::new(p, 280, st, false).unwrap(), 1e-4, 2000);
    g.bench_function("paper_fd_n280", |b| b.iter(|| fd.step(1e-4)));
    for k in [2, 3, 4, 6] {
        // IC i with modes 3..K at 0, past the start-up.
        let z = InitialCondition::parse("i").unwrap().unknowns(k);
        let mut m = ComovingEtd::new(&p, 192, &z).unwrap();
        for _ in 0..500 {
            m.step(0.02);
        }
        g.bench_function(format!("modes{k}_n192"), |b| b.iter(|| m.step(0.02)));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
