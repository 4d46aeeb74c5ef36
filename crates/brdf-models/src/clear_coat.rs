//! A clear-coat layer over any base model (Sopp 2017):
//!
//! `f_total = Fr(theta_i) + (1 - Fr(theta_i)) f_base`,
//!
//! with `Fr` the exact unpolarised Fresnel reflectance of the coat for
//! refractive index `eta` (fixed, not fitted; 1.5 for Sopp's paints). The
//! measured data of a coated sample is turned into base data by dividing by
//! `1 - Fr(theta_i)` before the base is fitted ([`divide_by_transmission`]),
//! as Sopp did.
//!
//! The parameters are the base model's. Properties: non-negative where the
//! base is. **Not reciprocal** (`Fr(theta_i)` depends on the incident
//! direction, as published). Energy: the `Fr` term alone contributes
//! `pi Fr(theta_i)` to the directional albedo, which exceeds 1 towards
//! grazing incidence (`Fr -> 1`); the albedo is at most 1 exactly where
//! `pi Fr + (1 - Fr) a_base <= 1`, i.e. for base albedo `a_base` while
//! `Fr(theta_i) <= (1 - a_base) / (pi - a_base)`. `tests/models/energy.rs` checks
//! this domain.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::{ClearCoat, Lambert};
//! use nalgebra::Vector3;
//! let m = ClearCoat::new(Box::new(Lambert::new(&[0.5]).unwrap()), 1.5).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // Fr(0) = 0.04: 0.04 + 0.96 * 0.5 / pi.
//! assert!((f[0] - (0.04 + 0.96 * 0.5 / std::f64::consts::PI)).abs() < 1e-12);
//! ```

use brdf_core::fresnel::fresnel_dielectric;
use brdf_core::{Brdf, DirPairs, ParamError, ParamSpec, Parametric, SampleSet};
use nalgebra::Vector3;

/// A base model under a clear coat of index `eta`.
pub struct ClearCoat {
    base: Box<dyn Parametric>,
    eta: f64,
    name: String,
}

impl Clone for ClearCoat {
    fn clone(&self) -> Self {
        Self {
            base: self.base.clone_box(),
            eta: self.eta,
            name: self.name.clone(),
        }
    }
}

impl std::fmt::Debug for ClearCoat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ClearCoat")
            .field("base", &self.base.name())
            .field("eta", &self.eta)
            .finish()
    }
}

impl ClearCoat {
    /// Name in the catalogue (over Sopp's AS paint shader).
    pub const NAME: &'static str = "clear-coat";

    /// `base` under a coat of refractive index `eta` in `[1, 3]`.
    pub fn new(base: Box<dyn Parametric>, eta: f64) -> Result<Self, ParamError> {
        if !(1.0..=3.0).contains(&eta) {
            return Err(ParamError::OutOfBounds {
                name: "eta".into(),
                value: eta,
                bounds: "[1, 3]".into(),
            });
        }
        Ok(Self {
            // The catalogue name; `base()` names what is underneath.
            name: Self::NAME.to_string(),
            base,
            eta,
        })
    }

    /// The coat's refractive index.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// The base model.
    pub fn base(&self) -> &dyn Parametric {
        self.base.as_ref()
    }
}

impl Brdf for ClearCoat {
    fn channels(&self) -> usize {
        self.base.channels()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(self.base.params(), l, v, out)
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        self.eval_batch_at(self.base.params(), pairs, out)
    }
}

impl Parametric for ClearCoat {
    fn name(&self) -> &str {
        &self.name
    }
    fn param_specs(&self) -> &[ParamSpec] {
        self.base.param_specs()
    }
    fn params(&self) -> &[f64] {
        self.base.params()
    }
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError> {
        self.base.set_params(p)
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.base.channels();
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        self.base.eval_at(p, l, v, out);
        let fr = fresnel_dielectric(l.z, self.eta);
        for o in &mut out[..nc] {
            *o = fr + (1.0 - fr) * *o;
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let nc = self.base.channels();
        let np = p.len();
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            grad[..nc * np].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        self.base.eval_grad_at(p, l, v, out, grad);
        let fr = fresnel_dielectric(l.z, self.eta);
        for o in &mut out[..nc] {
            *o = fr + (1.0 - fr) * *o;
        }
        for g in &mut grad[..nc * np] {
            *g *= 1.0 - fr;
        }
    }
    fn clone_box(&self) -> Box<dyn Parametric> {
        Box::new(self.clone())
    }
    fn is_reciprocal(&self) -> bool {
        false
    }
}

/// Base data of a coated sample: every value divided by
/// `1 - Fr(theta_i)` (a new set; the input is unchanged). Samples at or
/// below the horizon keep their value.
pub fn divide_by_transmission(samples: &SampleSet, eta: f64) -> Result<SampleSet, ParamError> {
    if !(1.0..=3.0).contains(&eta) {
        return Err(ParamError::OutOfBounds {
            name: "eta".into(),
            value: eta,
            bounds: "[1, 3]".into(),
        });
    }
    let pairs = samples.pairs();
    let mut out = SampleSet::new(
        format!("{} (coat removed, eta {eta})", samples.name),
        samples.provenance.clone(),
        samples.channel_names.clone(),
    );
    let nc = samples.channels();
    let mut vals = vec![0.0; nc];
    for j in 0..samples.len() {
        let l = pairs.l(j);
        let t = if l.z > 0.0 {
            1.0 - fresnel_dielectric(l.z, eta)
        } else {
            1.0
        };
        for c in 0..nc {
            vals[c] = samples.channel(c)[j] / t;
        }
        let (ld, vd) = (
            brdf_core::Direction::new_unchecked(l),
            brdf_core::Direction::new_unchecked(pairs.v(j)),
        );
        out.push(&ld, &vd, &vals, samples.weights()[j])
            .map_err(|e| ParamError::Config {
                model: ClearCoat::NAME.into(),
                reason: e.to_string(),
            })?;
    }
    Ok(out)
}
