//! One module per subcommand.

pub mod eval;
pub mod fit;
pub mod models;
pub mod nist;
pub mod reproduce;
pub mod select;
