//! Progress bars for every long loop, the study's and the `brdf`
//! command's (`fit`, `select`, `batch`, `report`, `reproduce`): indicatif
//! on stderr with items done, the current item (the bar's message) and an
//! estimate; drawn only when stderr is a terminal and `--quiet` was not
//! given ([`set_quiet`]), so logs and captured output stay clean.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

static QUIET: AtomicBool = AtomicBool::new(false);

/// Hide every bar made after this call (`--quiet`).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// A bar of `len` steps titled `what`; hidden when quiet or when stderr is
/// not a terminal. Set the current item with `set_message`.
pub fn bar(len: usize, what: &str) -> ProgressBar {
    let target = if !QUIET.load(Ordering::Relaxed) && std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(len as u64), target);
    if let Ok(style) = ProgressStyle::with_template(
        "{prefix:>12} [{bar:30}] {pos}/{len} {elapsed} (eta {eta}) {wide_msg}",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix(what.to_string());
    // The elapsed time moves even while one long item runs.
    bar.enable_steady_tick(Duration::from_millis(250));
    bar
}
