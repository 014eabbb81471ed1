//! The model with shape modes `2..K`: where its runs end either side of its own MD fold.
use droplet_solver::continuation::mode_branch::{md_fold, ModeLine};
use droplet_solver::contract::{outcome::RunStatus, settings::SolverSettings};
use droplet_solver::model::{
    classify::StateClass, initial::InitialCondition, param::ModelParam, params::ModelParams,
};
use droplet_solver::runs::mode_outcome::simulate_modes;

/// The `eta_t` of the MD branch's fold at `kappa2 = 0.13` with modes `2..=k_max` at N = 96.
fn fold(k_max: usize) -> f64 {
    md_fold(&ModeLine {
        base: ModelParams::at(0.07, 0.13),
        n: 96,
        k_max,
        parameter: ModelParam::EtaT,
        from: 0.07,
        to: 0.1,
        eta_k_exponent: 0.0,
    })
    .unwrap()
    .expect("the MD branch folds")
    .at
}

#[test]
fn with_four_modes_the_ic_md_band_ends_at_the_four_mode_fold() {
    // kappa2 = 0.13, N = 96: with modes 2..4 the MD branch folds left of the 2-mode fold
    // (measured: at eta_t = 0.0782561 against 0.0794535), so
    // eta_t = 0.0786 lies inside the 2-mode IC/MD band but right of the 4-mode fold, and
    // 0.0775 between the onset of motion and the 4-mode fold. The runs (the defaults, every
    // initial condition) agree: at 0.0786 every run rests on the disk (single-state IC); at
    // 0.0775 the moving conditions i and ii reach MD and the resting iii and iv stay IC
    // (bistable IC/MD). The same holds at N = 192 (results/k-mode-steps).
    let (two, four) = (fold(2), fold(4));
    assert!(
        four > 0.0775 && four < 0.0786 && two > 0.0786,
        "{two} {four}"
    );
    use StateClass::{IC, MD};
    for (eta_t, classes) in [(0.0786, [IC, IC, IC, IC]), (0.0775, [MD, MD, IC, IC])] {
        for (ic, class) in ["i", "ii", "iii", "iv"].into_iter().zip(classes) {
            let out = simulate_modes(
                &ModelParams::at(eta_t, 0.13),
                &InitialCondition::parse(ic).unwrap(),
                &SolverSettings {
                    n: 96,
                    modes: 4,
                    ..SolverSettings::default()
                },
            )
            .unwrap();
            assert_eq!(out.status, RunStatus::Steady, "{eta_t} {ic}: {out:?}");
            assert_eq!(out.class, Some(class), "{eta_t} {ic}: {out:?}");
        }
    }
}
