//! Spectra to colour: the CIE 1931 2-degree standard observer and the CIE
//! standard illuminant D65, tabulated at 400, 410, ..., 700 nm (CIE 15:2004,
//! Tables T.1 and T.4, abridged to the 31 wavelengths of the Cornell
//! files), and the XYZ to linear sRGB matrix (IEC 61966-2-1, D65 white).
//!
//! A spectral BRDF `f(lambda)` is treated as a reflectance under D65:
//! `X = sum f S xbar / sum S ybar` (and `Y`, `Z` alike), so a spectrally flat
//! BRDF of value `f` has luminance exactly `Y = f`. Linear sRGB is
//! `M [X Y Z]`; with the abridged 400-700 nm range a flat spectrum maps to
//! grey within about 1% (tested). Negative sRGB components (colours outside
//! the sRGB gamut) are kept, not clamped.

/// The 31 wavelengths (nm).
pub const WAVELENGTHS: [f64; 31] = [
    400.0, 410.0, 420.0, 430.0, 440.0, 450.0, 460.0, 470.0, 480.0, 490.0, 500.0, 510.0, 520.0,
    530.0, 540.0, 550.0, 560.0, 570.0, 580.0, 590.0, 600.0, 610.0, 620.0, 630.0, 640.0, 650.0,
    660.0, 670.0, 680.0, 690.0, 700.0,
];

/// CIE 1931 x-bar.
pub const X_BAR: [f64; 31] = [
    0.014310, 0.043510, 0.134380, 0.283900, 0.348280, 0.336200, 0.290800, 0.195360, 0.095640,
    0.032010, 0.004900, 0.009300, 0.063270, 0.165500, 0.290400, 0.433450, 0.594500, 0.762100,
    0.916300, 1.026300, 1.062200, 1.002600, 0.854450, 0.642400, 0.447900, 0.283500, 0.164900,
    0.087400, 0.046770, 0.022700, 0.011359,
];

/// CIE 1931 y-bar.
pub const Y_BAR: [f64; 31] = [
    0.000396, 0.001210, 0.004000, 0.011600, 0.023000, 0.038000, 0.060000, 0.090980, 0.139020,
    0.208020, 0.323000, 0.503000, 0.710000, 0.862000, 0.954000, 0.994950, 0.995000, 0.952000,
    0.870000, 0.757000, 0.631000, 0.503000, 0.381000, 0.265000, 0.175000, 0.107000, 0.061000,
    0.032000, 0.017000, 0.008210, 0.004102,
];

/// CIE 1931 z-bar.
pub const Z_BAR: [f64; 31] = [
    0.067850, 0.207400, 0.645600, 1.385600, 1.747060, 1.772110, 1.669200, 1.287640, 0.812950,
    0.465180, 0.272000, 0.158200, 0.078250, 0.042160, 0.020300, 0.008750, 0.003900, 0.002100,
    0.001650, 0.001100, 0.000800, 0.000340, 0.000190, 0.000050, 0.000020, 0.000000, 0.000000,
    0.000000, 0.000000, 0.000000, 0.000000,
];

/// CIE standard illuminant D65, relative spectral power.
pub const D65: [f64; 31] = [
    82.7549, 91.4860, 93.4318, 86.6823, 104.865, 117.008, 117.812, 114.861, 115.923, 108.811,
    109.354, 107.802, 104.790, 107.689, 104.405, 104.046, 100.000, 96.3342, 95.7880, 88.6856,
    90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268, 80.2146, 82.2778, 78.2842, 69.7213,
    71.6091,
];

/// XYZ to linear sRGB (D65 white).
pub const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.2404542, -1.5371385, -0.4985314],
    [-0.9692660, 1.8760108, 0.0415560],
    [0.0556434, -0.2040259, 1.0572252],
];

/// XYZ of a 31-sample spectrum under D65, normalised so that a flat
/// spectrum of value `f` has `Y = f`.
pub fn spectrum_to_xyz(s: &[f64; 31]) -> [f64; 3] {
    let norm: f64 = (0..31).map(|k| D65[k] * Y_BAR[k]).sum();
    let mut xyz = [0.0; 3];
    for k in 0..31 {
        let w = s[k] * D65[k] / norm;
        xyz[0] += w * X_BAR[k];
        xyz[1] += w * Y_BAR[k];
        xyz[2] += w * Z_BAR[k];
    }
    xyz
}

/// Linear sRGB of XYZ.
pub fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    let m = XYZ_TO_SRGB;
    [0, 1, 2].map(|r| m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2])
}
