//! Cost of one time step (single-threaded), co-moving spectral scheme at N = 128, 192, 256 and
//! the paper's finite-difference scheme at its own resolution (N = 280, dt = 1e-4); and the
//! `K`-mode model's ETD2RK step (`stepping::comoving_etd`) at N = 192 for K = 2, 3, 4, 6, to say what
//! each shape mode adds (K = 2 through the general stepper, beside the 2-mode fast path); and one
//! row-pruned transform of the K-mode step (`numerics::fft2`, N = 192, the 103 rows of the
//! K = 4 droplet's window at the MD point), five of which a K-mode step takes; and one steady
//! field solve of the 2-mode Newton finish (`roots::steady_solver::TwoModeSolver`, N = 192):
//! of a droplet whose transform is kept (the field and its forces) and of a new shape.
//! Run: `cargo bench --bench step` (add `-- --quick` for a fast pass).
use criterion::{criterion_group, criterion_main, Criterion};
use droplet_solver::numerics::fft2::PrunedFft2;
use droplet_solver::roots::steady_solver::TwoModeSolver;
use droplet_solver::stepping::comoving_etd::ComovingEtd;
use droplet_solver::stepping::{comoving_etd::TwoModeEtd, paper_fd::TwoModeFd, Stepper};
use droplet_solver::{model::initial::InitialCondition, model::params::ModelParams};
use rustfft::num_complex::Complex64;

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
    let n = 192;
    let (lo, hi) = (n / 2 - 51, n / 2 + 51);
    let mut fft = PrunedFft2::new(n);
    let real: Vec<f64> = (0..n * n)
        .map(|i| {
            if (lo..=hi).contains(&(i / n)) {
                (i % 7) as f64
            } else {
                0.0
            }
        })
        .collect();
    let mut spec = vec![Complex64::default(); (n / 2 + 1) * n];
    g.bench_function("transform_forward_n192", |b| {
        b.iter(|| fft.forward(&real, &mut spec, lo, hi))
    });
    let full = spec.clone();
    let mut out = vec![0.0; n * n];
    // The inverse consumes its spectrum: each iteration copies it back (a copy of 300 kB).
    g.bench_function("transform_inverse_n192", |b| {
        b.iter(|| {
            spec.copy_from_slice(&full);
            fft.inverse(&mut spec, &mut out, lo, hi)
        })
    });
    let mut solver = TwoModeSolver::new(p, 192).unwrap();
    let (v, a2) = (0.59, -0.25);
    let mut i = 0u32;
    g.bench_function("steady_field_n192", |b| {
        b.iter(|| {
            i = i.wrapping_add(1);
            solver
                .field_and_forces(v + 1e-9 * f64::from(i % 64), 0.0, a2, 0.0)
                .1
        })
    });
    g.bench_function("steady_field_new_shape_n192", |b| {
        b.iter(|| {
            i = i.wrapping_add(1);
            solver
                .field_and_forces(v, 0.0, a2 + 1e-9 * f64::from(i % 64), 0.0)
                .1
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
