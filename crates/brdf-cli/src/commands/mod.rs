//! One module per subcommand: its clap arguments and a thin `run` that
//! calls the library crates. Commands import [`crate::opts`],
//! [`crate::output`] (the `say!` macros) and [`crate::error`], never
//! `cli` or `main`.

pub mod batch;
pub mod eval;
pub mod export;
pub mod fit;
pub mod info;
pub mod models;
pub mod nist;
pub mod render;
pub mod report;
pub mod reproduce;
pub mod resample;
pub mod select;
