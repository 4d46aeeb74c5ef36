//! One module per subcommand.

pub mod eval;
pub mod fit;
pub mod info;
pub mod models;
pub mod nist;
pub mod reproduce;
pub mod resample;
pub mod select;
