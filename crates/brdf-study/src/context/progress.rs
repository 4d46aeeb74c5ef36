//! Progress of the study's long loops, reported to the observer the caller
//! of [`crate::reproduce::run`] hands over ([`crate::reproduce::Reproduce`]'s
//! `progress`); silent until one is installed. The study's parts run deep
//! below the call that names the observer, so it is kept here for the run
//! rather than threaded through every table's function.

use std::sync::{Arc, RwLock};

use brdf_core::progress::{Progress, Silent, Task};

static OBSERVER: RwLock<Option<Arc<dyn Progress>>> = RwLock::new(None);

/// Report the study's progress to `observer` from now on.
pub fn set_observer(observer: Arc<dyn Progress>) {
    if let Ok(mut slot) = OBSERVER.write() {
        *slot = Some(observer);
    }
}

/// A task of `len` items titled `what`, on the installed observer.
pub fn bar(len: usize, what: &str) -> Bar {
    let observer = OBSERVER.read().ok().and_then(|slot| slot.clone());
    Bar(match observer {
        Some(o) => o.task(what, len),
        None => Silent.task(what, len),
    })
}

/// One task of the study: items done and the item running.
pub struct Bar(Box<dyn Task>);

impl Bar {
    /// `n` more items done.
    pub fn inc(&self, n: u64) {
        self.0.advance(n as usize);
    }

    /// The item now running.
    pub fn set_message(&self, current: impl AsRef<str>) {
        self.0.item(current.as_ref());
    }

    /// The task is over.
    pub fn finish_and_clear(&self) {
        self.0.finish();
    }
}
