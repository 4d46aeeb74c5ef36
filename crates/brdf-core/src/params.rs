//! Named, boxed, flagged parameter vectors.
//!
//! Every model describes its parameters with [`ParamSpec`]s: a name (as in the
//! docs and on the command line), a meaning, the default box the fitters use,
//! whether the parameter enters the model linearly (`kd`, `ks`, per-channel
//! colours, Koenderink and polynomial coefficients), and a default value.
//! Solvers, variable projection, bound reporting and the writers work on these
//! descriptions, never on a named model.

use thiserror::Error;

/// Description of one model parameter.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ParamSpec {
    /// Name as in the docs and on the command line (`kd`, `ks_g`, `n`, `a`).
    pub name: String,
    /// One-line meaning.
    pub meaning: String,
    /// Lower end of the default box.
    pub lower: f64,
    /// Upper end of the default box.
    pub upper: f64,
    /// True when the lower end is excluded (`a in (0, 0.5]`).
    pub lower_open: bool,
    /// True when the model is linear in this parameter.
    pub linear: bool,
    /// A sensible value inside the box (used by `brdf eval` and as a start).
    pub default: f64,
}

impl ParamSpec {
    /// A parameter with a closed box `[lower, upper]`.
    pub fn new(
        name: impl Into<String>,
        meaning: impl Into<String>,
        lower: f64,
        upper: f64,
        default: f64,
        linear: bool,
    ) -> Self {
        ParamSpec {
            name: name.into(),
            meaning: meaning.into(),
            lower,
            upper,
            lower_open: false,
            linear,
            default,
        }
    }

    /// The same parameter with an open lower end `(lower, upper]`.
    pub fn open_below(mut self) -> Self {
        self.lower_open = true;
        self
    }

    /// Whether `value` lies in the box.
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.lower_open {
            value > self.lower
        } else {
            value >= self.lower
        };
        above && value <= self.upper
    }

    /// The box written as in the docs: `[0, 1]` or `(0, 0.5]`.
    pub fn box_string(&self) -> String {
        format!(
            "{}{}, {}]",
            if self.lower_open { '(' } else { '[' },
            self.lower,
            self.upper
        )
    }
}

/// Errors when setting or parsing parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParamError {
    /// A value lies outside its box.
    #[error("parameter `{name}` = {} is outside its box {bounds}", compact(.value))]
    OutOfBounds {
        /// parameter name
        name: String,
        /// value given
        value: f64,
        /// the box, as `[lo, hi]` or `(lo, hi]`
        bounds: String,
    },
    /// A value is NaN or infinite.
    #[error("parameter `{name}` is not finite ({value})")]
    NotFinite {
        /// parameter name
        name: String,
        /// value given
        value: f64,
    },
    /// The parameter vector has the wrong length.
    #[error("model `{model}` takes {expected} parameters, got {got}")]
    WrongCount {
        /// model name
        model: String,
        /// parameters the model has
        expected: usize,
        /// parameters supplied
        got: usize,
    },
    /// A name that the model does not have.
    #[error("model `{model}` has no parameter `{name}` (it has: {known})")]
    Unknown {
        /// model name
        model: String,
        /// the unknown name
        name: String,
        /// comma-separated list of the model's parameter names
        known: String,
    },
    /// A structural option (channels, lobes, order) is impossible.
    #[error("model `{model}`: {reason}")]
    Config {
        /// model name
        model: String,
        /// what is wrong
        reason: String,
    },
    /// A model read off its data (Dupuy's normal distribution) cannot be
    /// built from this data set: it lacks the samples the model reads.
    #[error("{data}: model `{model}` cannot be built from it: {reason}; {fix}")]
    Data {
        /// model name
        model: String,
        /// the data set (its file where known)
        data: String,
        /// what the data set lacks
        reason: String,
        /// what to do instead
        fix: String,
    },
}

/// A value for a one-line message: as written for ordinary magnitudes
/// (`1.5`, `2`), in exponent form outside `[1e-5, 1e16)` (`{}` of `1e300`
/// would print 301 digits).
fn compact(x: &f64) -> String {
    let a = x.abs();
    if *x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Check `values` against `specs`: length, finiteness, boxes.
pub fn validate(model: &str, specs: &[ParamSpec], values: &[f64]) -> Result<(), ParamError> {
    if specs.len() != values.len() {
        return Err(ParamError::WrongCount {
            model: model.to_string(),
            expected: specs.len(),
            got: values.len(),
        });
    }
    for (s, &v) in specs.iter().zip(values) {
        if !v.is_finite() {
            return Err(ParamError::NotFinite {
                name: s.name.clone(),
                value: v,
            });
        }
        if !s.contains(v) {
            return Err(ParamError::OutOfBounds {
                name: s.name.clone(),
                value: v,
                bounds: s.box_string(),
            });
        }
    }
    Ok(())
}

/// Build a full parameter vector from defaults overridden by `name=value`
/// assignments; unknown names are an error naming the known ones.
pub fn assign_by_name(
    model: &str,
    specs: &[ParamSpec],
    assignments: &[(String, f64)],
) -> Result<Vec<f64>, ParamError> {
    let mut values: Vec<f64> = specs.iter().map(|s| s.default).collect();
    for (name, value) in assignments {
        match specs.iter().position(|s| &s.name == name) {
            Some(i) => values[i] = *value,
            None => {
                return Err(ParamError::Unknown {
                    model: model.to_string(),
                    name: name.clone(),
                    known: specs
                        .iter()
                        .map(|s| s.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                });
            }
        }
    }
    validate(model, specs, &values)?;
    Ok(values)
}

/// Name of a per-channel parameter: `kd` for one channel, `kd_r`, `kd_g`,
/// `kd_b` for three, `kd_0`, `kd_1`, ... otherwise.
pub fn channel_param_name(base: &str, channel: usize, channels: usize) -> String {
    match channels {
        1 => base.to_string(),
        3 => format!("{base}_{}", ["r", "g", "b"][channel]),
        _ => format!("{base}_{channel}"),
    }
}

/// One [`ParamSpec`] per channel for a linear colour parameter such as `kd`.
pub fn per_channel_specs(
    base: &str,
    meaning: &str,
    channels: usize,
    lower: f64,
    upper: f64,
    default: f64,
) -> Vec<ParamSpec> {
    (0..channels)
        .map(|c| {
            ParamSpec::new(
                channel_param_name(base, c, channels),
                format!("{meaning} (channel {c})"),
                lower,
                upper,
                default,
                true,
            )
        })
        .collect()
}
