//! The integration tests of `brdf-models`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod strategies;

mod aliases;
mod coloured_lobes;
mod dupuy;
mod energy;
mod extremes;
mod gltf_iridescence;
mod koenderink;
mod kurt_polynomial;
mod lambert;
mod new_models;
mod properties;
mod reciprocity;
mod reference;
mod renderer_models;
mod shared_basis;
mod sopp_and_oren_nayar;
mod stability_extremes;
mod thin_film_reference;
