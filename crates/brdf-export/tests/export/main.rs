//! The integration tests of `brdf-export`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once. The renderers' answers they compare against live
//! in `tests/reference/`.

mod cases;

mod convert;
mod film_cycles;
mod front_end_texts;
mod gltf_mesh;
mod lobes;
mod mitsuba;
mod new_models;
mod paper_white;
mod render_check;
mod table;
mod targets;
