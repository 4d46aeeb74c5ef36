//! # brdf-report
//!
//! A fit report people would rather look at than read: one self-contained
//! HTML file per fit (no network: images are `data:` URIs, plots inline
//! SVG), in the manner of Disney's BRDF Explorer, and an index page for a
//! batch of fits.
//!
//! - [`fit_page`](mod@fit_page): header (material, data, samples, model, objective,
//!   solver, time, termination, parameters with standard errors and bound
//!   marks), polar incidence-plane slices, the data's coverage, sphere
//!   renders (measured | fitted | FLIP) with image errors, the selection
//!   ([`select_plot`]: plots and a table by L2 or by image error) and a
//!   plain-words [`verdict`];
//! - [`batch_page`]: the index of `DIR/fits.jsonl`, sortable, with
//!   thumbnails and one linked fit page per row;
//! - [`polar`], [`coverage`], [`spheres`], [`embed`]: the pictures.
//!
//! The HTML comes from the `minijinja` templates in `templates/`
//! (compiled in), never from concatenated strings.

pub mod batch_page;
pub mod coverage;
pub mod embed;
pub mod error;
pub mod fit_page;
pub mod polar;
pub mod select_plot;
pub mod spheres;
mod templates;
pub mod verdict;

pub use batch_page::{BatchReport, write_batch_report};
pub use error::ReportError;
pub use fit_page::{
    Analyser, FitInput, RunInfo, fit_page, fit_page_with, write_fit_page, write_fit_page_with,
};
