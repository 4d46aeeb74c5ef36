//! Sample sets as numpy arrays and back. `load(path)` gives a dict:
//! `wi`, `wo` (`(n, 3)` unit vectors, local frame), `values` (`(n,
//! channels)`, 1/sr), `weights` (`(n,)`), `channel_names`, `name`,
//! `provenance`. A dict with these keys (`weights`, `channel_names`, `name`,
//! `provenance` optional) is a data set for `fit` and `save_samples`.

use std::path::PathBuf;

use brdf_core::SampleSet;
use numpy::ndarray::{Array1, Array2};
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLike1, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{to_py, usage};

/// Read a data set into NumPy arrays.
///
/// Parameters
/// ----------
/// path : str or os.PathLike
///     Any format the library detects: CUReT ``abrdf.dat#N``, Cornell,
///     RGL ``.bsdf``, MERL, CSV; a relative path is also looked up under
///     ``BRDF_DATA``.
///
/// Returns
/// -------
/// dict
///     ``wi``, ``wo`` (``(n, 3)``), ``values`` (``(n, channels)``),
///     ``weights``, ``channel_names``, ``name``.
///
/// Raises
/// ------
/// BrdfError
///     Naming the file (and line) at fault; for a missing file, the
///     nearest names in its folder.
///
/// Warns
/// -----
/// UserWarning
///     For what the file left to an assumption, e.g. a CSV file without a
///     weight column (every sample weighted 1).
#[pyfunction]
pub fn load<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let spec = path.display().to_string();
    let set = py.detach(|| brdf_io::load(&spec)).map_err(to_py)?;
    for note in &set.notes {
        crate::error::warn(py, note)?;
    }
    to_dict(py, &set)
}

/// Write a data set as a CSV sample file, which ``load`` reads back exactly.
///
/// Parameters
/// ----------
/// data : dict
///     Arrays as ``load`` returns them.
/// path : str or os.PathLike
///     The CSV file to write.
#[pyfunction]
pub fn save_samples(data: &Bound<'_, PyDict>, path: PathBuf) -> PyResult<()> {
    let set = from_dict(data)?;
    brdf_io::csv_samples::write(&path, &set).map_err(to_py)
}

/// The arrays of a sample set.
pub fn to_dict<'py>(py: Python<'py>, set: &SampleSet) -> PyResult<Bound<'py, PyDict>> {
    let n = set.len();
    let p = set.pairs();
    let wi = Array2::from_shape_fn((n, 3), |(j, k)| [p.lx[j], p.ly[j], p.lz[j]][k]);
    let wo = Array2::from_shape_fn((n, 3), |(j, k)| [p.vx[j], p.vy[j], p.vz[j]][k]);
    let values = Array2::from_shape_fn((n, set.channels()), |(j, c)| set.channel(c)[j]);
    let d = PyDict::new(py);
    d.set_item("wi", wi.into_pyarray(py))?;
    d.set_item("wo", wo.into_pyarray(py))?;
    d.set_item("values", values.into_pyarray(py))?;
    d.set_item(
        "weights",
        Array1::from(set.weights().to_vec()).into_pyarray(py),
    )?;
    d.set_item("channel_names", set.channel_names.clone())?;
    d.set_item("name", set.name.clone())?;
    d.set_item("provenance", set.provenance.clone())?;
    Ok(d)
}

/// A sample set from a dict of arrays; every inconsistency is an error
/// naming the key (and row).
pub fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<SampleSet> {
    let (wi, _) = crate::directions::parse(array(d, "wi")?.as_array(), "data `wi`")?;
    let (wo, _) = crate::directions::parse(array(d, "wo")?.as_array(), "data `wo`")?;
    let values = array(d, "values")?;
    let values = values.as_array();
    let n = wi.len();
    let (rows, channels) = match values.shape() {
        [r] => (*r, 1),
        [r, c] => (*r, *c),
        s => {
            return Err(usage(format!(
                "data `values`: shape {s:?}; expected (n, channels)"
            )));
        }
    };
    if wo.len() != n || rows != n {
        return Err(usage(format!(
            "data: `wi` has {n} rows, `wo` {}, `values` {rows}; they must agree",
            wo.len()
        )));
    }
    let values: Vec<f64> = values.iter().copied().collect();
    let weights = match d.get_item("weights")? {
        Some(w) => w
            .extract::<PyArrayLike1<f64, AllowTypeChange>>()?
            .as_array()
            .to_vec(),
        None => vec![1.0; n],
    };
    if weights.len() != n {
        return Err(usage(format!(
            "data: `weights` has {} entries for {n} samples",
            weights.len()
        )));
    }
    let names: Vec<String> = match d.get_item("channel_names")? {
        Some(c) => c.extract()?,
        None if channels == 1 => vec!["grey".into()],
        None => (0..channels).map(|c| format!("c{c}")).collect(),
    };
    if names.len() != channels {
        return Err(usage(format!(
            "data: {} `channel_names` for {channels} value columns",
            names.len()
        )));
    }
    let text = |key: &str, default: &str| -> PyResult<String> {
        Ok(match d.get_item(key)? {
            Some(v) => v.extract()?,
            None => default.to_string(),
        })
    };
    let mut set = SampleSet::new(
        text("name", "numpy")?,
        text("provenance", "numpy arrays")?,
        names,
    );
    for j in 0..n {
        let row = &values[j * channels..(j + 1) * channels];
        set.push(&wi[j], &wo[j], row, weights[j]).map_err(to_py)?;
    }
    Ok(set)
}

/// The array under `key`, as f64 (converted from any numeric dtype or list).
fn array<'py>(
    d: &Bound<'py, PyDict>,
    key: &str,
) -> PyResult<PyArrayLikeDyn<'py, f64, AllowTypeChange>> {
    d.get_item(key)?
        .ok_or_else(|| usage(format!("data: no `{key}` array (expected wi, wo, values)")))?
        .extract()
        .map_err(|e| usage(format!("data `{key}`: {e}")))
}
