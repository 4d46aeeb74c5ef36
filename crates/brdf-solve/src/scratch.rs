//! Reusable scratch buffers for problems shared between threads.
//!
//! A fit evaluates its model hundreds of times on the same sample set;
//! allocating fresh zeroed buffers of millions of entries per pass costs page
//! faults and system time that rival the arithmetic. A [`ScratchPool`] hands
//! out buffers that earlier passes returned, so a problem that is shared by
//! the parallel starts of a multi-start (`&self`, `Sync`) still allocates
//! each buffer once per thread.

use std::sync::Mutex;

/// A pool of `f64` buffers.
#[derive(Debug, Default)]
pub struct ScratchPool {
    free: Mutex<Vec<Vec<f64>>>,
}

impl ScratchPool {
    /// An empty pool.
    pub fn new() -> Self {
        Self::default()
    }

    /// Run `f` with a buffer of length `len` (contents unspecified).
    pub fn with<R>(&self, len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
        let mut buf = self
            .free
            .lock()
            .map(|mut v| v.pop())
            .ok()
            .flatten()
            .unwrap_or_default();
        if buf.len() < len {
            buf.resize(len, 0.0);
        }
        let out = f(&mut buf[..len]);
        if let Ok(mut v) = self.free.lock() {
            v.push(buf);
        }
        out
    }
}
