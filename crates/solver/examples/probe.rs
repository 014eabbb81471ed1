//! Quick timing of one step and the steady MD state at several N (development aid; the
//! reported numbers come from `cargo bench --bench step`).
use droplet_solver::*;
use std::time::Instant;
fn main() {
    let md = ModelParams::at(0.085, 0.112);
    for n in [128, 192, 256, 384] {
        let mut s = SteadySolver::new(md, n).unwrap();
        let m = s.newton(0.6, -0.27, 1e-12).unwrap();
        println!("N={n} MD v={:.9} a2={:.9}", m.v, m.a2);
    }
    for n in [128, 192, 256] {
        let ic = InitialCondition::parse("i").unwrap();
        let mut sch = scheme::ComovingEtd::new(md, n, ic.state(), false).unwrap();
        for _ in 0..50 {
            sch.step(0.02);
        }
        let t0 = Instant::now();
        let k = 1000;
        for _ in 0..k {
            sch.step(0.02);
        }
        println!(
            "N={n}: {:.1} us/step  mass {:.12} state {:?}",
            t0.elapsed().as_secs_f64() / k as f64 * 1e6,
            sch.mass(),
            sch.state()
        );
    }
}
