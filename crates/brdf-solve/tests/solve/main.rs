//! The integration tests of `brdf-solve`, one module per concern, in one
//! test binary: Cargo makes every file under `tests/` a crate of its own,
//! each compiled and linked against its dependencies, so one binary builds
//! the shared code once.

mod irls;
mod levenberg_marquardt;
mod linear;
mod nnls;
mod robust_weights;
mod stability;
mod strd;
mod strd_formulas;
mod tall_qr;
mod varpro;
