//! # brdf-core
//!
//! The types and traits every other crate of the workspace builds on.
//!
//! ## Conventions
//!
//! Local shading frame: normal `N = +z`, tangent `+x`, bitangent `+y`. `L`
//! (`wi`) points towards the light, `V` (`wo`) towards the viewer, both away
//! from the surface. `H = (L + V)/|L + V|`. Values are reflectance in 1/sr, one
//! per channel. Below the horizon every model returns 0. See
//! `docs/conventions.md`.
//!
//! ## Catalogue
//!
//! | module | what |
//! | --- | --- |
//! | [`direction`] | `Direction` (a unit vector), spherical <-> Cartesian |
//! | [`format`](mod@format) | numbers with a fixed count of significant digits, as every table prints them |
//! | [`frame`] | orthonormal frames, world <-> local |
//! | [`trig`] | `cos_theta`, `tan2_theta`, `cos_phi`, ... as in pbrt |
//! | [`half_diff`] | the half vector; Rusinkiewicz angles both ways |
//! | [`brdf`] | the traits [`Brdf`] (evaluate) and [`Parametric`] (parameters, derivatives) |
//! | [`params`] | [`ParamSpec`], [`ParamError`], validation |
//! | [`samples`] | [`SampleSet`] in structure-of-arrays storage, filters |
//! | [`pair_geometry`] | [`PairGeometry`]: half-vector cosines of a sample set, computed once per fit |
//! | [`shared_basis`] | [`SharedBasis`]: models whose channels share one basis (block-diagonal fits) |
//! | [`weights`] | cosine weights, grid-cell and MERL-bin solid angles |
//! | [`metrics`] | Ngan L2, Sopp, Lafortune, log, RMS, relative RMS, PSNR |
//! | [`quadrature`] | adaptive Gauss-Kronrod, directional albedo |
//! | [`plausibility`] | reciprocity, non-negativity and energy scans |
//! | [`fresnel`] | Schlick and exact dielectric Fresnel terms |
//! | [`fresnel_conductor`] | exact conductor Fresnel (`eta + i k`) with derivatives |
//!
//! ## Crate features
//!
//! - `serde`: serialize sample sets, parameter specs and angles.
//!
//! ## Layering
//!
//! `brdf-core` is the bottom of the workspace: it depends on no other
//! crate of it. `brdf-models`, `brdf-solve`, `brdf-io` and `brdf-render`
//! build on it; everything above (`brdf-fit`, `brdf-export`, `brdf-study`,
//! the `brdf` command in `brdf-cli`, `brdf-py`) reaches it through them.

pub mod brdf;
pub mod direction;
pub mod error;
pub mod format;
pub mod frame;
pub mod fresnel;
pub mod fresnel_conductor;
pub mod half_diff;
pub mod metrics;
pub mod pair_geometry;
pub mod params;
pub mod plausibility;
pub mod progress;
pub mod quadrature;
pub mod samples;
pub mod shared_basis;
pub mod trig;
pub mod vmath;
pub mod weights;

pub use nalgebra;

pub use brdf::{Brdf, Parametric, central_difference_grad, fd_step};
pub use direction::{Direction, cartesian_to_spherical, spherical_to_cartesian};
pub use error::CoreError;
pub use frame::Frame;
pub use half_diff::{HalfDiff, half_vector};
pub use metrics::MetricValue;
pub use pair_geometry::PairGeometry;
pub use params::{ParamError, ParamSpec};
pub use quadrature::{Albedo, AlbedoFrame, QuadratureOptions, directional_albedo};
pub use samples::{DirPairs, FilterReport, PairChunk, SampleSet};
pub use shared_basis::SharedBasis;
