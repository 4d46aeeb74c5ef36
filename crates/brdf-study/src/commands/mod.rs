//! One module per subcommand, and the output helpers they share.

use std::io::Write;

use crate::StudyError;

/// Write to standard output; a closed pipe (`brdf info x | head`) is an
/// error ([`StudyError::Io`] with kind `BrokenPipe`), not a panic as with
/// `println!`. `main` ends quietly and successfully on it.
pub(crate) fn write_stdout(args: std::fmt::Arguments, newline: bool) -> Result<(), StudyError> {
    let mut out = std::io::stdout().lock();
    out.write_fmt(args)
        .and_then(|()| {
            if newline {
                out.write_all(b"\n")
            } else {
                Ok(())
            }
        })
        .and_then(|()| out.flush())
        .map_err(|source| StudyError::Io {
            path: "standard output".into(),
            source,
        })
}

/// `println!` through [`write_stdout`]: evaluates to a `Result`. Defined
/// before the subcommand modules, so it is in scope in all of them.
macro_rules! say {
    ($($t:tt)*) => {
        $crate::commands::write_stdout(format_args!($($t)*), true)
    };
}

/// `print!` through [`write_stdout`]: evaluates to a `Result`.
macro_rules! say_raw {
    ($($t:tt)*) => {
        $crate::commands::write_stdout(format_args!($($t)*), false)
    };
}

pub mod batch;
pub mod eval;
pub mod export;
pub mod fit;
pub mod info;
pub mod models;
pub mod nist;
pub mod reproduce;
pub mod resample;
pub mod select;
