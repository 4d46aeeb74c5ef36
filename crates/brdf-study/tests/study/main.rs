//! The integration tests of `brdf-study`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod common;

mod dupuy_fit;
mod fit_linear;
mod nist;
mod pipeline;
mod polynomial;
mod select;
mod stability_report;
