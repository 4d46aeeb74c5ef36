//! The integration tests of `brdf-core`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod finite_difference;
mod half_diff;
mod metric_scale;
mod quadrature;
mod samples;
mod vmath;
mod weights_metrics;
