//! Any BRDF written as an RGL `.bsdf` file on the grid of a measurement,
//! so that Mitsuba 3's `measured` plugin renders it.
//!
//! Mitsuba has no plugin for most models of the catalogue (SGD, ABC, STD,
//! Dupuy's tabulated NDF, ...). Its `measured` plugin renders any function
//! stored in the RGL format (see [`crate::rgl`] for the evaluation). This
//! module keeps every field of a measurement's file (the `ndf`, `sigma`
//! and `vndf` of its adaptive parameterisation, the `luminance` used for
//! importance sampling, the angles) and replaces the measured `rgb` values
//! by the model's: at each node `(phi_i, theta_i, s)` of the table, with
//! `L` the incident direction and `V` the outgoing direction of the
//! sample-space node `s` ([`Rgl::direction_of_sample`]), the stored value is
//! `f(L, V) / k(L, V)`, `k` = [`Rgl::jacobian_factor`]. The file then
//! evaluates to the model **exactly at the nodes** (to `f32` precision) and
//! to the bilinear interpolation of the model on the measurement's warped
//! grid between them: the same sampling, and the same interpolation, as
//! the measurement it is compared with.
//!
//! Incidences beyond the measured range (the files' 90 deg node, a copy
//! of their last measured elevation: a grazing incidence cannot be
//! measured) repeat the model's table at the last measured elevation, as
//! the measurement does; the model's own grazing values (unbounded for
//! models with `1 / cos theta_i`) would otherwise be interpolated into the
//! silhouette of every render.
//!
//! Limits, refused with an error rather than written wrong:
//! - the grid of an isotropic file has one azimuth, so an anisotropic
//!   model (one whose value changes when both directions turn about the
//!   normal by more than 0.1%) cannot be stored on it;
//! - a file with spectral fields (`spectra`, `wavelengths`) is written
//!   without them, so a spectral Mitsuba variant fails to load it instead of
//!   rendering the measurement's spectra;
//! - a model value that is not finite is an error naming the node.
//!
//! ```no_run
//! use brdf_core::Brdf;
//! use nalgebra::Vector3;
//!
//! /// A grey Lambertian reflector of albedo 0.5.
//! struct Matte;
//! impl Brdf for Matte {
//!     fn channels(&self) -> usize {
//!         1
//!     }
//!     fn eval(&self, _: &Vector3<f64>, _: &Vector3<f64>, out: &mut [f64]) {
//!         out[0] = 0.5 / std::f64::consts::PI;
//!     }
//! }
//!
//! let t = brdf_io::rgl_tabulated::tabulate(
//!     std::path::Path::new("rgl/cc_ibiza_sunset_rgb.bsdf"),
//!     &Matte,
//!     "a matte grey on the grid of cc_ibiza_sunset_rgb",
//! )?;
//! std::fs::write("matte.bsdf", t.bytes)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use brdf_core::{Brdf, spherical_to_cartesian};
use nalgebra::{Rotation3, Vector3};

use crate::IoError;
use crate::rgl::{Field, Rgl, TensorFile};

/// A tabulated model: the file's bytes and the size of its table.
#[derive(Clone, Debug)]
pub struct Tabulated {
    /// The `.bsdf` file's bytes.
    pub bytes: Vec<u8>,
    /// Tabulated incident directions (`phi_i` x `theta_i` nodes).
    pub incident: usize,
    /// Sample-space nodes per incident direction (`ny` x `nx`).
    pub per_incident: usize,
}

/// The largest relative change of the model's value under a turn about
/// the normal that an isotropic grid accepts: a tenth of a percent, well
/// below the tabulation's own interpolation error (0.75% median for a
/// smooth lobe), so a fit whose anisotropy parameter ended near, not at,
/// zero (principled on paper_white: 2.9e-5) is stored at the grid's
/// azimuth; anything larger is refused.
const ISOTROPY_TOLERANCE: f64 = 1e-3;

/// `brdf` tabulated on the grid of the RGL file `grid`, described by
/// `description` (stored in the file's `description` field).
pub fn tabulate(grid: &Path, brdf: &dyn Brdf, description: &str) -> Result<Tabulated, IoError> {
    let bytes = std::fs::read(grid).map_err(|source| IoError::Io {
        path: grid.to_path_buf(),
        source,
    })?;
    let rgl = Rgl::parse(grid, &bytes)?;
    let mut tf = TensorFile::parse(grid, &bytes)?;
    let refuse = |reason: String| IoError::Unsupported {
        path: grid.to_path_buf(),
        reason,
    };
    if rgl.is_isotropic()
        && let Some(change) = anisotropy(brdf)
    {
        return Err(refuse(format!(
            "the model is anisotropic (its value changes by {} under a turn about the normal) and this grid is isotropic; tabulate it on an anisotropic measurement",
            crate::error::short(change)
        )));
    }
    let angles = |name: &str| {
        tf.field(name)
            .and_then(Field::to_f64)
            .ok_or_else(|| refuse(format!("field `{name}` missing or not f32")))
    };
    let (phi_i, theta_i) = (angles("phi_i")?, angles("theta_i")?);
    let shape = tf
        .field("rgb")
        .map(|f| f.shape.clone())
        .ok_or_else(|| refuse("field `rgb` missing".into()))?;
    let (ny, nx) = (shape[3], shape[4]);
    let mut values = Vec::with_capacity(shape.iter().product());
    let mut f = vec![0.0; brdf.channels().max(1)];
    // Incidences beyond the measured range (the 90 deg node) repeat the
    // last measured one, as the measurements themselves do: the model's own
    // values there (up to 1e5 times the body for SGD at grazing incidence)
    // would be interpolated into the silhouette of every render.
    let last = theta_i
        .iter()
        .copied()
        .filter(|t| *t <= rgl.measured_theta_max())
        .fold(0.0, f64::max);
    for &phi in &phi_i {
        for &theta in &theta_i {
            let at = if theta > rgl.measured_theta_max() {
                last
            } else {
                theta
            };
            values.extend(node_table(&rgl, brdf, phi, at, (ny, nx), &mut f)?);
        }
    }
    let rgb_bytes = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    tf.fields
        .retain(|(name, _)| name != "spectra" && name != "wavelengths" && name != "description");
    if let Some((_, rgb)) = tf.fields.iter_mut().find(|(name, _)| name == "rgb") {
        rgb.bytes = rgb_bytes;
    }
    tf.fields.push((
        "description".into(),
        Field {
            dtype: 1,
            shape: vec![description.len()],
            bytes: description.as_bytes().to_vec(),
        },
    ));
    Ok(Tabulated {
        bytes: tf.to_bytes()?,
        incident: phi_i.len() * theta_i.len(),
        per_incident: ny * nx,
    })
}

/// The stored table (3 x `ny` x `nx`) of the incident direction
/// `(theta, phi)`.
fn node_table(
    rgl: &Rgl,
    brdf: &dyn Brdf,
    phi: f64,
    theta: f64,
    (ny, nx): (usize, usize),
    f: &mut [f64],
) -> Result<Vec<f32>, IoError> {
    let l = spherical_to_cartesian(theta, phi);
    let mut table = vec![0f32; 3 * ny * nx];
    for iy in 0..ny {
        for ix in 0..nx {
            let s = [ix as f64 / (nx - 1) as f64, iy as f64 / (ny - 1) as f64];
            let stored = node_value(rgl, brdf, &l, s, f).ok_or_else(|| IoError::Unsupported {
                path: rgl.path.clone(),
                reason: format!(
                    "the model is not finite at the node theta_i = {:.2} deg, phi_i = {:.2} deg, sample ({ix}, {iy}); it cannot be tabulated",
                    theta.to_degrees(),
                    phi.to_degrees()
                ),
            })?;
            for c in 0..3 {
                table[(c * ny + iy) * nx + ix] = stored[c] as f32;
            }
        }
    }
    Ok(table)
}

/// The three stored values of the node `s` for incident `l`: the model's
/// value over the file's Jacobian factor (0 where the outgoing direction is
/// below the horizon or the factor vanishes); `None` when the model is not
/// finite there.
fn node_value(
    rgl: &Rgl,
    brdf: &dyn Brdf,
    l: &Vector3<f64>,
    s: [f64; 2],
    f: &mut [f64],
) -> Option<[f64; 3]> {
    let (v, _) = rgl.direction_of_sample(l, s);
    if !(l.z > 0.0 && v.z > 0.0) {
        return Some([0.0; 3]);
    }
    brdf.eval(l, &v, f);
    let k = rgl.jacobian_factor(l, &v);
    if !(k.is_finite() && k > 0.0) {
        return Some([0.0; 3]);
    }
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let x = f[c.min(f.len() - 1)];
        if !x.is_finite() {
            return None;
        }
        *o = x / k;
    }
    Some(out)
}

/// The largest relative change of `brdf` over a few direction pairs when
/// both directions turn about the normal, if above
/// [`ISOTROPY_TOLERANCE`].
fn anisotropy(brdf: &dyn Brdf) -> Option<f64> {
    let n = brdf.channels().max(1);
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    let mut worst: f64 = 0.0;
    for &(ti, pi, to, po) in &[
        (0.3, 0.2, 0.5, 2.9),
        (0.7, 1.1, 0.4, 4.0),
        (0.9, 0.0, 0.9, 3.3),
        (0.2, 2.0, 1.1, 0.4),
    ] {
        let (l, v) = (
            spherical_to_cartesian(ti, pi),
            spherical_to_cartesian(to, po),
        );
        brdf.eval(&l, &v, &mut a);
        for turn in [0.7, 1.9, 4.4] {
            let r = Rotation3::from_axis_angle(&Vector3::z_axis(), turn);
            brdf.eval(&(r * l), &(r * v), &mut b);
            for (x, y) in a.iter().zip(&b) {
                let scale = x.abs().max(y.abs());
                if scale > 0.0 {
                    worst = worst.max((x - y).abs() / scale);
                }
            }
        }
    }
    (worst > ISOTROPY_TOLERANCE).then_some(worst)
}
