//! Elementary functions written so that a loop calling them vectorises.
//!
//! The fitting kernels spend most of their time in `exp` (every power
//! `c^e` of a lobe is `exp(e ln c)` over a precomputed `ln c`), and a call
//! into the C library's scalar `exp` stops the compiler from vectorising the
//! loop around it. [`exp`] is straight-line arithmetic on `f64` and its bit
//! pattern (no table, no branch, no call), so a loop over arrays that calls
//! it compiles to SIMD code (AVX2 under `pulp::Arch::dispatch`, SSE2
//! otherwise) with the same result in every lane as the scalar code: no
//! fused multiply-adds are used, so the value does not depend on the
//! instruction set.
//!
//! Method (Cody & Waite 1980; Tang 1989): `x = k ln 2 + r` with
//! `k = round(x / ln 2)`, `|r| <= ln(2)/2`, the product `k ln 2` split in a
//! part exact in `f64` and a correction; `e^r` by its Taylor polynomial of
//! degree 13 (truncation `< 5e-18` relative); `2^k` assembled in the
//! exponent bits. Accuracy: within 2 ulp of the correctly rounded value on
//! `[-708, 709]` (tested against `f64::exp` in `tests/core/vmath.rs`).

/// `e^x`: within 2 ulp on `[-708, 709]`; `0` below `-708` (the true value
/// is below `3.4e-308`, at the edge of the normal range), `+inf` above
/// `709.78`, NaN for NaN.
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    const LOG2_E: f64 = std::f64::consts::LOG2_E;
    // ln 2 = LN2_HI + LN2_LO, LN2_HI with 32 trailing zero bits so that
    // `k * LN2_HI` is exact for |k| < 2^21 (fdlibm's split).
    const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
    const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
    // Adding 1.5 * 2^52 rounds to an integer held in the low mantissa bits.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let xc = x.clamp(-708.0, 709.0);
    let t = xc * LOG2_E + SHIFT;
    let k = t - SHIFT;
    let r = (xc - k * LN2_HI) - k * LN2_LO;
    let mut p = 1.0 / 6_227_020_800.0;
    p = p * r + 1.0 / 479_001_600.0;
    p = p * r + 1.0 / 39_916_800.0;
    p = p * r + 1.0 / 3_628_800.0;
    p = p * r + 1.0 / 362_880.0;
    p = p * r + 1.0 / 40_320.0;
    p = p * r + 1.0 / 5_040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    let ki = (t.to_bits() as i64).wrapping_sub(SHIFT.to_bits() as i64);
    let scale = f64::from_bits((ki.wrapping_add(1023) as u64) << 52);
    let y = p * scale;
    let y = if x < -708.0 { 0.0 } else { y };
    if x > 709.782_712_893_384 {
        f64::INFINITY
    } else {
        y
    }
}
