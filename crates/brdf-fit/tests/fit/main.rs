//! The integration tests of `brdf-fit`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod common;

mod appearance_threads;
mod blocked_pass;
mod colour_plane;
mod flip_polish;
mod inert_parameters;
mod irls_report;
mod objectives;
mod scaling;
mod select_coarse;
mod select_scale;
mod sgd_per_channel;
