//! A method family of the benchmark: one curve of the work-precision picture. Its label
//! (`paper-fd`, `spectral N=192`, `adaptive N=192 dt_max=0.25`, `newton N=192 dt_max=0.25`)
//! is made only for tables, files and messages, and read back from them.
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// How a family computes a case.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum Family {
    /// The paper's finite-difference scheme.
    PaperFd,
    /// The spectral scheme with fixed steps on an `n x n` grid.
    Spectral { n: usize },
    /// Adaptive spectral steps capped at `dt_max`, ended by the paper's steady test.
    Adaptive { n: usize, dt_max: f64 },
    /// Adaptive spectral steps capped at `dt_max`, ended by the Newton finish.
    Newton { n: usize, dt_max: f64 },
}

impl Family {
    /// The curves drawn in one colour: every `n` of one kind and step cap.
    pub fn colour_group(&self) -> (u8, Option<u64>) {
        match *self {
            Self::PaperFd => (0, None),
            Self::Spectral { .. } => (1, None),
            Self::Adaptive { dt_max, .. } => (2, Some(dt_max.to_bits())),
            Self::Newton { dt_max, .. } => (3, Some(dt_max.to_bits())),
        }
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PaperFd => write!(f, "paper-fd"),
            Self::Spectral { n } => write!(f, "spectral N={n}"),
            Self::Adaptive { n, dt_max } => write!(f, "adaptive N={n} dt_max={dt_max}"),
            Self::Newton { n, dt_max } => write!(f, "newton N={n} dt_max={dt_max}"),
        }
    }
}

impl FromStr for Family {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("not a benchmark family: {s:?}");
        if s == "paper-fd" {
            return Ok(Self::PaperFd);
        }
        let mut words = s.split(' ');
        let kind = words.next().ok_or_else(bad)?;
        let value = |w: Option<&str>, key: &str| -> Result<String, String> {
            w.and_then(|w| w.strip_prefix(key))
                .map(str::to_string)
                .ok_or_else(bad)
        };
        let n: usize = value(words.next(), "N=")?.parse().map_err(|_| bad())?;
        let family = match kind {
            "spectral" => Self::Spectral { n },
            "adaptive" | "newton" => {
                let dt_max: f64 = value(words.next(), "dt_max=")?.parse().map_err(|_| bad())?;
                if kind == "adaptive" {
                    Self::Adaptive { n, dt_max }
                } else {
                    Self::Newton { n, dt_max }
                }
            }
            _ => return Err(bad()),
        };
        match words.next() {
            None => Ok(family),
            Some(_) => Err(bad()),
        }
    }
}

impl From<Family> for String {
    fn from(f: Family) -> String {
        f.to_string()
    }
}

impl TryFrom<String> for Family {
    type Error = String;

    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_read_back_to_the_same_family() {
        for f in [
            Family::PaperFd,
            Family::Spectral { n: 192 },
            Family::Adaptive {
                n: 128,
                dt_max: 0.25,
            },
            Family::Newton {
                n: 256,
                dt_max: 1.0,
            },
        ] {
            assert_eq!(f.to_string().parse::<Family>(), Ok(f));
            let json = serde_json::to_string(&f).unwrap();
            assert_eq!(json, format!("\"{f}\""));
            assert_eq!(serde_json::from_str::<Family>(&json).unwrap(), f);
        }
        assert_eq!(
            Family::Adaptive {
                n: 192,
                dt_max: 0.1
            }
            .to_string(),
            "adaptive N=192 dt_max=0.1"
        );
        for bad in [
            "",
            "spectral",
            "spectral N=x",
            "adaptive N=1",
            "newton N=1 dt_max=1 x",
        ] {
            assert!(bad.parse::<Family>().is_err(), "{bad}");
        }
    }
}
