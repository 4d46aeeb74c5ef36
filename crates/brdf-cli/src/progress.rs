//! The command's progress display: the libraries' [`Progress`] observer
//! drawn as indicatif bars on stderr, with items done, the item running
//! (the bar's message), the elapsed time and an estimate. Bars are drawn
//! only when stderr is a terminal and `--quiet` was not given, so logs and
//! captured output stay clean.

use std::io::IsTerminal;
use std::time::Duration;

use brdf_core::progress::{Progress, Task};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Bars on stderr, or none when `quiet`.
#[derive(Clone, Copy, Debug)]
pub struct Bars {
    quiet: bool,
}

impl Bars {
    /// Bars unless `quiet` (or stderr is not a terminal).
    pub fn new(quiet: bool) -> Self {
        Bars { quiet }
    }
}

impl Progress for Bars {
    fn task(&self, what: &str, total: usize) -> Box<dyn Task> {
        let target = if !self.quiet && std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        let bar = ProgressBar::with_draw_target(Some(total as u64), target);
        if let Ok(style) = ProgressStyle::with_template(
            "{prefix:>12} [{bar:30}] {pos}/{len} {elapsed} (eta {eta}) {wide_msg}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix(what.to_string());
        // The elapsed time moves even while one long item runs.
        bar.enable_steady_tick(Duration::from_millis(250));
        Box::new(Bar(bar))
    }
}

/// One task's bar.
struct Bar(ProgressBar);

impl Task for Bar {
    fn set_total(&self, total: usize) {
        self.0.set_length(total as u64);
    }
    fn item(&self, current: &str) {
        self.0.set_message(current.to_string());
    }
    fn advance(&self, n: usize) {
        self.0.inc(n as u64);
    }
    fn finish(&self) {
        self.0.finish_and_clear();
    }
}
