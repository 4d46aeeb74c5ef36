//! Variable projection on a sum of exponentials (the Lanczos problem,
//! linear amplitudes, non-linear rates): the reduced Jacobian against
//! central differences, recovery of the generating parameters from
//! deterministic multi-start, and the non-negative variant.

use brdf_solve::multistart::{StartBox, multistart};
use brdf_solve::{
    Constraints, LeastSquaresProblem, LmOptions, SeparableProblem, VarPro, bounded_least_squares,
    fd_jacobian, levenberg_marquardt,
};

struct Exps {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl Exps {
    fn lanczos(amp: [f64; 3], rate: [f64; 3]) -> Self {
        // Lanczos (1956): x = 0, 0.05, ..., 1.15.
        let x: Vec<f64> = (0..24).map(|i| 0.05 * i as f64).collect();
        let y = x
            .iter()
            .map(|x| (0..3).map(|k| amp[k] * (-rate[k] * x).exp()).sum())
            .collect();
        Self { x, y }
    }
}

impl SeparableProblem for Exps {
    fn n_nonlinear(&self) -> usize {
        3
    }
    fn n_linear(&self) -> usize {
        3
    }
    fn n_rows(&self) -> usize {
        self.x.len()
    }
    fn targets(&self) -> &[f64] {
        &self.y
    }
    fn basis(&self, a: &[f64], phi: &mut [f64], dphi: Option<&mut [f64]>) {
        let m = self.x.len();
        for j in 0..3 {
            for i in 0..m {
                phi[j * m + i] = (-a[j] * self.x[i]).exp();
            }
        }
        if let Some(d) = dphi {
            d.fill(0.0);
            for k in 0..3 {
                for i in 0..m {
                    d[k * m * 3 + k * m + i] = -self.x[i] * (-a[k] * self.x[i]).exp();
                }
            }
        }
    }
}

#[test]
fn reduced_jacobian_matches_differences() {
    let p = Exps::lanczos([0.0951, 0.8607, 1.5576], [1.0, 3.0, 5.0]);
    // Perturb the data so the residual is not zero (the second term of the
    // Golub-Pereyra Jacobian matters only then).
    let p = Exps {
        y: p.y
            .iter()
            .enumerate()
            .map(|(i, v)| v + 1e-2 * ((i * 7919) % 13) as f64 / 13.0)
            .collect(),
        x: p.x,
    };
    for nonneg in [false, true] {
        let vp = VarPro::new(&p, nonneg);
        let a = [0.7, 2.5, 6.0];
        let mut ja = vec![0.0; 24 * 3];
        let mut jf = vec![0.0; 24 * 3];
        vp.jacobian(&a, &mut ja);
        fd_jacobian(&vp, &a, &mut jf);
        let scale = jf.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..ja.len() {
            assert!(
                (ja[i] - jf[i]).abs() < 1e-7 * scale,
                "nonneg {nonneg} entry {i}: {} vs {}",
                ja[i],
                jf[i]
            );
        }
    }
}

#[test]
fn recovers_lanczos_parameters_from_automatic_starts() {
    let amp = [0.0951, 0.8607, 1.5576];
    let rate = [1.0, 3.0, 5.0];
    let p = Exps::lanczos(amp, rate);
    let vp_opts = LmOptions::default();
    let starts = StartBox {
        lower: vec![0.1; 3],
        upper: vec![10.0; 3],
        log_scale: vec![true; 3],
    }
    .starts(16)
    .unwrap();
    let c = Constraints::boxed(vec![1e-3; 3], vec![100.0; 3]).unwrap();
    let ms = multistart(&starts, |s| {
        let vp = VarPro::new(&p, true);
        bounded_least_squares(&vp, s, &c, &vp_opts)
    })
    .unwrap();
    assert!(ms.n_at_best >= 1);
    let mut a = ms.best.params.clone();
    let vp = VarPro::new(&p, true);
    let mut cc = vp.linear_coefficients(&a).unwrap();
    // Order the three terms by rate (the problem is symmetric under swaps).
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|i, j| a[*i].total_cmp(&a[*j]));
    let (a2, c2): (Vec<f64>, Vec<f64>) = idx.iter().map(|i| (a[*i], cc[*i])).unzip();
    a = a2;
    cc = c2;
    for k in 0..3 {
        assert!((a[k] - rate[k]).abs() < 1e-6 * rate[k], "rates {a:?}");
        assert!((cc[k] - amp[k]).abs() < 1e-6 * amp[k], "amplitudes {cc:?}");
    }
    // Deterministic: the same starts give the same answer.
    let again = StartBox {
        lower: vec![0.1; 3],
        upper: vec![10.0; 3],
        log_scale: vec![true; 3],
    }
    .starts(16)
    .unwrap();
    assert_eq!(starts, again);
}

#[test]
fn unconstrained_varpro_solves_from_nist_start() {
    // Lanczos1's second certified start for the rates (0.7, 4.2, 6.3).
    let p = Exps::lanczos([0.0951, 0.8607, 1.5576], [1.0, 3.0, 5.0]);
    let vp = VarPro::new(&p, false);
    let rep = levenberg_marquardt(&vp, &[0.7, 4.2, 6.3], &LmOptions::default()).unwrap();
    assert!(rep.termination.is_converged(), "{:?}", rep.termination);
    let mut a = rep.params.clone();
    a.sort_by(|x, y| x.total_cmp(y));
    assert!(
        (a[0] - 1.0).abs() < 1e-6 && (a[1] - 3.0).abs() < 1e-6 && (a[2] - 5.0).abs() < 1e-6,
        "{a:?}"
    );
}

#[test]
fn halton_starts_respect_the_box() {
    let b = StartBox {
        lower: vec![1.0, -1.0],
        upper: vec![1e4, 1.0],
        log_scale: vec![true, false],
    };
    let s = b.starts(50).unwrap();
    assert_eq!(s.len(), 50);
    for p in &s {
        assert!(p[0] >= 1.0 && p[0] <= 1e4 && p[1] >= -1.0 && p[1] <= 1.0);
    }
    // First Halton points: base 2 gives 1/2, base 3 gives 1/3.
    assert!(
        (s[0][0] - 100.0).abs() < 1e-9,
        "log-scale midpoint {}",
        s[0][0]
    );
    assert!((s[0][1] - (-1.0 + 2.0 / 3.0)).abs() < 1e-12);
    let bad = StartBox {
        lower: vec![0.0],
        upper: vec![1.0],
        log_scale: vec![true],
    };
    assert!(bad.starts(3).is_err());
}

/// Linear coefficients within a box: Lanczos's amplitudes are
/// (0.0951, 0.8607, 1.5576); with the third at most 1.5 it sits on that
/// bound, and the other two are the least-squares fit of `y - 1.5 phi_3` by
/// `phi_1, phi_2` (solved here independently by the normal equations;
/// 0.0807 and 0.9265, inside their box [0, 1]).
#[test]
fn linear_coefficients_in_box_put_the_third_amplitude_on_its_bound() {
    let rates = [1.0, 3.0, 5.0];
    let p = Exps::lanczos([0.0951, 0.8607, 1.5576], rates);
    let vp = VarPro::new(&p, true);
    let free = vp.linear_coefficients(&rates).unwrap();
    assert!((free[2] - 1.5576).abs() < 1e-9, "{free:?}");
    let c = vp
        .linear_coefficients_in_box(&rates, &[0.0; 3], &[1.0, 1.0, 1.5])
        .unwrap();
    assert!((c[2] - 1.5).abs() < 1e-9, "{c:?}");
    // Reference: 2 x 2 normal equations for y - 1.5 phi_3.
    let phi = |k: usize, x: f64| (-rates[k] * x).exp();
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (x, y) in p.x.iter().zip(&p.y) {
        let (u, v, r) = (phi(0, *x), phi(1, *x), y - 1.5 * phi(2, *x));
        a11 += u * u;
        a12 += u * v;
        a22 += v * v;
        b1 += u * r;
        b2 += v * r;
    }
    let det = a11 * a22 - a12 * a12;
    let reference = [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det];
    assert!(
        reference.iter().all(|r| (0.0..=1.0).contains(r)),
        "{reference:?}"
    );
    for k in 0..2 {
        assert!(
            (c[k] - reference[k]).abs() < 1e-6 * reference[k].abs().max(1.0),
            "{c:?} vs {reference:?}"
        );
    }
    // Wrong box sizes are an error, not a panic.
    assert!(
        vp.linear_coefficients_in_box(&rates, &[0.0; 2], &[1.0; 3])
            .is_err()
    );
}
