//! Progress bars for the commands that can run longer than a few seconds:
//! indicatif on stderr with items done, the current item and an estimate;
//! hidden with `--quiet` or when stderr is not a terminal (logs and
//! captured output stay clean).

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar of `len` items titled `what`; hidden when `quiet` or when stderr
/// is not a terminal. Set the current item with `set_message`.
pub fn bar(len: usize, what: &str, quiet: bool) -> ProgressBar {
    let target = if !quiet && std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(len as u64), target);
    if let Ok(style) = ProgressStyle::with_template(
        "{prefix} [{bar:30}] {pos}/{len} {elapsed} (eta {eta}) {wide_msg}",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix(what.to_string());
    bar
}
