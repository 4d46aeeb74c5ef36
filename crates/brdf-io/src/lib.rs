//! # brdf-io
//!
//! Readers and writers for the measured formats, each producing
//! [`brdf_core::SampleSet`]s and, where the format is dense, an evaluable
//! measured BRDF. Every reader returns an [`IoError`] naming the file and the
//! line or byte offset at fault; none panics on bad input, and none alters
//! data silently (invalid values are kept and counted, filters decide).
//!
//! | module | format | source | units | invalid marker |
//! | --- | --- | --- | --- | --- |
//! | [`curet`] | CUReT `abrdf.dat` + `table.txt` (and `r/g/bbrdf.dat`) | Dana et al. 1999 | 1/sr, radians | none (negative values are noise, kept) |
//! | [`cornell`] | Cornell `.brdf` (31 spectral samples) to linear sRGB / Y via [`colour`] | Cornell PCG | 1/sr, radians | none |
//! | [`merl`] | MERL `.binary` (read, write, lookup, resample, bin weights) | Matusik et al. 2003 | 1/sr after channel scales | negative bins |
//! | [`sopp_grid`] | Sopp's goniometric grid (resample, CSV, cell weights) | Sopp 2017 | 1/sr, degrees | none |
//! | [`csv_samples`] | generic CSV samples in and out | users | 1/sr, radians | NaN values kept, counted by filters |
//! | [`rgl`] | RGL `.bsdf` tensor files, evaluated through the inverse VNDF warp | Dupuy & Jakob 2018 | 1/sr | out-of-gamut values clamped at 0 (as the authors) |
//! | [`rgl_tabulated`] | any BRDF written as an RGL `.bsdf` on a measurement's own grid (for Mitsuba 3's `measured` plugin) | - | 1/sr | - |
//! | [`nist`] | NIST StRD non-linear regression `.dat` | NIST ITL | - | - |
//!
//! [`load`](fn@load) detects the format by name (`PATH` or `PATH#SAMPLE`, see
//! [`load::Format`]) and returns the sample set; [`load_dense`] gives an
//! evaluable BRDF for the dense formats (MERL, RGL); [`materials`](fn@materials)
//! lists the data sets a folder or a CUReT file stands for; [`describe`](mod@describe)
//! says what a data file holds (`brdf info`).
//!
//! ## Layering
//!
//! `brdf-io` depends on `brdf-core` only: it reads and writes data and
//! knows no model. `brdf-fit` (which loads what it fits), `brdf-study`,
//! the `brdf` command (`brdf-cli`) and the Python module build on it.
//!
//! ```no_run
//! let samples = brdf_io::load("curet/abrdf.dat#25")?;
//! println!("{} samples, {} channels", samples.len(), samples.channels());
//! # Ok::<(), brdf_io::IoError>(())
//! ```

pub mod colour;
pub mod cornell;
pub mod csv_samples;
pub mod curet;
pub mod describe;
pub mod error;
pub mod load;
pub mod materials;
pub mod merl;
pub mod nist;
pub mod rgl;
pub mod rgl_tabulated;
pub mod sopp_grid;

pub use error::IoError;
pub use load::{Format, format_of, load, load_dense, split_sample};
pub use materials::materials;
