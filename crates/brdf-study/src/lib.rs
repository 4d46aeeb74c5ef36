//! # brdf-study
//!
//! The `brdf` command line and the study it runs: fitting, evaluation,
//! rendering, and the reproduction of the Kurt (2007) and Sopp (2017) tables
//! into `results/`. The binary (`src/main.rs`) parses the command line; the
//! modules here do the work and are usable from tests.

pub mod bias;
pub mod cli;
pub mod commands;
pub mod dense_tables;
pub mod error;
pub mod figures;
pub mod kurt;
pub mod nist;
pub mod renderer_fits;
pub mod renderer_spheres;
pub mod report;
pub mod sopp_tables;
pub mod stability;
pub mod study;
pub mod synthetic;
#[cfg(test)]
mod test_support;

pub use error::StudyError;

// The fitting library, re-exported under the paths the study and its tests
// have always used.
pub use brdf_fit::{fit_linear as fit, pipeline, select};
pub use brdf_io::load as data;
pub use brdf_models::saved_model;
