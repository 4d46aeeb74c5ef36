//! The objects `fit` returns: [`PyFit`] (`brdf.Fit`: the report, the
//! fitted model, its image error) and [`PyModel`] (`brdf.Model`: a fitted
//! or saved model that evaluates, exports and saves itself).

use std::path::PathBuf;

use brdf_models::saved_model::SavedModel;
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLikeDyn, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::error::{to_py, usage};

/// A fitted or saved model.
///
/// Attributes
/// ----------
/// name : str
///     Catalogue name of the model.
/// params : dict[str, float]
///     Parameter values by name.
/// channels : int
///     Colour channels the model returns.
#[pyclass(name = "Model", module = "brdf", frozen)]
#[derive(Clone, Debug)]
pub struct PyModel {
    pub(crate) saved: SavedModel,
}

#[pymethods]
impl PyModel {
    /// Read a model saved by ``Model.save``, ``fit(..., save=...)`` or
    /// ``brdf fit --save``.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The saved model (JSON).
    ///
    /// Returns
    /// -------
    /// Model
    ///
    /// Raises
    /// ------
    /// BrdfError
    ///     When the file is missing, a data file, or not a saved model.
    #[staticmethod]
    pub fn load(path: PathBuf) -> PyResult<Self> {
        let saved = SavedModel::load(&path).map_err(to_py)?;
        saved.build().map_err(to_py)?;
        Ok(PyModel { saved })
    }

    /// Catalogue name of the model.
    #[getter]
    pub fn name(&self) -> String {
        self.saved.model.clone()
    }

    /// Colour channels the model returns.
    #[getter]
    pub fn channels(&self) -> PyResult<usize> {
        Ok(self.saved.build().map_err(to_py)?.channels())
    }

    /// Parameter values by name (a new dict on every access).
    #[getter]
    pub fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for p in &self.saved.parameters {
            d.set_item(&p.name, p.value)?;
        }
        Ok(d)
    }

    /// Evaluate the model at direction pairs.
    ///
    /// Parameters
    /// ----------
    /// wi, wo : array_like
    ///     ``(n, 3)`` unit vectors (local frame, normal +z), or one ``(3,)``
    ///     vector broadcast against the other.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     ``(n, channels)`` values in 1/sr, or ``(channels,)`` for two
    ///     single vectors.
    pub fn eval<'py>(
        &self,
        py: Python<'py>,
        wi: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
        wo: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let m = self.saved.build().map_err(to_py)?;
        crate::model::eval_model(py, m.as_ref(), wi, wo)
    }

    /// The model as a renderer's material, as ``brdf export`` writes it.
    ///
    /// Parameters
    /// ----------
    /// to : str
    ///     ``"mitsuba"``, ``"pbrt"``, ``"gltf"``, ``"materialx"``, ``"usd"``
    ///     or ``"blender"``.
    /// name, scene, light, surface, convert, force, mesh
    ///     As for ``brdf.export``.
    ///
    /// Returns
    /// -------
    /// str
    ///     The material's text; a ``BrdfError`` when there is no exact
    ///     equivalent and ``convert`` is false.
    ///
    /// Warns
    /// -----
    /// UserWarning
    ///     For a one-channel (grey) model, whose colour was never fitted.
    #[pyo3(signature = (*, to, name="fitted", scene=false, light="studio", surface="gltf_pbr",
                        convert=false, force=false, mesh=true))]
    pub fn export(
        &self,
        py: Python<'_>,
        to: &str,
        name: &str,
        scene: bool,
        light: &str,
        surface: &str,
        convert: bool,
        force: bool,
        mesh: bool,
    ) -> PyResult<String> {
        let m = self.saved.build().map_err(to_py)?;
        let opts = crate::model::ExportOptions {
            scene,
            light,
            surface,
            name,
            convert,
            force,
            mesh,
        };
        crate::model::export_text(py, m.as_ref(), to, &opts)
    }

    /// The model tabulated on the grid of an RGL measurement, as ``brdf
    /// export --to mitsuba --tabulate-on`` writes it: an RGL ``.bsdf`` file
    /// that Mitsuba 3's ``measured`` plugin renders. Any model, without
    /// conversion: its values at the grid's nodes, interpolated between
    /// them as the measurement is.
    ///
    /// Parameters
    /// ----------
    /// grid : str or os.PathLike
    ///     An RGL ``.bsdf`` measurement (isotropic, RGB); a relative path
    ///     is also looked up under ``BRDF_DATA``, as ``fit`` and ``load``
    ///     do.
    ///
    /// Returns
    /// -------
    /// bytes
    ///     The file's bytes; a ``BrdfError`` for an anisotropic model or
    ///     an unreadable or missing measurement.
    pub fn tabulate<'py>(&self, py: Python<'py>, grid: PathBuf) -> PyResult<Bound<'py, PyBytes>> {
        let t = brdf_export::measured::tabulate(&self.saved, &grid).map_err(to_py)?;
        Ok(PyBytes::new(py, &t.bytes))
    }

    /// Write the model (JSON) for ``Model.load`` and ``brdf eval --load``.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The file to write.
    pub fn save(&self, path: PathBuf) -> PyResult<()> {
        self.saved.save(&path).map_err(to_py)
    }

    /// Render the model on the judge's sphere (``brdf render``'s camera:
    /// a unit sphere seen from (0, 0, 6), 22 deg field of view).
    ///
    /// Parameters
    /// ----------
    /// light : str
    ///     ``"studio"`` (constant 0.05 and a square key light), ``"sky"``
    ///     (sky dome and sun) or ``"directional"`` (the study's light).
    /// size : int
    ///     Image width and height in pixels (16 to 1024).
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     ``(size, size, 3)`` linear radiance, row 0 at the top.
    ///
    /// Raises
    /// ------
    /// BrdfError
    ///     For an unknown light set or a size out of range.
    #[pyo3(signature = (*, light="studio", size=128))]
    pub fn render<'py>(
        &self,
        py: Python<'py>,
        light: &str,
        size: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !(16..=1024).contains(&size) {
            return Err(usage(format!(
                "render: size={size} is out of range; give 16 to 1024 pixels"
            )));
        }
        let lights = brdf_render::LightSet::parse(light).map_err(to_py)?;
        let m = self.saved.build().map_err(to_py)?;
        let image = py.detach(|| brdf_render::shading::render_judge(m.as_ref(), &lights, size));
        let shape = [image.height, image.width, image.channels];
        Ok(image.data.into_pyarray(py).reshape(shape)?.into_any())
    }

    fn __repr__(&self) -> String {
        let params: Vec<String> = self
            .saved
            .parameters
            .iter()
            .map(|p| format!("{}={:.6}", p.name, p.value))
            .collect();
        format!("Model({:?}, {})", self.saved.model, params.join(", "))
    }
}

/// The outcome of ``brdf.fit``.
///
/// Attributes
/// ----------
/// model : Model
///     The fitted model (the first channel's for ``channels="per-channel"``).
/// models : list of Model
///     One model per fit (three for ``channels="per-channel"``).
/// report : dict
///     The report ``brdf fit --json`` prints.
/// image_error : dict or None
///     Image errors against dense data (RGL, MERL), else None: per light
///     set (``lights``) HDR-FLIP, PSNR and the mean colours' CIEDE2000, and
///     ``colour_plane``: how far (``outside``, relative RMS) the data's
///     studio render lies from every plane of white and one colour, which
///     no ``principled`` or ``gltf`` render comes closer than.
#[pyclass(name = "Fit", module = "brdf", frozen)]
#[derive(Debug)]
pub struct PyFit {
    pub(crate) models: Vec<PyModel>,
    pub(crate) report: Py<PyAny>,
    /// Data name (relative to `BRDF_DATA`).
    pub(crate) data: String,
    /// Ngan L2 error of every fit.
    pub(crate) errors: Vec<f64>,
    /// The data path, when the data were named by one (for image errors
    /// against dense data).
    pub(crate) spec: Option<String>,
}

#[pymethods]
impl PyFit {
    /// The fitted model (the first of ``models``).
    #[getter]
    pub fn model(&self) -> PyResult<PyModel> {
        self.models
            .first()
            .cloned()
            .ok_or_else(|| usage("the fit produced no model".into()))
    }

    /// One model per fit.
    #[getter]
    pub fn models(&self) -> Vec<PyModel> {
        self.models.clone()
    }

    /// The report ``brdf fit --json`` prints, as a dict.
    #[getter]
    pub fn report(&self, py: Python<'_>) -> Py<PyAny> {
        self.report.clone_ref(py)
    }

    /// Image errors of the fit against dense data (RGL, MERL: rendered
    /// spheres under the standard light sets, computed on first access);
    /// None for scattered data or data given as arrays.
    #[getter]
    pub fn image_error(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        let (Some(spec), Some(model)) = (&self.spec, self.models.first()) else {
            return Ok(None);
        };
        let errors = py.detach(|| -> Result<_, String> {
            let Some(dense) = brdf_io::load_dense(spec).map_err(|e| e.to_string())? else {
                return Ok(None);
            };
            let fitted = model.saved.build().map_err(|e| e.to_string())?;
            brdf_render::Judge::new(brdf_render::judge::REPORT_SIZE)
                .errors(dense.as_ref(), fitted.as_ref())
                .map(Some)
                .map_err(|e| e.to_string())
        });
        match errors.map_err(usage)? {
            Some(e) => Ok(Some(crate::json::to_py_object(py, &e)?.unbind())),
            None => Ok(None),
        }
    }

    fn __repr__(&self) -> String {
        let errors: Vec<String> = self.errors.iter().map(|e| format!("{e:.4e}")).collect();
        let name = self
            .models
            .first()
            .map_or("?".into(), |m| m.saved.model.clone());
        format!(
            "Fit(model={name:?}, data={:?}, ngan_l2=[{}])",
            self.data,
            errors.join(", ")
        )
    }
}
