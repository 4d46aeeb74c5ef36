//! Fresnel reflectance terms shared by the models.

/// Schlick's approximation `F(c) = F0 + (1 - F0) (1 - c)^5`, `c` clamped to
/// `[0, 1]`.
#[inline]
pub fn schlick(f0: f64, cos: f64) -> f64 {
    let m = 1.0 - cos.clamp(0.0, 1.0);
    let m2 = m * m;
    f0 + (1.0 - f0) * m2 * m2 * m
}

/// `dF/dF0 = 1 - (1 - c)^5` of [`schlick`].
#[inline]
pub fn schlick_d_f0(cos: f64) -> f64 {
    let m = 1.0 - cos.clamp(0.0, 1.0);
    let m2 = m * m;
    1.0 - m2 * m2 * m
}

/// Exact unpolarised Fresnel reflectance of a dielectric interface with
/// relative index `eta` (outside to inside), for light arriving at
/// `cos_i = cos theta_i`:
/// `sin theta_t = sin theta_i / eta`,
/// `rs = (cos_i - eta cos_t) / (cos_i + eta cos_t)`,
/// `rp = (eta cos_i - cos_t) / (eta cos_i + cos_t)`, `F = (rs^2 + rp^2) / 2`.
/// These are the `sin`/`tan` ratio forms of models.md rewritten without
/// the `0/0` at normal incidence: `F(0) = ((eta - 1)/(eta + 1))^2`. Total
/// internal reflection (only for `eta < 1`) gives 1.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let ci = cos_i.clamp(0.0, 1.0);
    let s2t = (1.0 - ci * ci).max(0.0) / (eta * eta);
    if s2t >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - s2t).sqrt();
    let rs = (ci - eta * ct) / (ci + eta * ct);
    let rp = (eta * ci - ct) / (eta * ci + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Exact unpolarised Fresnel reflectance (as [`fresnel_dielectric`], light
/// arriving from the side of index 1, `eta >= 1`) and its derivative with
/// respect to `eta`. With `c_t = sqrt(1 - (1 - c_i^2)/eta^2)`:
/// `dc_t/deta = (1 - c_i^2) / (eta^3 c_t)`, and `r_s`, `r_p` are
/// differentiated as quotients.
#[inline]
pub fn fresnel_dielectric_d_eta(cos_i: f64, eta: f64) -> (f64, f64) {
    let ci = cos_i.clamp(0.0, 1.0);
    let sin2 = (1.0 - ci * ci).max(0.0);
    let s2t = sin2 / (eta * eta);
    if s2t >= 1.0 {
        return (1.0, 0.0);
    }
    let ct = (1.0 - s2t).sqrt();
    let dct = if ct > 0.0 {
        sin2 / (eta * eta * eta * ct)
    } else {
        0.0
    };
    let u = eta * ct;
    let du = ct + eta * dct;
    let rs = (ci - u) / (ci + u);
    let drs = -2.0 * ci * du / ((ci + u) * (ci + u));
    let (n, d) = (eta * ci - ct, eta * ci + ct);
    let rp = n / d;
    let drp = ((ci - dct) * d - n * (ci + dct)) / (d * d);
    (0.5 * (rs * rs + rp * rp), rs * drs + rp * drp)
}
