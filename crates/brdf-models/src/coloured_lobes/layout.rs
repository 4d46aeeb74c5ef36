//! How a coloured-lobe model's parameters are laid out, lobe by lobe, and
//! the weight of one lobe's term: what the per-pair kernel
//! ([`super::model`]) and the batch kernel ([`super::batch`]) share.

/// The Fresnel law of one GGX lobe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LobeFresnel {
    /// `F = 1`: the lobe's colour is three linear amplitudes `ks{k}`
    /// (Cycles' Glossy BSDF with the colour; Mitsuba's `roughconductor`
    /// with `material = "none"`, a perfect mirror, and
    /// `specular_reflectance` = the colour).
    None,
    /// F82 tint with colours `f0{k}` and `tint{k}` (see
    /// [`super::fresnel_laws`]).
    F82Tint,
    /// Exact conductor Fresnel with `eta{k}`, `kappa{k}` per channel.
    Conductor,
}

/// Where one lobe's parameters sit in the parameter vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LobeLayout {
    pub(super) fresnel: LobeFresnel,
    /// First of the lobe's per-channel blocks (one block for `None`, two
    /// for the others: `f0` then `tint`, or `eta` then `kappa`).
    pub(super) start: usize,
    /// Index of `alpha{k}`.
    pub(super) alpha: usize,
}

/// A term's weight `F (1 + F k)` for Fresnel `F` and compensation excess
/// `(k, dk/d alpha)`, with its derivatives in `F` and in `alpha`.
#[inline(always)]
pub(super) fn weighted(f: f64, (k, dk): (f64, f64)) -> (f64, f64, f64) {
    (f * (1.0 + f * k), 1.0 + 2.0 * f * k, f * f * dk)
}
