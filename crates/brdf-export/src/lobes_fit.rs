//! A coloured-lobe model (`brdf_models::coloured_lobes`) as its exporters
//! see it: the catalogue configuration (masking, coat), the Lambert colour
//! and each GGX lobe's width and colour law, read from the fitted model's
//! named parameters, so that the Mitsuba and Blender writers build their
//! terms from one decoding.

use brdf_models::coloured_lobes::{LobeFresnel, MAX_LOBES, Masking, Variant, variant_named};

use crate::fitted::Fitted;

/// The colour law of one GGX lobe, with its per-channel values (grey
/// repeated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LobeColour {
    /// Fresnel law none: the colour `ks{k}` itself.
    Plain([f64; 3]),
    /// F82 tint: `f0{k}` and `tint{k}`.
    F82 {
        /// reflectance at normal incidence
        f0: [f64; 3],
        /// value at 82 degrees over Schlick's
        tint: [f64; 3],
    },
    /// Exact conductor Fresnel of `eta{k} + i kappa{k}`.
    Conductor {
        /// real part of the index
        eta: [f64; 3],
        /// extinction coefficient
        kappa: [f64; 3],
    },
}

/// One GGX lobe: its width `alpha{k}` and colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// GGX width (the distribution's own `alpha`).
    pub alpha: f64,
    /// colour law and values
    pub colour: LobeColour,
}

/// The white dielectric coat lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coat {
    /// index of refraction
    pub ior: f64,
    /// GGX width
    pub alpha: f64,
}

/// A coloured-lobe model decoded.
#[derive(Clone, Debug, PartialEq)]
pub struct LobesFit {
    /// The catalogue configuration.
    pub variant: &'static Variant,
    /// Lambert albedo `kd` per channel.
    pub kd: [f64; 3],
    /// The GGX lobes, in order.
    pub lobes: Vec<Lobe>,
    /// The coat, when the configuration has one.
    pub coat: Option<Coat>,
}

impl LobesFit {
    /// Whether every lobe uses the separable Smith masking (Mitsuba 3's).
    pub fn separable(&self) -> bool {
        self.variant.masking == Masking::Separable
    }
}

impl Fitted {
    /// The model decoded as a coloured-lobe configuration, `None` for
    /// other models.
    pub fn lobes(&self) -> Result<Option<LobesFit>, crate::ExportError> {
        let Some(variant) = variant_named(&self.name) else {
            return Ok(None);
        };
        let mut lobes = Vec::new();
        for k in 1..=MAX_LOBES {
            let Ok(alpha) = self.get(&format!("alpha{k}")) else {
                break;
            };
            let law = if k == 1 {
                variant.first
            } else {
                LobeFresnel::None
            };
            let colour = match law {
                LobeFresnel::None => LobeColour::Plain(self.colour(&format!("ks{k}"))?),
                LobeFresnel::F82Tint => LobeColour::F82 {
                    f0: self.colour(&format!("f0{k}"))?,
                    tint: self.colour(&format!("tint{k}"))?,
                },
                LobeFresnel::Conductor => LobeColour::Conductor {
                    eta: self.colour(&format!("eta{k}"))?,
                    kappa: self.colour(&format!("kappa{k}"))?,
                },
            };
            lobes.push(Lobe { alpha, colour });
        }
        if lobes.is_empty() {
            // Reports `alpha1` as missing.
            self.get("alpha1")?;
        }
        let coat = if variant.coat {
            Some(Coat {
                ior: self.get("coat_ior")?,
                alpha: self.get("coat_alpha")?,
            })
        } else {
            None
        };
        Ok(Some(LobesFit {
            variant,
            kd: self.colour("kd")?,
            lobes,
            coat,
        }))
    }
}
