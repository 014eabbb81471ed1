//! How a run's co-moving state `(vx, vy, a_2..a_K, b_2..b_K)` (any `K`) compares with a root's, invariant under the box's
//! near-symmetries: its orientation (direction of motion, or long axis at rest), the angle
//! between the two compared like with like, a rotation-invariant distance, and whether one
//! class lies within reach of a root.
use crate::model::classify::StateClass;
use crate::model::state::{mode_two, reflected, speed_and_deformation};

/// Largest angle between a run's orientation and a stable root's for the run to be taken to
/// be turning towards it.
/// Known limitation: a run within this angle whose lean is growing (just past the basin
/// boundary between two stable orientations, e.g. at (0.1, 0.1) from IC iv) is also taken,
/// and ends on the wrong mirror line: same class, `s` off by the box's anisotropy (docs/numerics.md,
/// "Finishing runs by Newton").
pub const ORIENTATION: f64 = std::f64::consts::PI / 16.0;

/// The turns (degrees) from a state on a mirror line that is unstable in its rotation mode
/// at which [`NewtonFinish::stable_root`] looks for the stable root the run turns to.
pub const TURN_SEARCH: [f64; 7] = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 45.0];

/// Leans (radians) below this are round-off of a mirror-symmetric run and count as none.
pub const LEAN_FLOOR: f64 = 1e-9;

/// The direction of motion, or for a resting droplet the direction of its long axis (of
/// its mode 2).
pub(crate) fn orientation(z: &[f64]) -> f64 {
    if z[0].hypot(z[1]) > 1e-9 {
        z[1].atan2(z[0])
    } else {
        let (a2, b2) = mode_two(z);
        0.5 * b2.atan2(a2)
    }
}

/// The box's mirror line nearest the run's orientation (motion, or long axis at rest, at a
/// multiple of 45 degrees): which one (its multiple of 45 degrees, and whether the run
/// moves), and the run's lean from it, in [-pi/8, pi/8].
pub(crate) fn lean_from_mirror_line(z: &[f64]) -> ((i64, bool), f64) {
    let quarter = std::f64::consts::FRAC_PI_4;
    let phi = orientation(z);
    let line = (phi / quarter).round();
    ((line as i64, z[0].hypot(z[1]) > 1e-9), phi - line * quarter)
}

/// Whether `z = (vx, vy, a_2..a_K, b_2..b_K)` is its own mirror image in one of the box's
/// mirror lines (through the droplet at a multiple of 45 degrees): a run from such a state
/// stays on that line, its lean round-off. Reflection in the line at angle `alpha` takes the
/// velocity `v -> e^{2 i alpha} conj(v)` and shape mode `k`,
/// `a_k + i b_k -> e^{2 k i alpha} conj(a_k + i b_k)`.
pub(crate) fn mirror_symmetric(z: &[f64]) -> bool {
    let scale = z.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    (0..4).any(|n| {
        let image = reflected(z, f64::from(n) * std::f64::consts::FRAC_PI_4);
        z.iter()
            .zip(&image)
            .all(|(a, b)| (a - b).abs() <= 1e-14 * scale)
    })
}

/// Whether `z` has no orientation: at rest and round in mode 2 (the resting disk). Its
/// higher modes need not vanish: with modes 2..K the box's four-fold symmetry holds the
/// resting disk's modes 4, 8, ... at small amplitudes of their own, aligned with the box
/// (a4 = -2.8e-5 at (0.0765, 0.16425), N = 192), which no run's lean turns.
pub(crate) fn unoriented(z: &[f64]) -> bool {
    let (v, s) = speed_and_deformation(z);
    v <= 1e-9 && s <= 1e-9
}

/// The angle from the root `root`'s orientation to the run `z`'s, compared like with like:
/// directions of motion when both move, else long axes (modulo pi; a run slowing down onto
/// a resting deformed root moves along its short axis, not its long one), and 0 for a
/// resting round root, which has no orientation. In (-pi/2, pi/2].
pub(crate) fn angle_to(z: &[f64], root: &[f64]) -> f64 {
    let moving = |z: &[f64]| z[0].hypot(z[1]) > 1e-9;
    if moving(z) && moving(root) {
        return (z[1].atan2(z[0]) - root[1].atan2(root[0])).sin().asin();
    }
    let ((za, zb), (ra, rb)) = (mode_two(z), mode_two(root));
    if ra.hypot(rb) <= 1e-9 {
        return 0.0;
    }
    modulo_half_turn(0.5 * (zb.atan2(za) - rb.atan2(ra)))
}

/// The angle `d` modulo pi, in [-pi/2, pi/2] (orientations of long axes, or of lines).
pub(crate) fn modulo_half_turn(d: f64) -> f64 {
    d - std::f64::consts::PI * (d / std::f64::consts::PI).round()
}

/// The class of `z`.
pub(crate) fn class_of(z: &[f64]) -> StateClass {
    let (v, s) = speed_and_deformation(z);
    StateClass::of(v, s)
}

/// Max of the differences in speed and in deformation (invariant under rotation).
pub(crate) fn invariant_distance(a: &[f64], b: &[f64]) -> f64 {
    let ((va, sa), (vb, sb)) = (speed_and_deformation(a), speed_and_deformation(b));
    (va - vb).abs().max((sa - sb).abs())
}

/// Whether every state whose speed and deformation are within `reach` (max over the
/// components, so `sqrt(2) reach` in `v` and `s`) of the root `root`'s has the class of `z`.
/// Classes are quadrants of the `(v, s)` plane, so the corners of that box decide.
pub(crate) fn one_class_within(z: &[f64], root: &[f64], reach: f64) -> bool {
    let class = class_of(z);
    let (v, s) = speed_and_deformation(root);
    let r = std::f64::consts::SQRT_2 * reach;
    [(v - r).max(0.0), v + r].iter().all(|&v| {
        [(s - r).max(0.0), s + r]
            .iter()
            .all(|&s| StateClass::of(v, s) == class)
    })
}

/// How far (radians, in `(0, pi/4]`) the box's next mirror line lies from the orientation
/// `phi` turning to the side `side` (+1 or -1): 45 degrees from an orientation on a line
/// (within 1e-4 of the spacing, 0.0045 degree), nearer from one between two.
pub(crate) fn next_mirror_line(phi: f64, side: f64) -> f64 {
    const ON_LINE: f64 = 1e-4;
    let quarter = std::f64::consts::FRAC_PI_4;
    let f = phi / quarter;
    let line = if side > 0.0 {
        (f + ON_LINE).floor() + 1.0
    } else {
        (f - ON_LINE).ceil() - 1.0
    };
    side * (line * quarter - phi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::initial::NAMED;
    use crate::model::state::turned;

    #[test]
    fn only_states_that_are_their_own_mirror_image_are_mirror_symmetric() {
        // The paper's i' and ii' lie on the x axis; i-iv lean off every mirror line.
        for (name, z) in NAMED {
            assert_eq!(mirror_symmetric(&z), name.ends_with('\''), "{name}");
        }
        // On the diagonal, and turned by a quarter: still on a mirror line.
        let diagonal = turned(&[0.3, 0.0, 0.1, 0.0], std::f64::consts::FRAC_PI_4);
        assert!(mirror_symmetric(&diagonal));
        assert!(mirror_symmetric(&turned(
            &diagonal,
            std::f64::consts::FRAC_PI_2
        )));
        // Motion on the x axis but the shape turned: no mirror line keeps both.
        assert!(!mirror_symmetric(&[0.3, 0.0, 0.1, 0.02]));
        assert!(mirror_symmetric(&[0.0; 4]));
        // With modes 2..4 every mode must be its mirror image: on the x axis with a3 and a4,
        // and turned onto the diagonal; not with a b3 (mode 3 turned off the line).
        let axis = [0.3, 0.0, 0.1, 0.02, 0.01, 0.0, 0.0, 0.0];
        assert!(mirror_symmetric(&axis));
        assert!(mirror_symmetric(&turned(
            &axis,
            std::f64::consts::FRAC_PI_4
        )));
        assert!(!mirror_symmetric(&[
            0.3, 0.0, 0.1, 0.02, 0.01, 0.0, 0.005, 0.0
        ]));
    }

    #[test]
    fn only_the_resting_round_droplet_has_no_orientation() {
        // The resting disk with the box's mode 4 (a4, no b4): no orientation, whatever a4.
        assert!(unoriented(&[0.0, 0.0, 1e-13, 0.0, -5e-4, 0.0, 0.0, 0.0]));
        assert!(unoriented(&[0.0; 4]));
        // Moving, or deformed in mode 2: oriented.
        assert!(!unoriented(&[1e-6, 0.0, 0.0, 0.0, -5e-4, 0.0, 0.0, 0.0]));
        assert!(!unoriented(&[0.0, 0.0, 1e-6, 0.0, 0.0, 0.0, 0.0, 0.0]));
    }

    #[test]
    fn a_lean_is_measured_from_the_nearest_mirror_line() {
        let z = turned(&[0.3, 0.0, 0.1, 0.0], 50f64.to_radians());
        let ((line, moving), lean) = lean_from_mirror_line(&z);
        assert_eq!((line, moving), (1, true));
        assert!((lean - 5f64.to_radians()).abs() < 1e-12, "{lean}");
        // At rest the long axis decides.
        let ((line, moving), lean) = lean_from_mirror_line(&[0.0, 0.0, 0.0, -0.1]);
        assert_eq!((line, moving), (-1, false));
        assert!(lean.abs() < 1e-12, "{lean}");
    }

    #[test]
    fn the_next_mirror_line_is_a_quarter_turn_away_from_a_line_and_nearer_between_two() {
        let deg = |d: f64| d.to_radians();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        for (phi, side, to_line) in [
            (90.0, 1.0, 45.0),
            (90.0, -1.0, 45.0),
            (90.0 - 1e-6, 1.0, 45.0),
            (111.65, 1.0, 23.35),
            (111.65, -1.0, 21.65),
            (-2.25, 1.0, 2.25),
            (-2.25, -1.0, 42.75),
        ] {
            let got = next_mirror_line(deg(phi), side);
            assert!(
                close(got, deg(to_line)) || (phi == 90.0 - 1e-6 && (got - deg(45.0)).abs() < 1e-7),
                "{phi} {side}: {}",
                got.to_degrees()
            );
        }
    }
}
