//! # brdf-fit
//!
//! Fit any analytic BRDF model of [`brdf_models`] to any measured data set
//! that [`brdf_io`] reads, with no hand-picked start values: the linear
//! parameters (`kd`, `ks` per channel) are projected out (variable
//! projection), the bounded solver of [`brdf_solve`] optimises the rest
//! from deterministic multi-starts, and the result is polished on every
//! parameter inside its box. Then select the smallest adequate model, and
//! save the fit in the versioned schema of
//! [`brdf_models::saved_model`], which a renderer loads with only
//! `brdf-models` compiled.
//!
//! ## Quick start
//!
//! ```no_run
//! use brdf_fit::{Channels, Fit, Objective};
//! use brdf_models::saved_model::SavedModel;
//! // Any format brdf-io detects: CUReT `abrdf.dat#N`, Cornell, RGL, MERL, CSV.
//! let samples = brdf_io::load("rgl/paper_white_rgb.bsdf")?;
//! let report = Fit::model("Ashikhmin-Shirley")?     // forgiving names
//!     .objective(Objective::Ngan)
//!     .limit_deg(80.0)
//!     .channels(Channels::All)                    // RGB: shared lobe, per-channel kd, ks
//!     .starts(12)
//!     .run(&samples)?;
//! for p in &report.summary.parameters {
//!     println!("{} = {} {:?}", p.name, p.value, p.at_bound);
//! }
//! report.saved_model("rgl/paper_white_rgb.bsdf")?.save("paper.json".as_ref())?;
//! let model = SavedModel::load_model("paper.json".as_ref())?; // a brdf_core::Brdf
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! | module | what |
//! | --- | --- |
//! | [`appearance`] | the fit chosen by its image errors (candidates, lobes, refinement) |
//! | [`judged`] | fits and selections as front ends run them, judged at the report size |
//! | [`select_by_image`] | renderer models chosen among by image error |
//! | [`isotropy`] | whether data are isotropic |
//! | [`builder`] | [`Fit`] (the builder) and [`FitReport`] |
//! | [`pipeline`] | the automatic fit's dispatch, Sopp's two stages |
//! | [`objective`] | the objectives: row scalings, transforms, their errors |
//! | [`transformed_rows`] | a transformed objective's residual as a row transform |
//! | [`options`] | [`Solver`] and [`FitOptions`] |
//! | [`param_box`] | a model's parameter box as solver constraints |
//! | [`starts`] | multi-start boxes, coarse and screened starts, subsamples |
//! | [`linear`] | all-linear models by (non-negative) least squares or IRLS |
//! | [`nonlinear`] | the multi-start non-linear fit and its polish |
//! | [`summary`] | [`FitSummary`]: what a fit reports |
//! | [`termination`] | [`Termination`]: why a fit stopped, typed, in today's words |
//! | [`flip_polish`] | on request, an appearance fit's last step: compass search on the judge's mean FLIP |
//! | [`image_objective`] | the image objective: residuals of tone-mapped sphere pixels |
//! | [`boxed`] | [`BoxedModel`]: a model fitted in other parameter boxes than its own |
//! | [`scaling`] | internal scaling of extreme data and weights (scale invariance) |
//! | [`select`] | the smallest adequate model, AIC/BIC, the error-vs-size curve |
//! | [`linear_box`] | linear least squares within `[0, upper]` when NNLS exceeds an upper bound |
//! | [`names`] | forgiving model names with suggestions |
//! | [`report_json`] | the JSON report of `brdf fit --json`, data names for outputs |
//! | [`report_text`] | the readable report of `brdf fit`, parameters a fit leaves undetermined |
//! | [`table`] | report tables written as CSV and Markdown |
//! | [`batch`] | the resumable, shardable batch runner of `brdf batch` (`fits.jsonl`, summaries, merge) |
//! | [`resample`] | data or a saved model written as MERL, Sopp's grid or CSV samples |
//! | [`error`] | [`FitError`] |
//!
//! ## Layering
//!
//! `brdf-fit` sits on `brdf-core`, `brdf-models`, `brdf-solve` and
//! `brdf-io` (and on `brdf-render` for the judge of image errors and the number
//! format of its report tables). `brdf-export` (conversion by fitting), `brdf-study` (the
//! reproduction), the `brdf` command (`brdf-cli`) and the Python module
//! (`brdf-py`) build on it.

pub mod appearance;
pub mod batch;
pub mod boxed;
pub mod builder;
pub mod error;
pub mod flip_polish;
pub mod hints;
pub mod image_objective;
pub mod isotropy;
pub mod judged;
pub mod linear;
pub mod linear_box;
pub mod material;
pub mod names;
pub mod nonlinear;
pub mod objective;
pub mod options;
pub mod param_box;
pub mod pipeline;
pub mod render_cache;
pub mod report_json;
pub mod report_text;
pub mod request;
pub mod resample;
pub mod scaling;
pub mod select;
pub mod select_by_image;
pub mod select_request;
pub mod starts;
pub mod summary;
pub mod table;
pub mod termination;
pub mod transformed_rows;

pub use boxed::BoxedModel;
pub use builder::{Channels, Fit, FitReport};
pub use error::FitError;
pub use material::Material;
pub use names::resolve;
pub use objective::Objective;
pub use options::{FitOptions, Solver};
pub use report_json::{data_name, fit_json, select_by_image_json, select_json};
pub use request::{ChannelMode, FitOutcome, FitRequest, Metric};
pub use select_request::{SelectBy, SelectOutcome, SelectRequest};
pub use summary::{FitSummary, FittedParam};
pub use termination::Termination;
