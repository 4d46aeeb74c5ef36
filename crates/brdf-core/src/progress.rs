//! Progress of long work, as an observer the libraries report to and a
//! front end draws: the `brdf` command draws bars on stderr (indicatif),
//! Python and tests pass [`Silent`]. The libraries say what they do (a
//! task of so many items, the item now running, items done) and never
//! decide how it is shown.
//!
//! ```
//! use brdf_core::progress::{Progress, Silent};
//! let observer: &dyn Progress = &Silent;
//! let task = observer.task("fit", 3);
//! for item in ["a", "b", "c"] {
//!     task.item(item);
//!     task.advance(1);
//! }
//! task.finish();
//! ```

/// Whoever watches long work: a front end's progress display.
pub trait Progress: Send + Sync {
    /// A task of `total` items titled `what` (0 when the count is not yet
    /// known: set it with [`Task::set_total`]).
    fn task(&self, what: &str, total: usize) -> Box<dyn Task>;
}

/// One running task of a [`Progress`] observer; safe to advance from
/// several threads at once.
pub trait Task: Send + Sync {
    /// The number of items, once known.
    fn set_total(&self, total: usize);
    /// The item now running (shown beside the count).
    fn item(&self, current: &str);
    /// `n` more items done.
    fn advance(&self, n: usize);
    /// The task is over (its display is removed).
    fn finish(&self);
}

/// An observer that shows nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Progress for Silent {
    fn task(&self, _what: &str, _total: usize) -> Box<dyn Task> {
        Box::new(Silent)
    }
}

impl Task for Silent {
    fn set_total(&self, _total: usize) {}
    fn item(&self, _current: &str) {}
    fn advance(&self, _n: usize) {}
    fn finish(&self) {}
}
