//! Direction arrays from Python: `(n, 3)` (or one `(3,)`) arrays of unit
//! vectors in the local frame (normal `+z`), checked row by row. A vector
//! that is not of unit length is refused, not normalised, so data given as
//! arrays are fitted exactly as given.

use brdf_core::Direction;
use numpy::ndarray::ArrayViewD;
use pyo3::PyResult;

use crate::error::usage;

/// How far from 1 a unit vector's length may be (rounding of stored data).
const UNIT_TOLERANCE: f64 = 1e-9;

/// The rows of an `(n, 3)` array, or the one vector of a `(3,)` array, as
/// directions; `what` names the argument in errors. Also returns whether the
/// array was one vector (so results can drop the row axis).
pub fn parse(array: ArrayViewD<'_, f64>, what: &str) -> PyResult<(Vec<Direction>, bool)> {
    let (rows, single) = match array.shape() {
        [3] => (1, true),
        [n, 3] => (*n, false),
        shape => {
            return Err(usage(format!(
                "{what}: shape {shape:?}; expected (n, 3) unit vectors or one (3,) vector"
            )));
        }
    };
    let flat: Vec<f64> = array.iter().copied().collect();
    let dirs = (0..rows)
        .map(|j| unit(&flat[3 * j..3 * j + 3], what, j))
        .collect::<PyResult<_>>()?;
    Ok((dirs, single))
}

/// One row as a direction, refused unless finite and of unit length.
pub fn unit(v: &[f64], what: &str, row: usize) -> PyResult<Direction> {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !((len - 1.0).abs() <= UNIT_TOLERANCE) {
        return Err(usage(format!(
            "{what} row {row}: ({}, {}, {}) has length {len}; directions must be unit vectors",
            v[0], v[1], v[2]
        )));
    }
    Ok(Direction::new_unchecked(brdf_core::nalgebra::Vector3::new(
        v[0], v[1], v[2],
    )))
}
