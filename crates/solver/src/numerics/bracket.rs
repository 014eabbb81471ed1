//! A root of a scalar function in a sign-changing bracket: the Illinois variant of regula
//! falsi (superlinear, and never leaves the bracket).

/// The root of `f` between `a` and `b` (`fa = f(a)`, `fb = f(b)` of opposite signs, or one of
/// them zero), to `|b - a| <= tol` or 100 evaluations. `None` when `f` is not finite inside
/// (it is not defined over the whole bracket).
pub fn illinois(
    f: &mut impl FnMut(f64) -> f64,
    (mut a, mut fa): (f64, f64),
    (mut b, mut fb): (f64, f64),
    tol: f64,
) -> Option<f64> {
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    let mut side = 0i32;
    for _ in 0..100 {
        if (b - a).abs() <= tol {
            break;
        }
        let x = (a * fb - b * fa) / (fb - fa);
        let x = if x.is_finite() && (x - a) * (x - b) < 0.0 {
            x
        } else {
            0.5 * (a + b)
        };
        let fx = f(x);
        if !fx.is_finite() {
            return None;
        }
        if fx == 0.0 {
            return Some(x);
        }
        if fx.signum() == fa.signum() {
            (a, fa) = (x, fx);
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            (b, fb) = (x, fx);
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    Some(if fa.abs() < fb.abs() { a } else { b })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_root_of_a_convex_function_superlinearly() {
        let mut calls = 0;
        let mut f = |x: f64| {
            calls += 1;
            x.exp() - 2.0
        };
        let (fa, fb) = (f(0.0), f(3.0));
        let r = illinois(&mut f, (0.0, fa), (3.0, fb), 1e-13).unwrap();
        assert!((r - 2f64.ln()).abs() < 1e-12, "{r}");
        // Plain regula falsi would creep from one side (hundreds of calls).
        assert!(calls < 20, "{calls}");
    }

    #[test]
    fn refuses_a_function_undefined_inside_the_bracket() {
        let mut f = |x: f64| if x > 0.5 { f64::NAN } else { x - 0.7 };
        assert_eq!(illinois(&mut f, (0.0, -0.7), (1.0, 0.3), 1e-12), None);
    }
}
