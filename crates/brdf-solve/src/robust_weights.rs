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
//!
//! Each weight has its loss `rho(u) = int_0^u t w(t) dt` ([`RobustWeight::rho`],
//! so that `rho'(u) = psi(u) = u w(u)` and `rho(u) ~ u^2 / 2` at 0): the
//! objective IRLS decreases at a fixed scale, and (times `tune^2`) the
//! deviance statsmodels' stopping test watches.
//!
//! | weight | rho(u) |
//! | --- | --- |
//! | andrews | `1 - cos(u)` for `abs(u) < pi`, else 2 |
//! | bisquare | `(1 - (1 - u^2)^3) / 6` for `abs(u) < 1`, else 1/6 |
//! | cauchy | `ln(1 + u^2) / 2` |
//! | fair | `abs(u) - ln(1 + abs(u))` |
//! | huber | `u^2 / 2` for `abs(u) <= 1`, else `abs(u) - 1/2` |
//! | logistic | `ln(cosh(u))` |
//! | talwar | `min(u^2, 1) / 2` |
//! | welsch | `(1 - exp(-u^2)) / 2` |

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

    /// The loss `rho(u) = int_0^u t w(t) dt` (a NaN or infinite `u` gives the
    /// loss's supremum, infinity where it is unbounded).
    pub fn rho(self, u: f64) -> f64 {
        let a = u.abs();
        if !a.is_finite() {
            return match self {
                RobustWeight::Andrews => 2.0,
                RobustWeight::Bisquare => 1.0 / 6.0,
                RobustWeight::Talwar | RobustWeight::Welsch => 0.5,
                _ => f64::INFINITY,
            };
        }
        // Forms without cancellation at small |u| (the objective sums many
        // small losses): 1 - cos a = 2 sin^2(a/2), 1 - t^3 = a^2 (1 + t + t^2),
        // cosh a - 1 = 2 sinh^2(a/2).
        match self {
            RobustWeight::Andrews => {
                if a < PI {
                    2.0 * (0.5 * a).sin().powi(2)
                } else {
                    2.0
                }
            }
            RobustWeight::Bisquare => {
                if a < 1.0 {
                    let t = 1.0 - a * a;
                    a * a * (1.0 + t + t * t) / 6.0
                } else {
                    1.0 / 6.0
                }
            }
            RobustWeight::Cauchy => 0.5 * (a * a).ln_1p(),
            RobustWeight::Fair => a - a.ln_1p(),
            RobustWeight::Huber => {
                if a <= 1.0 {
                    0.5 * a * a
                } else {
                    a - 0.5
                }
            }
            RobustWeight::Logistic => {
                if a < 20.0 {
                    (2.0 * (0.5 * a).sinh().powi(2)).ln_1p()
                } else {
                    a + (-2.0 * a).exp().ln_1p() - std::f64::consts::LN_2
                }
            }
            RobustWeight::Talwar => 0.5 * (a * a).min(1.0),
            RobustWeight::Welsch => -0.5 * (-a * a).exp_m1(),
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
