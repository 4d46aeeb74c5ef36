//! The eight weight functions of robust regression (as in MATLAB
//! `robustfit`), with their default tuning constants. IRLS scales residuals
//! to `u = r_adj / (tune * s)` and weights each row by `w(u)`.
//!
//! | weight | w(u) | tune |
//! | --- | --- | --- |
//! | andrews | `(abs(u) < pi) sin(u)/u` | 1.339 |
//! | bisquare (default) | `(abs(u) < 1) (1 - u^2)^2` | 4.685 |
//! | cauchy | `1 / (1 + u^2)` | 2.385 |
//! | fair | `1 / (1 + abs(u))` | 1.400 |
//! | huber | `1 / max(1, abs(u))` | 1.345 |
//! | logistic | `tanh(u) / u` | 1.205 |
//! | talwar | `abs(u) < 1` | 2.795 |
//! | welsch | `exp(-u^2)` | 2.985 |
//!
//! `sin(u)/u` and `tanh(u)/u` take their limit 1 at `u = 0`.

use std::f64::consts::PI;

use crate::SolveError;

/// A robust weight function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RobustWeight {
    /// Andrews' sine.
    Andrews,
    /// Tukey's bisquare (the default).
    #[default]
    Bisquare,
    /// Cauchy.
    Cauchy,
    /// Fair.
    Fair,
    /// Huber.
    Huber,
    /// Logistic.
    Logistic,
    /// Talwar.
    Talwar,
    /// Welsch.
    Welsch,
}

impl RobustWeight {
    /// Every weight function, in the table's order.
    pub const ALL: [RobustWeight; 8] = [
        RobustWeight::Andrews,
        RobustWeight::Bisquare,
        RobustWeight::Cauchy,
        RobustWeight::Fair,
        RobustWeight::Huber,
        RobustWeight::Logistic,
        RobustWeight::Talwar,
        RobustWeight::Welsch,
    ];

    /// The default tuning constant (95% efficiency at the normal model).
    pub fn default_tune(self) -> f64 {
        match self {
            RobustWeight::Andrews => 1.339,
            RobustWeight::Bisquare => 4.685,
            RobustWeight::Cauchy => 2.385,
            RobustWeight::Fair => 1.400,
            RobustWeight::Huber => 1.345,
            RobustWeight::Logistic => 1.205,
            RobustWeight::Talwar => 2.795,
            RobustWeight::Welsch => 2.985,
        }
    }

    /// `w(u)` for a scaled residual `u` (NaN gives 0: such a row gets no weight).
    pub fn weight(self, u: f64) -> f64 {
        if u.is_nan() {
            return 0.0;
        }
        let a = u.abs();
        match self {
            RobustWeight::Andrews => {
                if a >= PI {
                    0.0
                } else if a < 1e-8 {
                    1.0 - u * u / 6.0
                } else {
                    u.sin() / u
                }
            }
            RobustWeight::Bisquare => {
                if a < 1.0 {
                    let t = 1.0 - u * u;
                    t * t
                } else {
                    0.0
                }
            }
            RobustWeight::Cauchy => 1.0 / (1.0 + u * u),
            RobustWeight::Fair => 1.0 / (1.0 + a),
            RobustWeight::Huber => 1.0 / a.max(1.0),
            RobustWeight::Logistic => {
                if a < 1e-8 {
                    1.0 - u * u / 3.0
                } else {
                    u.tanh() / u
                }
            }
            RobustWeight::Talwar => {
                if a < 1.0 {
                    1.0
                } else {
                    0.0
                }
            }
            RobustWeight::Welsch => (-u * u).exp(),
        }
    }

    /// The lower-case name (`bisquare`).
    pub fn name(self) -> &'static str {
        match self {
            RobustWeight::Andrews => "andrews",
            RobustWeight::Bisquare => "bisquare",
            RobustWeight::Cauchy => "cauchy",
            RobustWeight::Fair => "fair",
            RobustWeight::Huber => "huber",
            RobustWeight::Logistic => "logistic",
            RobustWeight::Talwar => "talwar",
            RobustWeight::Welsch => "welsch",
        }
    }
}

impl std::str::FromStr for RobustWeight {
    type Err = SolveError;
    fn from_str(s: &str) -> Result<Self, SolveError> {
        RobustWeight::ALL
            .into_iter()
            .find(|w| w.name() == s.to_ascii_lowercase())
            .ok_or(SolveError::InvalidOption {
                name: "robust weight function",
                value: f64::NAN,
                reason: "use andrews, bisquare, cauchy, fair, huber, logistic, talwar or welsch",
            })
    }
}
