//! Standard output for the commands: a closed pipe (`brdf info x | head`)
//! is an error ([`CliError::Io`] with kind `BrokenPipe`), not a panic as
//! with `println!`; `main` ends quietly and successfully on it.

use std::io::Write;

use crate::error::CliError;

/// Write `args` (and a newline) to standard output.
pub fn write_stdout(args: std::fmt::Arguments, newline: bool) -> Result<(), CliError> {
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
        .map_err(|source| CliError::Io {
            path: "standard output".into(),
            source,
        })
}

/// `println!` through [`write_stdout`]: evaluates to a `Result`.
macro_rules! say {
    ($($t:tt)*) => {
        $crate::output::write_stdout(format_args!($($t)*), true)
    };
}

/// `print!` through [`write_stdout`]: evaluates to a `Result`.
macro_rules! say_raw {
    ($($t:tt)*) => {
        $crate::output::write_stdout(format_args!($($t)*), false)
    };
}
