//! # brdf-io
//!
//! Readers and writers for the measured formats, each producing
//! [`brdf_core::SampleSet`]s and, where the format is dense, an evaluable
//! measured BRDF. Every reader returns an [`IoError`] naming the file and the
//! line or byte offset at fault; none panics on bad input, and none alters
//! data silently (invalid values are kept and counted, filters decide).
//!
//! | module | format | source | units | invalid marker |
//! | --- | --- | --- | --- | --- |
//! | [`curet`] | CUReT `abrdf.dat` + `table.txt` (and `r/g/bbrdf.dat`) | Dana et al. 1999 | 1/sr, radians | none (negative values are noise, kept) |
//! | [`nist`] | NIST StRD non-linear regression `.dat` | NIST ITL | - | - |

pub mod curet;
pub mod error;
pub mod nist;

pub use error::IoError;
