use droplet_solver::*;
use std::time::Instant;
fn main() {
    let md = ModelParams::at(0.085, 0.112);
    let id = ModelParams::at(0.085, 0.116);
    for n in [128, 192, 256, 384] {
        let mut s = SteadySolver::new(md, n).unwrap();
        let m = s.newton(0.6, -0.27, 1e-12).unwrap();
        let mut s2 = SteadySolver::new(id, n).unwrap();
        let i = s2.newton(0.0, 0.12, 1e-12).unwrap();
        println!("N={n} MD v={:.9} a2={:.9} | ID a2={:.9}", m.v, m.a2, i.a2);
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
