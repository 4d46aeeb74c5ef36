//! Set-ups that depend on an image size alone, made once and shared while
//! anything holds them.
//!
//! The judge's shading terms at a size depend on nothing but the size (the
//! camera and light sets are fixed), yet `brdf select` and `brdf fit
//! --for` fit a model per candidate, and each candidate's appearance fit
//! builds a judge and image-objective terms at the fit size: on
//! cc_iris_purple_gem `--for mitsuba`, the nine candidates' terms were 6%
//! of its processor time (`perf`). [`BySize`] hands out the same terms to
//! every user alive at once; it keeps only weak references, so terms no one
//! holds are freed (a 128-px judge's terms are some hundred megabytes) and
//! made again on the next request.

use std::sync::{Arc, Mutex, Weak};

/// A value per size, shared while referenced (see the module doc).
pub struct BySize<T> {
    made: Mutex<Vec<(usize, Weak<T>)>>,
}

impl<T> BySize<T> {
    /// An empty memo, for a `static`.
    pub const fn new() -> Self {
        BySize {
            made: Mutex::new(Vec::new()),
        }
    }

    /// The value at `size`: the one some holder keeps alive, else made by
    /// `make`. `make` runs without the lock held (it may itself run in
    /// parallel on the thread pool, whose threads may ask for the same
    /// memo); two threads asking at once may both make it, and the first to
    /// finish is the one kept.
    pub fn get_or_make<E>(
        &self,
        size: usize,
        make: impl FnOnce() -> Result<T, E>,
    ) -> Result<Arc<T>, E> {
        if let Some(alive) = self.alive(size) {
            return Ok(alive);
        }
        let made = Arc::new(make()?);
        let mut list = self.made.lock().unwrap_or_else(|e| e.into_inner());
        list.retain(|(_, w)| w.strong_count() > 0);
        if let Some(alive) = list
            .iter()
            .find(|(s, _)| *s == size)
            .and_then(|(_, w)| w.upgrade())
        {
            return Ok(alive);
        }
        list.push((size, Arc::downgrade(&made)));
        Ok(made)
    }

    fn alive(&self, size: usize) -> Option<Arc<T>> {
        let list = self.made.lock().unwrap_or_else(|e| e.into_inner());
        list.iter()
            .find(|(s, _)| *s == size)
            .and_then(|(_, w)| w.upgrade())
    }
}

impl<T> Default for BySize<T> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use std::convert::Infallible;

    use super::*;

    #[test]
    fn a_value_is_shared_while_held_and_made_again_after() {
        let memo: BySize<Vec<usize>> = BySize::new();
        let made = std::cell::Cell::new(0);
        let make = |n: usize| {
            made.set(made.get() + 1);
            Ok::<_, Infallible>(vec![n; n])
        };
        let a = memo.get_or_make(4, || make(4)).expect("made");
        let b = memo.get_or_make(4, || make(4)).expect("made");
        assert!(Arc::ptr_eq(&a, &b));
        let c = memo.get_or_make(2, || make(2)).expect("made");
        assert_eq!(*c, vec![2, 2]);
        assert_eq!(made.get(), 2);
        drop((a, b));
        let d = memo.get_or_make(4, || make(4)).expect("made");
        assert_eq!(*d, vec![4; 4]);
        assert_eq!(made.get(), 3, "a value no one held is made again");
    }

    #[test]
    fn a_failed_make_is_not_kept() {
        let memo: BySize<usize> = BySize::new();
        assert_eq!(memo.get_or_make(1, || Err("no")), Err("no"));
        assert_eq!(memo.get_or_make(1, || Ok::<_, &str>(7)).map(|v| *v), Ok(7));
    }
}
