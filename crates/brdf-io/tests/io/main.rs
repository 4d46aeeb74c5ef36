//! The integration tests of `brdf-io`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod common;

mod csv_weights;
mod curet;
mod curet_directions;
mod did_you_mean;
mod formats;
mod fuzz;
mod materials;
mod merl_independent;
mod nist;
mod rgl;
mod rgl_mitsuba;
mod rgl_tabulated;
mod sopp_grid_nodes;
