//! RGL material database `.bsdf` files (Dupuy & Jakob 2018, "An Adaptive
//! Parameterization for Efficient Material Acquisition and Rendering", ACM
//! TOG 37(6)), isotropic RGB variant.
//!
//! ## Container ("tensor file", little-endian)
//!
//! 12-byte magic `tensor_file\0`, `u8` major (1), `u8` minor (0), `u32` field
//! count; per field: `u16` name length, name, `u16` rank, `u8` dtype (1 =
//! u8, 5 = u32, 10 = f32, ...), `u64` absolute byte offset of the data, one
//! `u64` per dimension. [`TensorFile`] reads any such file; every offset
//! and size is checked against the file length.
//!
//! ## Evaluation
//!
//! The values are stored on the warped domain of the adaptive
//! parameterisation. With `theta2u(t) = sqrt(2 t / pi)`,
//! `phi2u(p) = (p + pi) / (2 pi)` and the half vector `M` of `(L, V)`:
//!
//! 1. `u_m = (theta2u(theta_m), phi2u(phi_m - phi_i) mod 1)` (isotropic);
//! 2. the VNDF warp (a piecewise-bilinear 2D distribution conditioned on
//!    `(phi_i, theta_i)`, sampled by marginal-then-conditional inversion of
//!    its CDFs) is **inverted** at `u_m` to the sample-space point `s`;
//! 3. `f_c = max(0, rgb_c(s; phi_i, theta_i)) ndf(u_m) / (4 sigma(u_i) cos theta_v)`,
//!    with `u_i = (theta2u(theta_i), phi2u(phi_i))`, where `rgb`, `ndf` and
//!    `sigma` are bilinear interpolants (linear across the conditioning
//!    parameters). `rgb ndf / (4 sigma)` is the cosine-weighted BRDF
//!    `f cos theta_v` (what Mitsuba 3's `measured` plugin returns from
//!    `eval`, which includes the foreshortening of the outgoing direction;
//!    pbrt-v4's `Sample_f` divides by that cosine as here). Without the
//!    division, `f(L, V)` and `f(V, L)` of `paper_white` differ by a median
//!    17% over the 48 pairs of `tests/io/rgl.rs` (29% over a wider grid
//!    reaching 75 deg); with it, by 1.7% (largest 7%). A file
//!    whose `jacobian` flag is 0 stores values that already include
//!    `ndf / (4 sigma)`: only the cosine is divided out.
//!
//! [`Rgl`] implements [`Brdf`] with this evaluation, and
//! [`Rgl::direction_of_sample`] maps a sample-space point forward (the
//! inverse of step 2), which the tests use to check that evaluation at grid
//! nodes reproduces the stored values.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

use brdf_core::{Brdf, DirPairs};
use nalgebra::Vector3;

use crate::IoError;

/// One field of a tensor file.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// dtype code.
    pub dtype: u8,
    /// Shape.
    pub shape: Vec<usize>,
    /// Raw little-endian bytes.
    pub bytes: Vec<u8>,
}

impl Field {
    /// The values as `f64` (f32 or u8 fields).
    pub fn to_f64(&self) -> Option<Vec<f64>> {
        match self.dtype {
            10 => Some(
                self.bytes
                    .chunks_exact(4)
                    .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64)
                    .collect(),
            ),
            1 => Some(self.bytes.iter().map(|b| *b as f64).collect()),
            _ => None,
        }
    }
}

/// A parsed tensor file: named fields.
#[derive(Clone, Debug, PartialEq)]
pub struct TensorFile {
    /// Fields in file order.
    pub fields: Vec<(String, Field)>,
}

/// Type byte of `f32` fields.
const DTYPE_F32: u8 = 10;

/// The name of a tensor-file type byte (for messages).
fn dtype_name(d: u8) -> &'static str {
    match d {
        1 => "u8",
        2 => "i8",
        3 => "u16",
        4 => "i16",
        5 => "u32",
        6 => "i32",
        7 => "u64",
        8 => "i64",
        9 => "f16",
        10 => "f32",
        11 => "f64",
        _ => "unknown",
    }
}

fn dtype_size(d: u8) -> Option<usize> {
    Some(match d {
        1 | 2 => 1,
        3 | 4 | 9 => 2,
        5 | 6 | 10 => 4,
        7 | 8 | 11 => 8,
        _ => return None,
    })
}

impl TensorFile {
    /// Parse the bytes of a tensor file (`path` only names it in errors).
    pub fn parse(path: &Path, b: &[u8]) -> Result<Self, IoError> {
        let bytes = Bytes { path, b };
        if bytes.take(0, 12)? != b"tensor_file\0" {
            return Err(bytes.err(0, "not a tensor file (magic `tensor_file` missing)".into()));
        }
        let v = bytes.take(12, 2)?;
        if v != [1, 0] {
            return Err(bytes.err(12, format!("version {}.{}, expected 1.0", v[0], v[1])));
        }
        let n = u32::from_le_bytes(bytes.take(14, 4)?.try_into().unwrap_or([0; 4])) as usize;
        let mut at = 18;
        let mut fields = Vec::new();
        for _ in 0..n {
            fields.push(bytes.field(&mut at)?);
        }
        Ok(Self { fields })
    }

    /// A field by name.
    pub fn field(&self, name: &str) -> Option<&Field> {
        self.fields.iter().find(|(n, _)| n == name).map(|(_, f)| f)
    }

    /// The file's bytes: the header, then each field's data in field order,
    /// contiguous (the layout [`TensorFile::parse`] reads back to `self`).
    ///
    /// Fails when a field's byte count does not match its dtype and shape,
    /// or a name or rank does not fit the format's `u16` lengths.
    pub fn to_bytes(&self) -> Result<Vec<u8>, IoError> {
        let bad = |name: &str, reason: String| IoError::Format {
            path: PathBuf::new(),
            line: 0,
            reason: format!("field `{name}`: {reason}"),
        };
        let mut header_len = 18;
        for (name, f) in &self.fields {
            let size = dtype_size(f.dtype)
                .ok_or_else(|| bad(name, format!("unknown dtype {}", f.dtype)))?;
            let count = f.shape.iter().try_fold(size, |a, s| a.checked_mul(*s));
            if count != Some(f.bytes.len()) {
                return Err(bad(
                    name,
                    format!("{} bytes for shape {:?}", f.bytes.len(), f.shape),
                ));
            }
            if name.len() > u16::MAX as usize || f.shape.len() > u16::MAX as usize {
                return Err(bad(name, "name or rank too long".into()));
            }
            header_len += 2 + name.len() + 2 + 1 + 8 + 8 * f.shape.len();
        }
        let mut out = b"tensor_file\0".to_vec();
        out.extend_from_slice(&[1, 0]);
        out.extend_from_slice(&(self.fields.len() as u32).to_le_bytes());
        let mut offset = header_len;
        for (name, f) in &self.fields {
            out.extend_from_slice(&(name.len() as u16).to_le_bytes());
            out.extend_from_slice(name.as_bytes());
            out.extend_from_slice(&(f.shape.len() as u16).to_le_bytes());
            out.push(f.dtype);
            out.extend_from_slice(&(offset as u64).to_le_bytes());
            for s in &f.shape {
                out.extend_from_slice(&(*s as u64).to_le_bytes());
            }
            offset += f.bytes.len();
        }
        for (_, f) in &self.fields {
            out.extend_from_slice(&f.bytes);
        }
        Ok(out)
    }
}

/// The bytes of a tensor file being parsed, with the file's path for the
/// errors: every read is checked against the file length, so a truncated
/// or damaged file is an error naming the byte, never a panic.
struct Bytes<'a> {
    path: &'a Path,
    b: &'a [u8],
}

impl<'a> Bytes<'a> {
    fn err(&self, at: usize, reason: String) -> IoError {
        IoError::Format {
            path: self.path.to_path_buf(),
            line: 0,
            reason: format!("byte {at}: {reason}"),
        }
    }

    /// The `n` bytes at `at`.
    fn take(&self, at: usize, n: usize) -> Result<&'a [u8], IoError> {
        self.b.get(at..at.saturating_add(n)).ok_or_else(|| {
            self.err(
                at,
                format!(
                    "needs {n} more bytes; the file has {} (truncated?)",
                    self.b.len()
                ),
            )
        })
    }

    /// The field whose header starts at `at` (moved past that header), its
    /// data copied from wherever the header's offset points.
    fn field(&self, at: &mut usize) -> Result<(String, Field), IoError> {
        let nl = u16::from_le_bytes(self.take(*at, 2)?.try_into().unwrap_or([0; 2])) as usize;
        let name = String::from_utf8_lossy(self.take(*at + 2, nl)?).into_owned();
        *at += 2 + nl;
        let rank = u16::from_le_bytes(self.take(*at, 2)?.try_into().unwrap_or([0; 2])) as usize;
        let dtype = self.take(*at + 2, 1)?[0];
        let offset = u64::from_le_bytes(self.take(*at + 3, 8)?.try_into().unwrap_or([0; 8]));
        *at += 11;
        let mut shape = Vec::with_capacity(rank);
        for _ in 0..rank {
            shape
                .push(u64::from_le_bytes(self.take(*at, 8)?.try_into().unwrap_or([0; 8])) as usize);
            *at += 8;
        }
        let at = *at;
        let size = dtype_size(dtype)
            .ok_or_else(|| self.err(at, format!("field `{name}`: unknown dtype {dtype}")))?;
        let count = shape
            .iter()
            .try_fold(size, |acc, s| acc.checked_mul(*s))
            .ok_or_else(|| self.err(at, format!("field `{name}`: size overflows")))?;
        let offset = usize::try_from(offset)
            .map_err(|_| self.err(at, format!("field `{name}`: offset too large")))?;
        let bytes = self
            .take(offset, count)
            .map_err(|_| {
                self.err(
                    offset,
                    format!("field `{name}`: data ({count} bytes) beyond the end of the file"),
                )
            })?
            .to_vec();
        Ok((
            name,
            Field {
                dtype,
                shape,
                bytes,
            },
        ))
    }
}

/// Piecewise-bilinear 2D function on `[0, 1]^2` (`nx` columns contiguous),
/// conditioned on up to three parameters with linear interpolation between
/// their tabulated values; optionally normalised to a density with its
/// marginal and conditional CDFs for inversion.
#[derive(Clone, Debug)]
struct Interp2D {
    nx: usize,
    ny: usize,
    params: Vec<Vec<f64>>,
    strides: Vec<usize>,
    data: Vec<f64>,
    marginal: Vec<f64>,
    conditional: Vec<f64>,
}

/// Interval `i` with `values[i] <= x`, clamped to `[0, n - 2]`, and the
/// weight of `values[i + 1]`.
fn locate(values: &[f64], x: f64) -> (usize, f64) {
    let n = values.len();
    if n < 2 {
        return (0, 0.0);
    }
    let i = values
        .partition_point(|v| *v <= x)
        .saturating_sub(1)
        .min(n - 2);
    let (a, b) = (values[i], values[i + 1]);
    (i, ((x - a) / (b - a)).clamp(0.0, 1.0))
}

/// Most conditioning parameters of an [`Interp2D`] (RGL files use up to
/// three: `phi_i`, `theta_i` and the channel or wavelength).
const MAX_PARAMS: usize = 3;

/// The corners of a parameter cell: slice offsets from `base` and their
/// weights (`len` of them, at most `2^MAX_PARAMS`).
#[derive(Clone, Copy)]
struct Corners {
    base: usize,
    len: usize,
    offset: [usize; 1 << MAX_PARAMS],
    weight: [f64; 1 << MAX_PARAMS],
}

impl Corners {
    /// No parameter: one corner of weight 1.
    fn one() -> Self {
        let mut c = Corners {
            base: 0,
            len: 1,
            offset: [0; 1 << MAX_PARAMS],
            weight: [0.0; 1 << MAX_PARAMS],
        };
        c.weight[0] = 1.0;
        c
    }
}

impl Interp2D {
    fn new(
        nx: usize,
        ny: usize,
        raw: &[f64],
        params: Vec<Vec<f64>>,
        density: bool,
    ) -> Option<Self> {
        if nx < 2 || ny < 2 || params.len() > MAX_PARAMS {
            return None;
        }
        let mut strides = vec![0; params.len()];
        let mut slices = 1;
        for i in (0..params.len()).rev() {
            strides[i] = if params[i].len() > 1 { slices } else { 0 };
            slices *= params[i].len().max(1);
        }
        let n = nx * ny;
        if raw.len() != slices * n {
            return None;
        }
        let mut s = Self {
            nx,
            ny,
            params,
            strides,
            data: raw.to_vec(),
            marginal: Vec::new(),
            conditional: Vec::new(),
        };
        if density {
            s.marginal = vec![0.0; slices * ny];
            s.conditional = vec![0.0; slices * n];
            for sl in 0..slices {
                let d = &raw[sl * n..(sl + 1) * n];
                let cc = &mut s.conditional[sl * n..(sl + 1) * n];
                for y in 0..ny {
                    for x in 0..nx - 1 {
                        cc[y * nx + x + 1] =
                            cc[y * nx + x] + 0.5 * (d[y * nx + x] + d[y * nx + x + 1]);
                    }
                }
                let mc = &mut s.marginal[sl * ny..(sl + 1) * ny];
                for y in 0..ny - 1 {
                    mc[y + 1] = mc[y] + 0.5 * (cc[y * nx + nx - 1] + cc[(y + 1) * nx + nx - 1]);
                }
                let total = mc[ny - 1];
                if !(total > 0.0 && total.is_finite()) {
                    return None;
                }
                mc.iter_mut().for_each(|v| *v /= total);
                cc.iter_mut().for_each(|v| *v /= total);
                s.data[sl * n..(sl + 1) * n]
                    .iter_mut()
                    .for_each(|v| *v /= total);
            }
        }
        Some(s)
    }

    /// Corner offsets and weights of the parameter cell of `p` (on the
    /// stack: an evaluation of an RGL file computes five of them).
    fn weights(&self, p: &[f64]) -> Corners {
        let mut c = Corners::one();
        for d in 0..self.params.len() {
            self.extend(&mut c, d, p[d]);
        }
        c
    }

    /// `c` extended by parameter dimension `d` at `x` (the corners of the
    /// earlier dimensions each split into two, in order).
    #[inline]
    fn extend(&self, c: &mut Corners, d: usize, x: f64) {
        let (i, w) = locate(&self.params[d], x);
        c.base += self.strides[d] * i;
        if self.strides[d] == 0 {
            return;
        }
        let n = c.len;
        // A weight of exactly 0 or 1 (a tabulated node, such as each
        // channel of the RGB table) keeps one corner of each pair: the
        // other would add `0 * value`, which leaves every sum unchanged.
        if w == 0.0 || w == 1.0 {
            let shift = if w == 0.0 { 0 } else { self.strides[d] };
            c.offset[..n].iter_mut().for_each(|o| *o += shift);
            return;
        }
        for k in (0..n).rev() {
            let (o, cw) = (c.offset[k], c.weight[k]);
            c.offset[2 * k] = o;
            c.weight[2 * k] = cw * (1.0 - w);
            c.offset[2 * k + 1] = o + self.strides[d];
            c.weight[2 * k + 1] = cw * w;
        }
        c.len = 2 * n;
    }

    fn look(table: &[f64], i: usize, size: usize, c: &Corners) -> f64 {
        c.offset[..c.len]
            .iter()
            .zip(&c.weight[..c.len])
            .map(|(o, w)| w * table[(c.base + o) * size + i])
            .sum()
    }

    fn cell(&self, u: [f64; 2]) -> (usize, usize, f64, f64) {
        let sx = (u[0].clamp(0.0, 1.0)) * (self.nx - 1) as f64;
        let sy = (u[1].clamp(0.0, 1.0)) * (self.ny - 1) as f64;
        // `as usize` truncates, which is the floor here (`sx, sy >= 0`;
        // NaN gives 0 either way) without a call to `floor` (no rounding
        // instruction in the baseline x86-64 target).
        let ix = (sx as usize).min(self.nx - 2);
        let iy = (sy as usize).min(self.ny - 2);
        (ix, iy, sx - ix as f64, sy - iy as f64)
    }

    /// Bilinear value at `u` (density scale for normalised tables).
    fn eval(&self, u: [f64; 2], p: &[f64]) -> f64 {
        self.eval_at(u, &self.weights(p))
    }

    /// [`Interp2D::eval`] in the parameter cell `corners`.
    fn eval_at(&self, u: [f64; 2], corners: &Corners) -> f64 {
        let [value] = self.eval_many_at(u, &[*corners]);
        value
    }

    /// [`Interp2D::eval_at`] in each of the parameter cells `corners`,
    /// the cell of `u` found once (the same arithmetic per value).
    fn eval_many_at<const K: usize>(&self, u: [f64; 2], corners: &[Corners; K]) -> [f64; K] {
        let (ix, iy, fx, fy) = self.cell(u);
        let n = self.nx * self.ny;
        let i = iy * self.nx + ix;
        let scale = ((self.nx - 1) * (self.ny - 1)) as f64;
        corners.map(|c| {
            let v = |k: usize| Self::look(&self.data, k, n, &c);
            let (v00, v10, v01, v11) = (v(i), v(i + 1), v(i + self.nx), v(i + self.nx + 1));
            let val =
                (1.0 - fy) * ((1.0 - fx) * v00 + fx * v10) + fy * ((1.0 - fx) * v01 + fx * v11);
            if self.marginal.is_empty() {
                val
            } else {
                val * scale
            }
        })
    }

    /// Map a point of the warped domain back to the sample space (the
    /// inverse of [`Interp2D::sample`]) in the parameter cell `corners`.
    fn invert_at(&self, u: [f64; 2], corners: &Corners) -> [f64; 2] {
        let corners = *corners;
        let (ix, iy, fx, fy) = self.cell(u);
        let n = self.nx * self.ny;
        let i = iy * self.nx + ix;
        let d = |k: usize| Self::look(&self.data, k, n, &corners);
        let cc = |k: usize| Self::look(&self.conditional, k, n, &corners);
        let c0 = (1.0 - fy) * d(i) + fy * d(i + self.nx);
        let c1 = (1.0 - fy) * d(i + 1) + fy * d(i + self.nx + 1);
        let mut x = fx * (c0 + 0.5 * fx * (c1 - c0));
        x += (1.0 - fy) * cc(i) + fy * cc(i + self.nx);
        let r0 = cc(iy * self.nx + self.nx - 1);
        let r1 = cc((iy + 1) * self.nx + self.nx - 1);
        x /= (1.0 - fy) * r0 + fy * r1;
        let y =
            fy * (r0 + 0.5 * fy * (r1 - r0)) + Self::look(&self.marginal, iy, self.ny, &corners);
        [x.clamp(0.0, 1.0), y.clamp(0.0, 1.0)]
    }

    /// Map a sample-space point into the warped domain (marginal row, then
    /// conditional column, each by inverting a piecewise-quadratic CDF).
    fn sample(&self, s: [f64; 2], p: &[f64]) -> [f64; 2] {
        let corners = self.weights(p);
        let n = self.nx * self.ny;
        let eps = 1e-12;
        let (mut sx, mut sy) = (s[0].clamp(eps, 1.0 - eps), s[1].clamp(eps, 1.0 - eps));
        let mc = |k: usize| Self::look(&self.marginal, k, self.ny, &corners);
        let cc = |k: usize| Self::look(&self.conditional, k, n, &corners);
        let d = |k: usize| Self::look(&self.data, k, n, &corners);
        let row = (0..self.ny - 1).rev().find(|r| mc(*r) <= sy).unwrap_or(0);
        sy -= mc(row);
        let (r0, r1) = (
            cc(row * self.nx + self.nx - 1),
            cc((row + 1) * self.nx + self.nx - 1),
        );
        let ty = solve_quadratic(r0, r1, sy);
        sx *= (1.0 - ty) * r0 + ty * r1;
        let fc = |k: usize| (1.0 - ty) * cc(row * self.nx + k) + ty * cc((row + 1) * self.nx + k);
        let col = (0..self.nx - 1).rev().find(|c| fc(*c) <= sx).unwrap_or(0);
        sx -= fc(col);
        let i = row * self.nx + col;
        let c0 = (1.0 - ty) * d(i) + ty * d(i + self.nx);
        let c1 = (1.0 - ty) * d(i + 1) + ty * d(i + self.nx + 1);
        let tx = solve_quadratic(c0, c1, sx);
        [
            (col as f64 + tx) / (self.nx - 1) as f64,
            (row as f64 + ty) / (self.ny - 1) as f64,
        ]
    }
}

/// `t` in `[0, 1]` with `t (a + t (b - a) / 2) = s` (the integral of the
/// linear density from `a` to `b`).
fn solve_quadratic(a: f64, b: f64, s: f64) -> f64 {
    let t = if (a - b).abs() < 1e-9 * (a + b).abs().max(f64::MIN_POSITIVE) {
        2.0 * s / (a + b)
    } else {
        (a - (a * a - 2.0 * s * (a - b)).max(0.0).sqrt()) / (a - b)
    };
    if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// An RGL isotropic RGB material, evaluable at any direction pair.
#[derive(Clone, Debug)]
pub struct Rgl {
    /// File read.
    pub path: PathBuf,
    /// The file's description text.
    pub description: String,
    ndf: Interp2D,
    sigma: Interp2D,
    vndf: Interp2D,
    rgb: Interp2D,
    isotropic: bool,
    /// The file's `jacobian` flag (absent: set): whether the stored values
    /// still need the `ndf / (4 sigma)` factor.
    jacobian: bool,
    /// The largest tabulated incident elevation below 90 deg (radians).
    measured_theta_max: f64,
}

/// An RGL material restricted to its measured range, for resampling onto
/// MERL's table: pairs whose incident or outgoing elevation exceeds the
/// largest measured incidence ([`Rgl::measured_theta_max`]) get MERL's
/// invalid marker `-1` instead of a value. Beyond it the files hold only
/// the 90 deg node (not a measurement: a grazing incidence cannot be
/// measured), and `f = stored / cos theta_v` amplifies it without bound
/// near the horizon: `paper_white`, whose stored maximum is 8.5 1/sr,
/// would give bins within a degree of the horizon of up to 1081 1/sr.
/// By reciprocity the outgoing elevation has the same range.
pub struct MeasuredRange<'a>(pub &'a Rgl);

impl Brdf for MeasuredRange<'_> {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let limit = self.0.measured_theta_max.cos();
        if l.z < limit || v.z < limit {
            out[..3].fill(-1.0);
            return;
        }
        self.0.eval(l, v, out);
    }
}

/// An outgoing direction `V` with a smaller cosine counts as on the
/// horizon, where RGL evaluation returns 0 as below it: there
/// `f = stored / cos theta_v` has no finite value, because the stored
/// cosine-weighted values do not vanish at the horizon (`paper_white` at
/// exactly 90 deg would give 5e15 1/sr). `1e-6` is 0.00006 deg from the
/// horizon. The incident direction needs no such rule (nothing is divided
/// by its cosine; the files tabulate incidence up to 90 deg).
pub const HORIZON_COS: f64 = 1e-6;

/// What evaluating an [`Rgl`] table needs of the incident direction alone:
/// computed once for a run of pairs that share it ([`Brdf::eval_pairs`];
/// every term of a rendered pixel has the camera's direction there).
struct Incidence {
    l: Vector3<f64>,
    phi_i: f64,
    /// the `(phi_i, theta_i)` cell of the VNDF warp
    vndf: Corners,
    /// the `(phi_i, theta_i, channel)` cells of the RGB table
    rgb: [Corners; 3],
    /// `sigma(u_i)` (the projected area), when the file needs the factor
    sigma: f64,
}

fn theta2u(t: f64) -> f64 {
    (t * 2.0 / PI).max(0.0).sqrt()
}

fn phi2u(p: f64) -> f64 {
    (p + PI) / (2.0 * PI)
}

fn format_error(path: &Path, reason: String) -> IoError {
    IoError::Format {
        path: path.to_path_buf(),
        line: 0,
        reason,
    }
}

/// The shape and values of the f32 table `name` of rank `rank`, every value
/// finite.
fn table(
    tf: &TensorFile,
    path: &Path,
    name: &str,
    rank: usize,
) -> Result<(Vec<usize>, Vec<f64>), IoError> {
    let bad = |reason: String| format_error(path, reason);
    let f = tf
        .field(name)
        .ok_or_else(|| bad(format!("field `{name}` missing")))?;
    if f.shape.len() != rank {
        return Err(bad(format!(
            "field `{name}` has rank {}, expected {rank}",
            f.shape.len()
        )));
    }
    // The tables are f32 in every RGL file; any other type byte
    // (even one `to_f64` could read, such as u8) is a damaged file.
    if f.dtype != DTYPE_F32 {
        return Err(bad(format!(
            "field `{name}` has type byte {} ({}), expected {DTYPE_F32} (f32)",
            f.dtype,
            dtype_name(f.dtype)
        )));
    }
    let v = f.to_f64().ok_or_else(|| {
        bad(format!(
            "field `{name}` has dtype {}, expected f32",
            f.dtype
        ))
    })?;
    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
        return Err(bad(format!("field `{name}` value {k} is not finite")));
    }
    Ok((f.shape.clone(), v))
}

/// The largest tabulated incident elevation below 90 deg (90 deg when
/// there is none): the 90 deg node itself is not a measurement.
fn measured_theta_max(theta_i: &[f64]) -> f64 {
    let measured_theta_max = theta_i
        .iter()
        .copied()
        .filter(|t| *t < FRAC_PI_2 - 1e-6)
        .fold(f64::NAN, f64::max);
    if measured_theta_max.is_finite() {
        measured_theta_max
    } else {
        FRAC_PI_2
    }
}

/// The file's `jacobian` flag: whether the stored values still need the
/// `ndf / (4 sigma)` factor (absent: they do).
fn jacobian_flag(tf: &TensorFile, path: &Path) -> Result<bool, IoError> {
    Ok(match tf.field("jacobian") {
        None => true,
        Some(f) => match f.to_f64().as_deref() {
            Some([x]) => *x != 0.0,
            _ => {
                return Err(format_error(
                    path,
                    "field `jacobian`: expected one u8 or f32 flag".into(),
                ));
            }
        },
    })
}

impl Rgl {
    /// Read an RGL `.bsdf` file (RGB variant).
    pub fn read(path: &Path) -> Result<Self, IoError> {
        let bytes = std::fs::read(path).map_err(|source| IoError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(path, &bytes)
    }

    /// Parse the bytes of an RGL file.
    pub fn parse(path: &Path, bytes: &[u8]) -> Result<Self, IoError> {
        let tf = TensorFile::parse(path, bytes)?;
        let get = |name: &str, rank: usize| table(&tf, path, name, rank);
        let (_, theta_i) = get("theta_i", 1)?;
        let (_, phi_i) = get("phi_i", 1)?;
        let (ns, ndf) = get("ndf", 2)?;
        let (ss, sigma) = get("sigma", 2)?;
        let (vs, vndf) = get("vndf", 4)?;
        let (rs, rgb) = get("rgb", 5)?;
        if vs[0] != phi_i.len()
            || vs[1] != theta_i.len()
            || rs[0] != phi_i.len()
            || rs[1] != theta_i.len()
            || rs[2] != 3
        {
            return Err(format_error(
                path,
                format!(
                    "inconsistent shapes: vndf {vs:?}, rgb {rs:?}, {} phi_i, {} theta_i",
                    phi_i.len(),
                    theta_i.len()
                ),
            ));
        }
        let description = tf
            .field("description")
            .map(|f| String::from_utf8_lossy(&f.bytes).into_owned())
            .unwrap_or_default();
        let err = |what: &str| format_error(path, format!("field `{what}`: degenerate table"));
        let measured_theta_max = measured_theta_max(&theta_i);
        let isotropic = phi_i.len() <= 2;
        let jacobian = jacobian_flag(&tf, path)?;
        Ok(Self {
            path: path.to_path_buf(),
            description,
            ndf: Interp2D::new(ns[1], ns[0], &ndf, vec![], false).ok_or_else(|| err("ndf"))?,
            sigma: Interp2D::new(ss[1], ss[0], &sigma, vec![], false)
                .ok_or_else(|| err("sigma"))?,
            vndf: Interp2D::new(
                vs[3],
                vs[2],
                &vndf,
                vec![phi_i.clone(), theta_i.clone()],
                true,
            )
            .ok_or_else(|| err("vndf"))?,
            rgb: Interp2D::new(
                rs[4],
                rs[3],
                &rgb,
                vec![phi_i, theta_i, vec![0.0, 1.0, 2.0]],
                false,
            )
            .ok_or_else(|| err("rgb"))?,
            isotropic,
            jacobian,
            measured_theta_max,
        })
    }

    /// Whether the file is isotropic (one tabulated `phi_i`): its values
    /// depend on the azimuths only through `phi_m - phi_i`.
    pub fn is_isotropic(&self) -> bool {
        self.isotropic
    }

    /// The largest tabulated incident elevation below 90 deg (radians):
    /// the measured range (see [`MeasuredRange`]).
    pub fn measured_theta_max(&self) -> f64 {
        self.measured_theta_max
    }

    fn params(l: &Vector3<f64>) -> (f64, f64) {
        (l.y.atan2(l.x), l.z.clamp(-1.0, 1.0).acos())
    }

    /// The outgoing direction of sample-space point `s` for incident `l`,
    /// and the RGB value stored there (before [`Rgl::jacobian_factor`]).
    pub fn direction_of_sample(&self, l: &Vector3<f64>, s: [f64; 2]) -> (Vector3<f64>, [f64; 3]) {
        let (phi_i, theta_i) = Self::params(l);
        let u = self.vndf.sample(s, &[phi_i, theta_i]);
        let theta_m = u[0] * u[0] * PI / 2.0;
        let mut phi_m = (2.0 * u[1] - 1.0) * PI;
        if self.isotropic {
            phi_m += phi_i;
        }
        let m = Vector3::new(
            phi_m.cos() * theta_m.sin(),
            phi_m.sin() * theta_m.sin(),
            theta_m.cos(),
        );
        let v = 2.0 * m.dot(l) * m - l;
        let rgb = [0, 1, 2].map(|c| self.rgb.eval(s, &[phi_i, theta_i, c as f64]));
        (v, rgb)
    }

    /// The factor that turns a stored value into the BRDF:
    /// `ndf(u_m) / (4 sigma(u_i) cos theta_v)`, or `1 / cos theta_v` when the
    /// file's `jacobian` flag is 0.
    pub fn jacobian_factor(&self, l: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
        let m = (l + v).normalize();
        let inc = self.incidence(l);
        self.factor(&self.u_m(&m, inc.phi_i), inc.sigma, v.z)
    }

    fn factor(&self, u_m: &[f64; 2], sigma: f64, cos_v: f64) -> f64 {
        if !self.jacobian {
            return 1.0 / cos_v;
        }
        if !(sigma > 0.0) {
            return f64::NAN;
        }
        self.ndf.eval(*u_m, &[]) / (4.0 * sigma * cos_v)
    }

    fn incidence(&self, l: &Vector3<f64>) -> Incidence {
        let (phi_i, theta_i) = Self::params(l);
        let mut angles = Corners::one();
        self.rgb.extend(&mut angles, 0, phi_i);
        self.rgb.extend(&mut angles, 1, theta_i);
        let rgb = [0, 1, 2].map(|c| {
            let mut corners = angles;
            self.rgb.extend(&mut corners, 2, c as f64);
            corners
        });
        let sigma = if self.jacobian {
            self.sigma.eval([theta2u(theta_i), phi2u(phi_i)], &[])
        } else {
            1.0
        };
        Incidence {
            l: *l,
            phi_i,
            vndf: self.vndf.weights(&[phi_i, theta_i]),
            rgb,
            sigma,
        }
    }

    /// [`Brdf::eval`] with the incident direction's part done.
    fn eval_with(&self, inc: &Incidence, v: &Vector3<f64>, out: &mut [f64]) {
        out[..3].fill(0.0);
        let l = &inc.l;
        if !(l.z > 0.0 && v.z > HORIZON_COS) {
            return;
        }
        let sum = l + v;
        let len = sum.norm();
        if !(len > 0.0) {
            return;
        }
        let m = sum / len;
        let u_m = self.u_m(&m, inc.phi_i);
        let s = self.vndf.invert_at(u_m, &inc.vndf);
        let k = self.factor(&u_m, inc.sigma, v.z);
        if !(k.is_finite()) {
            return;
        }
        // Negative values come from out-of-gamut spectra: clamped, as the
        // format's authors do.
        let values = self.rgb.eval_many_at(s, &inc.rgb);
        for (o, x) in out.iter_mut().zip(values) {
            *o = x.max(0.0) * k;
        }
    }

    fn u_m(&self, m: &Vector3<f64>, phi_i: f64) -> [f64; 2] {
        let theta_m = m.z.clamp(-1.0, 1.0).acos();
        let phi_m = m.y.atan2(m.x);
        let y = phi2u(if self.isotropic { phi_m - phi_i } else { phi_m });
        [theta2u(theta_m), y - y.floor()]
    }
}

impl Brdf for Rgl {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_with(&self.incidence(l), v, out);
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        let n = pairs.len();
        let mut inc: Option<Incidence> = None;
        let mut f = [0.0; 3];
        for j in 0..n {
            let l = pairs.l(j);
            if inc.as_ref().is_none_or(|i| i.l != l) {
                inc = Some(self.incidence(&l));
            }
            if let Some(i) = &inc {
                self.eval_with(i, &pairs.v(j), &mut f);
            }
            for (c, x) in f.iter().enumerate() {
                out[c * n + j] = *x;
            }
        }
    }
}
