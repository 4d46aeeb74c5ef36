//! Tables written by the study: CSV (machine-readable) and Markdown
//! (readable, with the thesis value beside the project's where there is
//! one), and the names and numbers they print.

// The tables live in brdf-fit (the batch summary and `brdf select` write
// them too); the study uses them under the names it always has.
/// The workspace's one number formatter ([`brdf_core::format::number`]),
/// by the name `new_models` imports it under.
pub use brdf_fit::table::{Cell, Table};

pub use brdf_fit::data_name;
