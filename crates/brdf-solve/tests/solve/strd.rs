//! The 27 StRD model functions: analytic gradients against central finite
//! differences at the certified solutions (and at both starts).

use brdf_solve::strd::{PROBLEMS, StrdModel, lre};

/// Certified values of a few problems per family (NIST), with a typical x.
fn points() -> Vec<(&'static str, Vec<f64>, Vec<f64>)> {
    vec![
        (
            "Bennett5",
            vec![-2.5235058043e3, 4.6736564644e1, 9.3218483193e-1],
            vec![8.0],
        ),
        ("BoxBOD", vec![2.1380940889e2, 5.4723748542e-1], vec![3.0]),
        (
            "Chwirut1",
            vec![1.9027818370e-1, 6.1314004477e-3, 1.0530908399e-2],
            vec![2.5],
        ),
        ("DanWood", vec![7.6886226176e-1, 3.8604055871], vec![1.5]),
        (
            "ENSO",
            vec![
                10.51, 3.076, 0.5328, 44.31, -1.623, 0.5255, 26.89, 0.2123, 1.497,
            ],
            vec![37.0],
        ),
        (
            "Eckerle4",
            vec![1.5543827178, 4.0888321754, 4.5154121844e2],
            vec![450.0],
        ),
        (
            "Gauss1",
            vec![98.78, 0.0105, 100.49, 67.48, 23.13, 71.99, 178.998, 18.39],
            vec![70.0],
        ),
        (
            "Hahn1",
            vec![
                1.0776, -0.1227, 4.086e-3, -1.426e-6, -5.761e-3, 2.405e-4, -1.231e-7,
            ],
            vec![300.0],
        ),
        (
            "Kirby2",
            vec![1.6745, -0.13927, 2.5961e-3, -1.7242e-3, 2.1665e-5],
            vec![40.0],
        ),
        (
            "Lanczos1",
            vec![0.0951, 1.0, 0.8607, 3.0, 1.5576, 5.0],
            vec![0.3],
        ),
        ("MGH09", vec![0.1928, 0.1913, 0.1231, 0.1361], vec![0.5]),
        ("MGH10", vec![5.6096e-3, 6.1813e3, 3.4522e2], vec![80.0]),
        (
            "MGH17",
            vec![0.3754, 1.9358, -1.4647, 0.01287, 0.02212],
            vec![100.0],
        ),
        ("Misra1b", vec![337.99, 3.9039e-4], vec![200.0]),
        ("Misra1c", vec![636.43, 2.0814e-4], vec![200.0]),
        ("Misra1d", vec![437.37, 3.0227e-4], vec![200.0]),
        (
            "Nelson",
            vec![2.5907, 5.6178e-9, -5.7701e-2],
            vec![16.0, 40.0],
        ),
        ("Rat42", vec![72.462, 2.6181, 0.067359], vec![30.0]),
        ("Rat43", vec![699.64, 5.2771, 0.75962, 1.2792], vec![5.0]),
        (
            "Roszman1",
            vec![0.20197, -6.1954e-6, 1204.5, -181.34],
            vec![-1000.0],
        ),
        (
            "Thurber",
            vec![1288.1, 1491.1, 583.24, 75.417, 0.96630, 0.39797, 0.049727],
            vec![-1.5],
        ),
    ]
}

#[test]
fn every_problem_has_a_model() {
    for name in PROBLEMS {
        assert!(StrdModel::for_problem(name).is_some(), "{name}");
    }
    assert!(StrdModel::for_problem("NotAProblem").is_none());
}

#[test]
fn gradients_match_central_differences() {
    for (name, b, x) in points() {
        let model = StrdModel::for_problem(name).unwrap();
        let n = model.n_params();
        assert_eq!(b.len(), n, "{name}");
        let mut g = vec![0.0; n];
        let mut scratch = vec![0.0; n];
        let f0 = model.eval(&x, &b, &mut g);
        assert!(f0.is_finite(), "{name}");
        for k in 0..n {
            let h = 1e-6 * b[k].abs().max(1e-4);
            let mut bp = b.clone();
            bp[k] += h;
            let fp = model.eval(&x, &bp, &mut scratch);
            bp[k] = b[k] - h;
            let fm = model.eval(&x, &bp, &mut scratch);
            let fd = (fp - fm) / (2.0 * h);
            // Truncation (relative 1e-6) plus rounding of f over the step.
            let tol = 1e-6 * g[k].abs() + 1e3 * f64::EPSILON * f0.abs() / h;
            assert!(
                (fd - g[k]).abs() <= tol,
                "{name} b{}: analytic {} vs fd {fd}",
                k + 1,
                g[k]
            );
        }
    }
}

#[test]
fn lre_definition() {
    assert!((lre(1.0001, 1.0) - 4.0).abs() < 1e-6);
    assert_eq!(lre(2.0, 2.0), 15.0);
    assert_eq!(lre(f64::NAN, 2.0), 0.0);
    assert_eq!(lre(5.0, 1.0), 0.0);
}
