//! # brdf-render
//!
//! Pictures of reflectance: anything that evaluates as a
//! [`brdf_core::Brdf`] (a model, a saved fit, measured data that can be
//! evaluated at arbitrary direction pairs) rendered on a sphere, and the
//! means to compare, label and write those pictures.
//!
//! - [`sphere`]: a unit sphere under a directional light (the study's
//!   figures and the CLI's `render`);
//! - [`Image`]: linear radiance, PNG output after an exposure stated by the
//!   caller;
//! - [`grid`]: labelled grids of tiles (tone mapped with their exposure
//!   written beside them, difference tiles on a colour bar);
//! - [`plot`]: line and scatter plots (SVG and PNG) with the bundled font.
//!
//! ## Layering
//!
//! `brdf-render` depends on `brdf-core` only: it never fits and never reads
//! data files. `brdf-fit` (image errors of a fit), `brdf-study` (figures),
//! the `brdf` command and the Python module call it.

pub mod error;
pub mod grid;
pub mod image;
pub mod number;
pub mod plot;
pub mod side_by_side;
pub mod sphere;

pub use error::RenderError;
pub use image::Image;
pub use number::fmt_sig;
pub use sphere::render_sphere;
