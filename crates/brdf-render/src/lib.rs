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
//! The appearance judge (`docs/appearance.md`): a unit sphere seen by
//! a perspective camera under named light sets, compared by image metrics.
//!
//! - [`camera`], [`scene`]: the judge camera and the pixels that see the
//!   sphere (point, shading frame, view direction);
//! - [`quadrature`], [`environment`], [`area_light`], [`sky`], [`light`]:
//!   light sets (`directional`, `sky`, `studio`) as weighted incident
//!   directions;
//! - [`shading`]: [`ShadingPoints`], the precomputed `(pixel, l, v, weight)`
//!   terms of a scene; [`batch`]: the render of any BRDF from them, a row
//!   of terms per batch evaluation;
//! - [`film`]: Mitsuba's film (antialiased silhouette, Gaussian pixel
//!   filter) for pictures compared with the judge's;
//! - [`tonemap`], [`openexr`]: exposure `1 / p99`, gamma 2.2, PNG and EXR;
//! - [`flip`], [`psnr`], [`colour`]: LDR- and HDR-FLIP (NVIDIA's FLIP through
//!   `nv-flip`), PSNR, mean colour and CIEDE2000 (through `palette`);
//! - [`colour_plane`](mod@colour_plane): how far an image's colours lie from
//!   every plane of white and one colour, a bound on what a renderer model
//!   with one base colour can match;
//! - [`image_error`]: the image errors of a fit per light set and over the
//!   judge's light sets, and their warnings;
//! - [`reference`](mod@reference): the data's render made once, and tests compared with it;
//! - [`judge`]: [`Judge`], the data and fits rendered under the standard
//!   light sets and compared;
//! - [`compare`](mod@compare): all metrics of a test BRDF against a reference.
//!
//! ## Layering
//!
//! `brdf-render` depends on `brdf-core` only: it never fits and never reads
//! data files. `brdf-fit` (image errors of a fit), `brdf-study` (figures),
//! the `brdf` command and the Python module call it.

pub mod area_light;
pub mod batch;
pub mod by_size;
pub mod camera;
pub mod colour;
pub mod colour_plane;
pub mod compare;
pub mod environment;
pub mod error;
pub mod film;
pub mod flip;
pub mod grid;
pub mod image;
pub mod image_error;
pub mod judge;
pub mod light;
pub mod openexr;
pub mod plot;
pub mod psnr;
pub mod quadrature;
pub mod reference;
pub mod scene;
pub mod shading;
pub mod side_by_side;
pub mod sky;
pub mod sphere;
pub mod tonemap;

pub use compare::compare;
pub use error::RenderError;
pub use image::Image;
pub use image_error::{ImageError, LightError};
pub use judge::Judge;
pub use light::LightSet;
pub use shading::ShadingPoints;
pub use sphere::render_sphere;
