//! The `brdf` command's integration tests, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against the whole workspace, so one binary
//! builds the shared code once.

mod common;

mod appearance;
mod batch;
mod batch_kill;
mod cli_data;
mod cli_models;
mod export;
mod export_paper_white;
mod first_hour;
mod fit_command;
mod for_renderer;
mod hints;
mod messages;
mod readme;
mod render;
mod render_cache;
mod renderer_models;
mod report;
mod reproduce_partial_data;
mod reproduce_spec;
mod reproduce_synthetic;
mod smoke;
mod stability_cli;
