//! The error type of `brdf-core`.

use thiserror::Error;

/// Everything that can go wrong when building core values from user input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CoreError {
    /// A direction was zero, not finite, or otherwise unusable.
    #[error("invalid direction ({x}, {y}, {z}): {reason}")]
    InvalidDirection {
        /// x component as given
        x: f64,
        /// y component as given
        y: f64,
        /// z component as given
        z: f64,
        /// what is wrong with it
        reason: &'static str,
    },
    /// Spherical angles were not finite.
    #[error("invalid spherical angles theta = {theta}, phi = {phi}: {reason}")]
    InvalidAngles {
        /// polar angle (radians)
        theta: f64,
        /// azimuth (radians)
        phi: f64,
        /// what is wrong with them
        reason: &'static str,
    },
    /// A sample had the wrong number of channel values.
    #[error("sample set `{set}`: sample {index} has {got} channel values, expected {expected}")]
    ChannelCount {
        /// name of the sample set
        set: String,
        /// index of the offending sample
        index: usize,
        /// number of channels of the set
        expected: usize,
        /// number of values supplied
        got: usize,
    },
    /// A weight was negative or not finite.
    #[error(
        "sample set `{set}`: weight of sample {index} is {weight}; weights must be finite and >= 0"
    )]
    InvalidWeight {
        /// name of the sample set
        set: String,
        /// index of the offending sample
        index: usize,
        /// the weight supplied
        weight: f64,
    },
    /// Two arrays that must have the same length did not.
    #[error("length mismatch in {what}: {left} vs {right}")]
    LengthMismatch {
        /// what was being compared
        what: &'static str,
        /// first length
        left: usize,
        /// second length
        right: usize,
    },
    /// An operation needs at least one sample (or one pixel, one node).
    #[error("{what} is empty")]
    Empty {
        /// what was empty
        what: &'static str,
    },
    /// An option was outside its allowed range.
    #[error("invalid option `{name}` = {value}: {reason}")]
    InvalidOption {
        /// option name
        name: &'static str,
        /// value given
        value: f64,
        /// allowed range or reason
        reason: &'static str,
    },
}
