//! A fitted model as the exporters see it: its catalogue name, the
//! renderer material its formula is (its catalogue entry's
//! [`RendererForm`]), channel count and parameters by name, with the GGX
//! family decoded into lobes.

use brdf_core::Parametric;
use brdf_models::{GgxFresnel, RendererForm};

use crate::{ExportError, Target};

/// A fitted model's name, channels and named parameter values.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// Catalogue name.
    pub name: String,
    /// The renderer material its formula is ([`RendererForm::None`] for a
    /// model outside the catalogue).
    pub form: RendererForm,
    /// 1 (grey) or 3 (linear sRGB).
    pub channels: usize,
    /// `(name, value)` in parameter-vector order.
    pub params: Vec<(String, f64)>,
}

/// Fresnel term of one GGX lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LobeFresnel {
    /// Schlick with `F0`.
    Schlick(f64),
    /// Exact Fresnel of `eta + i k` (a dielectric has `k = 0`).
    Complex {
        /// real index
        eta: f64,
        /// extinction
        k: f64,
    },
}

/// One GGX lobe: strength per RGB channel, widths, Fresnel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeFit {
    /// `ks` per channel (grey repeated).
    pub ks: [f64; 3],
    /// width along the tangent
    pub ax: f64,
    /// width along the bitangent
    pub ay: f64,
    /// Fresnel term
    pub fresnel: LobeFresnel,
}

/// A model of the GGX family: Lambert plus lobes.
#[derive(Clone, Debug, PartialEq)]
pub struct GgxFit {
    /// `kd` per channel (grey repeated).
    pub kd: [f64; 3],
    /// The lobes.
    pub lobes: Vec<LobeFit>,
    /// Separable (true) or height-correlated Smith.
    pub separable: bool,
}

impl Fitted {
    /// Read `model`; only 1 or 3 channels.
    pub fn new(model: &dyn Parametric) -> Result<Self, ExportError> {
        let channels = model.channels();
        if channels != 1 && channels != 3 {
            return Err(ExportError::Channels {
                model: model.name().to_string(),
                channels,
            });
        }
        let params = model
            .param_specs()
            .iter()
            .zip(model.params())
            .map(|(s, &v)| (s.name.clone(), v))
            .collect();
        let form = brdf_models::entry(model.name()).map_or(RendererForm::None, |e| e.form);
        Ok(Fitted {
            form,
            name: model.name().to_string(),
            channels,
            params,
        })
    }

    /// The value of parameter `name`.
    pub fn get(&self, name: &str) -> Result<f64, ExportError> {
        self.params
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| *v)
            .ok_or_else(|| ExportError::MissingParameter {
                model: self.name.clone(),
                name: name.to_string(),
            })
    }

    /// A per-channel parameter as RGB: `base` for grey, `base_r/g/b` for RGB.
    pub fn colour(&self, base: &str) -> Result<[f64; 3], ExportError> {
        if self.channels == 1 {
            let v = self.get(base)?;
            return Ok([v; 3]);
        }
        Ok([
            self.get(&format!("{base}_r"))?,
            self.get(&format!("{base}_g"))?,
            self.get(&format!("{base}_b"))?,
        ])
    }

    /// The error for a model `target` cannot represent.
    pub fn no_equivalent(&self, target: Target, reason: impl Into<String>) -> ExportError {
        ExportError::NoEquivalent {
            model: self.name.clone(),
            target,
            reason: reason.into(),
        }
    }

    /// The model decoded as the GGX family, `None` for other models.
    pub fn ggx(&self) -> Result<Option<GgxFit>, ExportError> {
        let RendererForm::Ggx(form) = self.form else {
            return Ok(None);
        };
        let kd = self.colour("kd")?;
        if form.numbered {
            let mut lobes = Vec::new();
            let mut k = 1;
            while self.get(&format!("alpha{k}")).is_ok() {
                let a = self.get(&format!("alpha{k}"))?;
                lobes.push(LobeFit {
                    ks: self.colour(&format!("ks{k}"))?,
                    ax: a,
                    ay: a,
                    fresnel: LobeFresnel::Schlick(self.get(&format!("f0_{k}"))?),
                });
                k += 1;
            }
            return Ok(Some(GgxFit {
                kd,
                lobes,
                separable: form.separable,
            }));
        }
        let (ax, ay) = if form.anisotropic {
            (self.get("ax")?, self.get("ay")?)
        } else {
            let a = self.get("alpha")?;
            (a, a)
        };
        let fresnel = match form.fresnel {
            GgxFresnel::Conductor => LobeFresnel::Complex {
                eta: self.get("eta")?,
                k: self.get("k")?,
            },
            GgxFresnel::Dielectric => LobeFresnel::Complex {
                eta: self.get("eta")?,
                k: 0.0,
            },
            GgxFresnel::Schlick => LobeFresnel::Schlick(self.get("f0")?),
        };
        let lobe = LobeFit {
            ks: self.colour("ks")?,
            ax,
            ay,
            fresnel,
        };
        Ok(Some(GgxFit {
            kd,
            lobes: vec![lobe],
            separable: form.separable,
        }))
    }
}

/// `[r, g, b]` as `"r, g, b"` (shortest round-trip decimals).
pub(crate) fn rgb_string(c: &[f64; 3]) -> String {
    format!("{}, {}, {}", c[0], c[1], c[2])
}
