//! # brdf-study
//!
//! The reproduction of the Kurt (2007) and Sopp (2017) theses as a
//! library: every table, figure and stability check `brdf reproduce`
//! writes into `results/`, with the NIST StRD certification of the solver.
//!
//! ## Layering
//!
//! `brdf-study` sits on top: it fits with `brdf-fit`, renders with
//! `brdf-render` and reads data with `brdf-io`; only the `brdf` command (`brdf-cli`) and the benchmarks
//! build on it. Inside, the modules import downwards only:
//!
//! - [`reproduce`] runs a selection and writes the README ([`readme`]);
//! - [`parts`] is the list of named parts and knows every part;
//! - the parts ([`kurt`], [`figures`], [`dense_tables`], [`sopp_tables`],
//!   [`nist`], [`stability`], ...) know only the shared [`context`]
//!   ([`context::Study`]), never the list;
//! - [`context`] imports no part.
//!
//! `.ci/module_cycles.py` checks that no module imports one that imports
//! it back.

pub mod bias;
pub mod context;
pub mod dense_tables;
pub mod error;
pub mod figures;
pub mod kurt;
pub mod new_models;
pub mod nist;
pub mod parts;
pub mod readme;
pub mod renderer_fits;
pub mod renderer_spheres;
pub mod report;
pub mod reproduce;
pub mod sopp_tables;
pub mod stability;
pub mod synthetic;
#[cfg(test)]
mod test_support;

pub use error::StudyError;

pub use brdf_io::load as data;
pub use brdf_models::saved_model;
