//! Forward-mode dual numbers for the renderer models whose parameters are
//! tangled in many places (Disney principled, glTF): each formula is
//! written once over [`Dual`], and evaluating it with seeded parameters
//! gives the value and the exact parameter derivatives (no truncation
//! error, unlike finite differences).
//!
//! A dual carries up to [`MAX_DERIV`] partial derivatives, of which the
//! first `n` are live; constants have `n = 0`, so evaluating without
//! derivatives costs little more than plain `f64` arithmetic.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Largest number of parameters a dual can differentiate in.
pub const MAX_DERIV: usize = 24;

/// `v + sum_k d_k eps_k`.
///
/// `N` is the room for derivatives: the value-only path runs with `N = 0`
/// (no derivative storage to clear or copy), the gradient path with the
/// smallest `N` that holds the model's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const N: usize = MAX_DERIV> {
    /// Value.
    pub v: f64,
    /// Partial derivatives (entries `n..` are 0).
    pub d: [f64; N],
    /// Number of live derivatives.
    pub n: usize,
}

impl<const N: usize> Dual<N> {
    /// A constant.
    #[inline]
    pub fn c(v: f64) -> Self {
        Dual {
            v,
            d: [0.0; N],
            n: 0,
        }
    }

    /// Independent variable `i` of `n` (with `n = 0`: no derivatives).
    #[inline]
    pub fn var(v: f64, i: usize, n: usize) -> Self {
        let mut x = Dual::c(v);
        if n > 0 {
            x.d[i] = 1.0;
            x.n = n;
        }
        x
    }

    /// `g(self)` given `g(v)` and `g'(v)`.
    #[inline]
    pub fn chain(&self, value: f64, slope: f64) -> Self {
        let mut r = Dual::c(value);
        r.n = self.n;
        for k in 0..self.n {
            r.d[k] = slope * self.d[k];
        }
        r
    }

    /// `g(self, b)` given `g`, `dg/dself` and `dg/db`.
    #[inline]
    pub fn chain2(&self, b: &Dual<N>, value: f64, da: f64, db: f64) -> Self {
        let mut r = Dual::c(value);
        r.n = self.n.max(b.n);
        for k in 0..r.n {
            r.d[k] = da * self.d[k] + db * b.d[k];
        }
        r
    }

    /// Square root; the derivative at 0 is taken as 0 (callers keep
    /// arguments away from 0 where the derivative matters).
    #[inline]
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, if s > 0.0 { 0.5 / s } else { 0.0 })
    }

    /// Natural logarithm.
    #[inline]
    pub fn ln(self) -> Self {
        self.chain(self.v.ln(), 1.0 / self.v)
    }

    /// `self^2`.
    #[inline]
    pub fn sq(self) -> Self {
        self * self
    }

    /// The larger of `self` and the constant `b` (derivative 0 when `b` wins).
    #[inline]
    pub fn max_c(self, b: f64) -> Self {
        if self.v >= b { self } else { Dual::c(b) }
    }

    /// The smaller of `self` and the constant `b`.
    #[inline]
    pub fn min_c(self, b: f64) -> Self {
        if self.v <= b { self } else { Dual::c(b) }
    }

    /// The larger of two duals.
    #[inline]
    pub fn max(self, b: Dual<N>) -> Self {
        if self.v >= b.v { self } else { b }
    }

    /// Linear interpolation `a (1 - t) + b t` with weight `t = self`.
    #[inline]
    pub fn lerp(self, a: Dual<N>, b: Dual<N>) -> Self {
        a + (b - a) * self
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn add(self, b: Dual<N>) -> Dual<N> {
        self.chain2(&b, self.v + b.v, 1.0, 1.0)
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn sub(self, b: Dual<N>) -> Dual<N> {
        self.chain2(&b, self.v - b.v, 1.0, -1.0)
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn mul(self, b: Dual<N>) -> Dual<N> {
        self.chain2(&b, self.v * b.v, b.v, self.v)
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn div(self, b: Dual<N>) -> Dual<N> {
        let q = self.v / b.v;
        self.chain2(&b, q, 1.0 / b.v, -q / b.v)
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn neg(self) -> Dual<N> {
        self.chain(-self.v, -1.0)
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn add(self, b: f64) -> Dual<N> {
        self.chain(self.v + b, 1.0)
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn sub(self, b: f64) -> Dual<N> {
        self.chain(self.v - b, 1.0)
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn mul(self, b: f64) -> Dual<N> {
        self.chain(self.v * b, b)
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Dual<N>;
    #[inline]
    fn div(self, b: f64) -> Dual<N> {
        self.chain(self.v / b, 1.0 / b)
    }
}

impl<const N: usize> Add<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn add(self, b: Dual<N>) -> Dual<N> {
        b + self
    }
}

impl<const N: usize> Sub<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn sub(self, b: Dual<N>) -> Dual<N> {
        b.chain(self - b.v, -1.0)
    }
}

impl<const N: usize> Mul<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn mul(self, b: Dual<N>) -> Dual<N> {
        b * self
    }
}

impl<const N: usize> Div<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn div(self, b: Dual<N>) -> Dual<N> {
        let q = self / b.v;
        b.chain(q, -q / b.v)
    }
}

/// The parameter vector `p` as duals: seeded variables when `grad`, else
/// constants. Writes `p.len()` entries into `out`.
pub fn seed<const N: usize>(p: &[f64], grad: bool, out: &mut [Dual<N>]) {
    let n = if grad { p.len() } else { 0 };
    for (i, (&x, o)) in p.iter().zip(out.iter_mut()).enumerate() {
        *o = Dual::var(x, i, n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_a_composite() {
        // f(x, y) = sqrt(x y) / (1 + x) + ln(y); at (2, 3):
        // df/dx = y / (2 sqrt(xy) (1+x)) - sqrt(xy)/(1+x)^2,
        // df/dy = x / (2 sqrt(xy) (1+x)) + 1/y.
        let x = Dual::<2>::var(2.0, 0, 2);
        let y = Dual::<2>::var(3.0, 1, 2);
        let f = (x * y).sqrt() / (1.0 + x) + y.ln();
        let s = 6f64.sqrt();
        assert!((f.v - (s / 3.0 + 3f64.ln())).abs() < 1e-15);
        assert!((f.d[0] - (3.0 / (2.0 * s * 3.0) - s / 9.0)).abs() < 1e-15);
        assert!((f.d[1] - (2.0 / (2.0 * s * 3.0) + 1.0 / 3.0)).abs() < 1e-15);
    }
}
