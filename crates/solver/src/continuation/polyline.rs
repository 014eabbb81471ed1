//! Distances to curves drawn as polylines (the boundaries' points in a plane): used to tell
//! a new start point from a curve already traced, and by the studies comparing curves.

/// The distance from `p` to the polyline `line` (to its one point if it has one; infinite if
/// it has none).
pub fn distance_to_polyline(p: (f64, f64), line: &[(f64, f64)]) -> f64 {
    let to_segment = |a: (f64, f64), b: (f64, f64)| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
    };
    match line {
        [] => f64::INFINITY,
        [a] => to_segment(*a, *a),
        _ => line
            .windows(2)
            .map(|w| to_segment(w[0], w[1]))
            .fold(f64::INFINITY, f64::min),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_segments_ends_and_empty_lines() {
        let line = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)];
        assert!((distance_to_polyline((0.5, 0.3), &line) - 0.3).abs() < 1e-15);
        assert!((distance_to_polyline((1.5, 0.5), &line) - 0.5).abs() < 1e-15);
        assert!((distance_to_polyline((-3.0, 4.0), &line) - 5.0).abs() < 1e-15);
        assert!((distance_to_polyline((0.0, 2.0), &[(0.0, 0.0)]) - 2.0).abs() < 1e-15);
        assert!(distance_to_polyline((0.0, 0.0), &[]).is_infinite());
    }
}
