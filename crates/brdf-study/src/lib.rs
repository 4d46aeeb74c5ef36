//! # brdf-study
//!
//! The `brdf` command line and the study it runs: fitting, evaluation,
//! rendering, and the reproduction of the Kurt (2007) and Sopp (2017) tables
//! into `results/`. The binary (`src/main.rs`) parses the command line; the
//! modules here do the work and are usable from tests.
//!
//! ## Crate features
//!
//! - `plots` (default): SVG plots of the figures through plotters.

pub mod bias;
pub mod cli;
pub mod commands;
pub mod data;
pub mod dense_tables;
pub mod error;
pub mod fit;
pub mod kurt_tables;
pub mod nist;
pub mod pipeline;
#[cfg(feature = "plots")]
pub mod plots;
pub mod render;
pub mod report;
pub mod saved_model;
pub mod select;
pub mod sopp_tables;
pub mod synthetic;

pub use error::StudyError;
