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
}
