//! The Ashikhmin-Shirley paint shader of Sopp (2017): per-channel colours
//! `cd`, `cs`, a scalar specular strength `Rs` and exponent `ns`:
//!
//! `f = cd/pi (1 - Rs) + Rs cs (ns+1)/(8 pi) (N.H)^ns / ((H.V) max(N.L, N.V))`.
//!
//! `Rs` and `cs` are redundant in a fit, so the model that is fitted
//! ([`AsPaint`], catalogue name `as-paint`) has `cd' = cd (1 - Rs)` and
//! `cs' = Rs cs` as its linear parameters, and [`PaintShader::from_fit`]
//! converts afterwards: `Rs = max_c cs'_c`, `cs_c = cs'_c / Rs`,
//! `cd_c = cd'_c / (1 - Rs)`.
//!
//! | parameter (fitted form) | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `cd` (per channel) | diffuse colour times `1 - Rs` | `[0, 1]` | yes |
//! | `cs` (per channel) | specular colour times `Rs` | `[0, 1]` | yes |
//! | `ns` | exponent | `[0, 1e6]` | no |
//!
//! Properties: reciprocal; non-negative; finite above the horizon.
//!
//! ```
//! use brdf_core::Parametric;
//! use brdf_models::paint_shader::{AsPaint, PaintShader};
//! let fitted = AsPaint::new(&[0.3, 0.2, 0.1], &[0.2, 0.4, 0.1], &[50.0]).unwrap();
//! let paint = PaintShader::from_fit(&fitted).unwrap();
//! assert_eq!(paint.rs, 0.4);
//! assert_eq!(paint.cs, vec![0.5, 1.0, 0.25]);
//! assert!((paint.cd[0] - 0.5).abs() < 1e-15);
//! ```

use brdf_core::{ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

use crate::ashikhmin_shirley::{as_lobe, exponent};
use crate::combinators::{DiffuseLobe, Lobe};

/// The AS lobe without Fresnel, parameter `ns`.
#[derive(Clone, Debug, PartialEq)]
pub struct AsPaintLobe;

impl Lobe for AsPaintLobe {
    const NAME: &'static str = "as-paint";
    const DIFFUSE: &'static str = "cd";
    const SPECULAR: &'static str = "cs";
    fn specs() -> Vec<ParamSpec> {
        vec![exponent("ns")]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let (s, d) = as_lobe(q[0], q[0], None, l, v);
        if let Some(dq) = dq {
            dq[0] = d[0] + d[1];
        }
        s
    }
}

/// The fitted form of the paint shader.
pub type AsPaint = DiffuseLobe<AsPaintLobe>;

/// The paint shader in Sopp's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct PaintShader {
    /// Diffuse colour per channel.
    pub cd: Vec<f64>,
    /// Specular colour per channel (its largest component is 1).
    pub cs: Vec<f64>,
    /// Specular strength.
    pub rs: f64,
    /// Exponent.
    pub ns: f64,
}

impl PaintShader {
    /// Convert a fitted [`AsPaint`]: `Rs = max cs'`, `cs = cs'/Rs`,
    /// `cd = cd'/(1 - Rs)`. Errors when there is no specular part
    /// (`Rs = 0`) or `Rs >= 1` (no diffuse colour can be recovered).
    pub fn from_fit(m: &AsPaint) -> Result<Self, ParamError> {
        let nc = m.channels;
        let p = m.params();
        let rs = p[nc..2 * nc].iter().fold(0.0f64, |a, v| a.max(*v));
        if !(rs > 0.0 && rs < 1.0) {
            return Err(ParamError::OutOfBounds {
                name: "Rs = max(cs)".into(),
                value: rs,
                bounds: "(0, 1)".into(),
            });
        }
        Ok(Self {
            cd: p[..nc].iter().map(|v| v / (1.0 - rs)).collect(),
            cs: p[nc..2 * nc].iter().map(|v| v / rs).collect(),
            rs,
            ns: p[2 * nc],
        })
    }

    /// Back to the fitted form.
    pub fn to_fit(&self) -> Result<AsPaint, ParamError> {
        let cd: Vec<f64> = self.cd.iter().map(|v| v * (1.0 - self.rs)).collect();
        let cs: Vec<f64> = self.cs.iter().map(|v| v * self.rs).collect();
        AsPaint::new(&cd, &cs, &[self.ns])
    }
}
