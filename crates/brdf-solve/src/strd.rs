//! The 27 model functions of the NIST StRD non-linear regression problems
//! (NIST ITL, Statistical Reference Datasets), with analytic gradients, and
//! [`StrdProblem`], which turns a model and its data into a
//! [`LeastSquaresProblem`] for solver certification.
//!
//! Residuals are `f(x; b) - y` (Nelson: `f(x; b) - ln y`, as NIST states its
//! model for `log[y]`). The formulas are NIST's, listed by problem:
//!
//! | problems | `f(x; b)` |
//! | --- | --- |
//! | Bennett5 | `b1 (b2 + x)^(-1/b3)` |
//! | BoxBOD, Misra1a | `b1 (1 - exp(-b2 x))` |
//! | Chwirut1, Chwirut2 | `exp(-b1 x) / (b2 + b3 x)` |
//! | DanWood | `b1 x^b2` |
//! | ENSO | `b1 + b2 cos(2 pi x/12) + b3 sin(2 pi x/12) + b5 cos(2 pi x/b4) + b6 sin(2 pi x/b4) + b8 cos(2 pi x/b7) + b9 sin(2 pi x/b7)` |
//! | Eckerle4 | `(b1/b2) exp(-0.5 ((x - b3)/b2)^2)` |
//! | Gauss1-3 | `b1 exp(-b2 x) + b3 exp(-(x-b4)^2/b5^2) + b6 exp(-(x-b7)^2/b8^2)` |
//! | Hahn1, Thurber | `(b1 + b2 x + b3 x^2 + b4 x^3) / (1 + b5 x + b6 x^2 + b7 x^3)` |
//! | Kirby2 | `(b1 + b2 x + b3 x^2) / (1 + b4 x + b5 x^2)` |
//! | Lanczos1-3 | `b1 exp(-b2 x) + b3 exp(-b4 x) + b5 exp(-b6 x)` |
//! | MGH09 | `b1 (x^2 + x b2) / (x^2 + x b3 + b4)` |
//! | MGH10 | `b1 exp(b2 / (x + b3))` |
//! | MGH17 | `b1 + b2 exp(-x b4) + b3 exp(-x b5)` |
//! | Misra1b | `b1 (1 - (1 + b2 x/2)^(-2))` |
//! | Misra1c | `b1 (1 - (1 + 2 b2 x)^(-1/2))` |
//! | Misra1d | `b1 b2 x / (1 + b2 x)` |
//! | Nelson | `ln y = b1 - b2 x1 exp(-b3 x2)` |
//! | Rat42 | `b1 / (1 + exp(b2 - b3 x))` |
//! | Rat43 | `b1 / (1 + exp(b2 - b3 x))^(1/b4)` |
//! | Roszman1 | `b1 - b2 x - atan(b3 / (x - b4)) / pi` |

use crate::SolveError;
use crate::problem::LeastSquaresProblem;
use std::f64::consts::PI;

/// The names of all 27 StRD non-linear regression problems.
pub const PROBLEMS: [&str; 27] = [
    "Misra1a", "Chwirut2", "Chwirut1", "Lanczos3", "Gauss1", "Gauss2", "DanWood", "Misra1b",
    "Kirby2", "Hahn1", "Nelson", "MGH17", "Lanczos1", "Lanczos2", "Gauss3", "Misra1c", "Misra1d",
    "Roszman1", "ENSO", "MGH09", "Thurber", "BoxBOD", "Rat42", "MGH10", "Eckerle4", "Rat43",
    "Bennett5",
];

/// A StRD model family (several problems share one formula).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StrdModel {
    /// Bennett5.
    Bennett5,
    /// BoxBOD and Misra1a.
    SaturatingExp,
    /// Chwirut1 and Chwirut2.
    Chwirut,
    /// DanWood.
    DanWood,
    /// ENSO.
    Enso,
    /// Eckerle4.
    Eckerle4,
    /// Gauss1, Gauss2, Gauss3.
    Gauss,
    /// Hahn1 and Thurber (cubic over cubic).
    Rational33,
    /// Kirby2 (quadratic over quadratic).
    Rational22,
    /// Lanczos1, Lanczos2, Lanczos3.
    Lanczos,
    /// MGH09.
    Mgh09,
    /// MGH10.
    Mgh10,
    /// MGH17.
    Mgh17,
    /// Misra1b.
    Misra1b,
    /// Misra1c.
    Misra1c,
    /// Misra1d.
    Misra1d,
    /// Nelson (two predictors, response `ln y`).
    Nelson,
    /// Rat42.
    Rat42,
    /// Rat43.
    Rat43,
    /// Roszman1.
    Roszman1,
}

impl StrdModel {
    /// The model of a problem by its NIST name (case-insensitive).
    pub fn for_problem(name: &str) -> Option<Self> {
        use StrdModel::*;
        Some(match name.to_ascii_lowercase().as_str() {
            "bennett5" => Bennett5,
            "boxbod" | "misra1a" => SaturatingExp,
            "chwirut1" | "chwirut2" => Chwirut,
            "danwood" => DanWood,
            "enso" => Enso,
            "eckerle4" => Eckerle4,
            "gauss1" | "gauss2" | "gauss3" => Gauss,
            "hahn1" | "thurber" => Rational33,
            "kirby2" => Rational22,
            "lanczos1" | "lanczos2" | "lanczos3" => Lanczos,
            "mgh09" => Mgh09,
            "mgh10" => Mgh10,
            "mgh17" => Mgh17,
            "misra1b" => Misra1b,
            "misra1c" => Misra1c,
            "misra1d" => Misra1d,
            "nelson" => Nelson,
            "rat42" => Rat42,
            "rat43" => Rat43,
            "roszman1" => Roszman1,
            _ => return None,
        })
    }

    /// Number of parameters.
    pub fn n_params(self) -> usize {
        use StrdModel::*;
        match self {
            SaturatingExp | DanWood | Misra1b | Misra1c | Misra1d => 2,
            Bennett5 | Chwirut | Eckerle4 | Mgh10 | Nelson | Rat42 => 3,
            Mgh09 | Rat43 | Roszman1 => 4,
            Rational22 | Mgh17 => 5,
            Lanczos => 6,
            Rational33 => 7,
            Gauss => 8,
            Enso => 9,
        }
    }

    /// Number of predictors per observation (2 for Nelson, else 1).
    pub fn n_predictors(self) -> usize {
        if self == StrdModel::Nelson { 2 } else { 1 }
    }

    /// Whether the model is stated for `ln y` rather than `y`.
    pub fn log_response(self) -> bool {
        self == StrdModel::Nelson
    }

    /// `f(x; b)` and its gradient `df/db` (into `grad`, length `n_params`).
    pub fn eval(self, x: &[f64], b: &[f64], grad: &mut [f64]) -> f64 {
        use StrdModel::*;
        let x0 = x[0];
        match self {
            Bennett5 => {
                let u = b[1] + x0;
                let e = -1.0 / b[2];
                let ue = u.powf(e);
                grad[0] = ue;
                grad[1] = b[0] * e * ue / u;
                grad[2] = b[0] * ue * u.ln() / (b[2] * b[2]);
                b[0] * ue
            }
            SaturatingExp => {
                let e = (-b[1] * x0).exp();
                grad[0] = 1.0 - e;
                grad[1] = b[0] * x0 * e;
                b[0] * (1.0 - e)
            }
            Chwirut => {
                let e = (-b[0] * x0).exp();
                let q = b[1] + b[2] * x0;
                grad[0] = -x0 * e / q;
                grad[1] = -e / (q * q);
                grad[2] = -x0 * e / (q * q);
                e / q
            }
            DanWood => {
                let p = x0.powf(b[1]);
                grad[0] = p;
                grad[1] = b[0] * p * x0.ln();
                b[0] * p
            }
            Enso => {
                let w = 2.0 * PI * x0;
                let (s12, c12) = (w / 12.0).sin_cos();
                let (t4, t7) = (w / b[3], w / b[6]);
                let (s4, c4) = t4.sin_cos();
                let (s7, c7) = t7.sin_cos();
                grad[0] = 1.0;
                grad[1] = c12;
                grad[2] = s12;
                grad[3] = (-b[4] * s4 + b[5] * c4) * (-t4 / b[3]);
                grad[4] = c4;
                grad[5] = s4;
                grad[6] = (-b[7] * s7 + b[8] * c7) * (-t7 / b[6]);
                grad[7] = c7;
                grad[8] = s7;
                b[0] + b[1] * c12 + b[2] * s12 + b[4] * c4 + b[5] * s4 + b[7] * c7 + b[8] * s7
            }
            Eckerle4 => {
                let z = (x0 - b[2]) / b[1];
                let e = (-0.5 * z * z).exp();
                grad[0] = e / b[1];
                grad[1] = b[0] * e / (b[1] * b[1]) * (z * z - 1.0);
                grad[2] = b[0] / b[1] * e * z / b[1];
                b[0] / b[1] * e
            }
            Gauss => {
                let e1 = (-b[1] * x0).exp();
                let (d4, d7) = (x0 - b[3], x0 - b[6]);
                let g1 = (-d4 * d4 / (b[4] * b[4])).exp();
                let g2 = (-d7 * d7 / (b[7] * b[7])).exp();
                grad[0] = e1;
                grad[1] = -b[0] * x0 * e1;
                grad[2] = g1;
                grad[3] = b[2] * g1 * 2.0 * d4 / (b[4] * b[4]);
                grad[4] = b[2] * g1 * 2.0 * d4 * d4 / (b[4] * b[4] * b[4]);
                grad[5] = g2;
                grad[6] = b[5] * g2 * 2.0 * d7 / (b[7] * b[7]);
                grad[7] = b[5] * g2 * 2.0 * d7 * d7 / (b[7] * b[7] * b[7]);
                b[0] * e1 + b[2] * g1 + b[5] * g2
            }
            Rational33 => rational(x0, b, 4, grad),
            Rational22 => rational(x0, b, 3, grad),
            Lanczos => {
                let mut f = 0.0;
                for k in 0..3 {
                    let e = (-b[2 * k + 1] * x0).exp();
                    grad[2 * k] = e;
                    grad[2 * k + 1] = -b[2 * k] * x0 * e;
                    f += b[2 * k] * e;
                }
                f
            }
            Mgh09 => {
                let nn = x0 * x0 + x0 * b[1];
                let d = x0 * x0 + x0 * b[2] + b[3];
                grad[0] = nn / d;
                grad[1] = b[0] * x0 / d;
                grad[2] = -b[0] * nn * x0 / (d * d);
                grad[3] = -b[0] * nn / (d * d);
                b[0] * nn / d
            }
            Mgh10 => {
                let q = x0 + b[2];
                let e = (b[1] / q).exp();
                grad[0] = e;
                grad[1] = b[0] * e / q;
                grad[2] = -b[0] * e * b[1] / (q * q);
                b[0] * e
            }
            Mgh17 => {
                let e4 = (-x0 * b[3]).exp();
                let e5 = (-x0 * b[4]).exp();
                grad[0] = 1.0;
                grad[1] = e4;
                grad[2] = e5;
                grad[3] = -b[1] * x0 * e4;
                grad[4] = -b[2] * x0 * e5;
                b[0] + b[1] * e4 + b[2] * e5
            }
            Misra1b => {
                let u = 1.0 + b[1] * x0 / 2.0;
                grad[0] = 1.0 - u.powi(-2);
                grad[1] = b[0] * x0 * u.powi(-3);
                b[0] * (1.0 - u.powi(-2))
            }
            Misra1c => {
                let u = 1.0 + 2.0 * b[1] * x0;
                let s = u.sqrt();
                grad[0] = 1.0 - 1.0 / s;
                grad[1] = b[0] * x0 / (u * s);
                b[0] * (1.0 - 1.0 / s)
            }
            Misra1d => {
                let q = 1.0 + b[1] * x0;
                grad[0] = b[1] * x0 / q;
                grad[1] = b[0] * x0 / (q * q);
                b[0] * b[1] * x0 / q
            }
            Nelson => {
                let (x1, x2) = (x[0], x[1]);
                let e = (-b[2] * x2).exp();
                grad[0] = 1.0;
                grad[1] = -x1 * e;
                grad[2] = b[1] * x1 * x2 * e;
                b[0] - b[1] * x1 * e
            }
            Rat42 => {
                let e = (b[1] - b[2] * x0).exp();
                let q = 1.0 + e;
                grad[0] = 1.0 / q;
                grad[1] = -b[0] * e / (q * q);
                grad[2] = b[0] * x0 * e / (q * q);
                b[0] / q
            }
            Rat43 => {
                let e = (b[1] - b[2] * x0).exp();
                let q = 1.0 + e;
                let qp = q.powf(-1.0 / b[3]);
                grad[0] = qp;
                grad[1] = -b[0] / b[3] * qp / q * e;
                grad[2] = b[0] / b[3] * qp / q * x0 * e;
                grad[3] = b[0] * qp * q.ln() / (b[3] * b[3]);
                b[0] * qp
            }
            Roszman1 => {
                let dx = x0 - b[3];
                let w = b[2] / dx;
                let da = 1.0 / (1.0 + w * w);
                grad[0] = 1.0;
                grad[1] = -x0;
                grad[2] = -da / (dx * PI);
                grad[3] = -da * b[2] / (dx * dx * PI);
                b[0] - b[1] * x0 - w.atan() / PI
            }
        }
    }
}

/// `(sum_{k<nn} b_k x^k) / (1 + sum_{k=1}^{nn-1} b_{nn+k-1} x^k)`.
fn rational(x: f64, b: &[f64], nn: usize, grad: &mut [f64]) -> f64 {
    let mut num = 0.0;
    let mut den = 1.0;
    let mut xp = 1.0;
    for k in 0..nn {
        num += b[k] * xp;
        if k > 0 {
            den += b[nn + k - 1] * xp;
        }
        xp *= x;
    }
    let f = num / den;
    let mut xp = 1.0;
    for k in 0..nn {
        grad[k] = xp / den;
        if k > 0 {
            grad[nn + k - 1] = -f * xp / den;
        }
        xp *= x;
    }
    f
}

/// A StRD problem: a model and its observations.
#[derive(Clone, Debug)]
pub struct StrdProblem {
    model: StrdModel,
    /// Predictors, `n_predictors` per observation, row after row.
    x: Vec<f64>,
    /// Responses (already `ln y` for Nelson).
    y: Vec<f64>,
}

impl StrdProblem {
    /// A problem from predictors (row after row) and responses `y` as they
    /// appear in the data file (Nelson's `y` is transformed to `ln y` here;
    /// `y <= 0` is then an error).
    pub fn new(model: StrdModel, x: Vec<f64>, y: Vec<f64>) -> Result<Self, SolveError> {
        let np = model.n_predictors();
        if x.len() != y.len() * np {
            return Err(SolveError::Dimension {
                what: "predictors vs responses",
                left: x.len(),
                right: y.len() * np,
            });
        }
        if y.is_empty() {
            return Err(SolveError::Empty {
                what: "observations",
            });
        }
        let y = if model.log_response() {
            y.iter()
                .map(|v| {
                    if *v > 0.0 {
                        Ok(v.ln())
                    } else {
                        Err(SolveError::InvalidOption {
                            name: "y",
                            value: *v,
                            reason: "log-response model needs y > 0",
                        })
                    }
                })
                .collect::<Result<Vec<_>, _>>()?
        } else {
            y
        };
        Ok(Self { model, x, y })
    }

    /// The model.
    pub fn model(&self) -> StrdModel {
        self.model
    }
}

impl LeastSquaresProblem for StrdProblem {
    fn n_params(&self) -> usize {
        self.model.n_params()
    }

    fn n_residuals(&self) -> usize {
        self.y.len()
    }

    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        let np = self.model.n_predictors();
        let mut g = [0.0; 9];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.model.eval(&self.x[i * np..(i + 1) * np], p, &mut g) - self.y[i];
        }
    }

    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        let np = self.model.n_predictors();
        let n = self.model.n_params();
        for i in 0..self.y.len() {
            self.model.eval(
                &self.x[i * np..(i + 1) * np],
                p,
                &mut jac[i * n..(i + 1) * n],
            );
        }
    }
}

/// Log relative error `-log10(|estimate - certified| / |certified|)`, capped
/// at 15 digits (an exact match) and floored at 0; `0` for a non-finite
/// estimate.
pub fn lre(estimate: f64, certified: f64) -> f64 {
    if !estimate.is_finite() {
        return 0.0;
    }
    let err = if certified == 0.0 {
        estimate.abs()
    } else {
        (estimate - certified).abs() / certified.abs()
    };
    if err == 0.0 {
        15.0
    } else {
        (-err.log10()).clamp(0.0, 15.0)
    }
}
