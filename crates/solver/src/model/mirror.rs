//! The mirror lines of the periodic square box through the droplet's centre that steady states
//! are symmetric about: the x axis and the diagonal (the y axis and the other diagonal are
//! their quarter turns). A state on a line moves along it and its shape is symmetric about it;
//! in the line's own frame (the state turned back by the line's angle) it is a state on the x
//! axis, `b_k = 0`. The box's images tell the two lines apart (an ID droplet settles on the
//! diagonal near its onset of motion).
use serde::Serialize;

/// A mirror line of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MirrorLine {
    /// Motion along x; with two modes the shape `(a2, 0)`.
    X,
    /// Motion along `(1, 1) / sqrt 2`; with two modes the shape `(0, b2)`.
    Diagonal,
}

impl MirrorLine {
    /// The line's angle to the x axis.
    pub fn angle(self) -> f64 {
        match self {
            Self::X => 0.0,
            Self::Diagonal => std::f64::consts::FRAC_PI_4,
        }
    }

    /// The 2-mode state `(vx, vy, a2, b2)` moving at `v` along the line with the mode-2
    /// amplitude `c` on it: `(v, 0, c, 0)` on the x axis, `(v / sqrt 2, v / sqrt 2, 0, c)` on
    /// the diagonal (mode 2 turned by 90 degrees).
    pub fn two_mode_state(self, v: f64, c: f64) -> [f64; 4] {
        match self {
            Self::X => [v, 0.0, c, 0.0],
            Self::Diagonal => {
                let d = v * std::f64::consts::FRAC_1_SQRT_2;
                [d, d, 0.0, c]
            }
        }
    }
}
