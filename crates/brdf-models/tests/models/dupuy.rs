//! Dupuy et al. 2015's extraction of a tabulated normal distribution by
//! power iteration on back-scattering data: exact (to the table's
//! quadrature) for data of the assumed form `rho(w) = F D(w) G1(w) /
//! (4 cos^2 theta)`, generated here from the crate's GGX `D` and `Lambda`
//! and from a Beckmann `D` and `Lambda` written in this file; the widths
//! read off the table and the channel factors match the generating ones;
//! extraction from a `SampleSet` agrees with extraction from a `Brdf`.

use std::f64::consts::PI;

use brdf_core::{Brdf, Direction, Parametric, SampleSet, central_difference_grad};
use brdf_models::dupuy::{ExtractOptions, TabulatedMicrofacet, TabulatedNdf};
use brdf_models::ggx::{ggx_d, smith_lambda};
use nalgebra::Vector3;

/// `erfc(a)`, `a >= 0`, by Simpson's rule on `[a, a + 9]` (error < 1e-13).
fn erfc(a: f64) -> f64 {
    let n = 20_000;
    let h = 9.0 / n as f64;
    let f = |t: f64| (-t * t).exp();
    let mut s = f(a) + f(a + 9.0);
    for i in 1..n {
        s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 / PI.sqrt() * s * h / 3.0
}

#[derive(Clone, Copy)]
enum Ndf {
    Ggx(f64),
    Beckmann(f64),
}

impl Ndf {
    fn d(self, h: &Vector3<f64>) -> f64 {
        match self {
            Ndf::Ggx(a) => ggx_d(h, a, a).0,
            Ndf::Beckmann(m) => {
                let c2 = h.z * h.z;
                let t2 = (1.0 - c2) / c2;
                (-t2 / (m * m)).exp() / (PI * m * m * c2 * c2)
            }
        }
    }
    fn lambda(self, w: &Vector3<f64>) -> f64 {
        match self {
            Ndf::Ggx(a) => smith_lambda(w, a, a).0,
            Ndf::Beckmann(m) => {
                let r = w.x.hypot(w.y);
                if r == 0.0 {
                    return 0.0;
                }
                let a = w.z / (m * r);
                0.5 * ((-a * a).exp() / (a * PI.sqrt()) - erfc(a))
            }
        }
    }
}

/// A microfacet BRDF with fully correlated masking-shadowing
/// (`G = min(G1(L), G1(V))`) and per-channel factors `F_c`.
struct Microfacet {
    ndf: Ndf,
    f: Vec<f64>,
}

impl Brdf for Microfacet {
    fn channels(&self) -> usize {
        self.f.len()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let h = (l + v).normalize();
        let g = (1.0 / (1.0 + self.ndf.lambda(l))).min(1.0 / (1.0 + self.ndf.lambda(v)));
        let s = self.ndf.d(&h) * g / (4.0 * l.z * v.z);
        for (o, f) in out.iter_mut().zip(&self.f) {
            *o = f * s;
        }
    }
}

/// Largest relative error of the table against `ndf` over the nodes up to
/// 85 deg where the projected density `D cos sin` is at least 1e-4 of its
/// peak (towards 90 deg `D = rho cos sigma` is a product with a vanishing
/// factor, and measured data stop before it).
fn table_error(t: &TabulatedNdf, ndf: Ndf) -> f64 {
    let (theta, d) = t.table();
    let dens: Vec<f64> = theta
        .iter()
        .zip(d)
        .map(|(th, x)| x * th.cos() * th.sin())
        .collect();
    let peak = dens.iter().cloned().fold(0.0, f64::max);
    theta
        .iter()
        .zip(d)
        .zip(&dens)
        .filter(|(_, p)| **p >= 1e-4 * peak)
        .map(|((&th, &x), _)| {
            let want = ndf.d(&Vector3::new(th.sin(), 0.0, th.cos()));
            if std::env::var("DBG").is_ok() {
                eprintln!("{th} {}", (x - want) / want);
            }
            ((x - want).abs() / want, th)
        })
        .filter(|(_, th)| *th <= 85f64.to_radians())
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a })
        .0
}

#[test]
fn extraction_recovers_ggx_and_beckmann() {
    for ndf in [
        Ndf::Ggx(0.1),
        Ndf::Ggx(0.3),
        Ndf::Ggx(0.6),
        Ndf::Beckmann(0.15),
        Ndf::Beckmann(0.4),
    ] {
        let data = Microfacet {
            ndf,
            f: vec![0.9, 0.5, 0.2],
        };
        // The extraction is exact up to the quadrature of sigma and of the
        // normalisation over the linearly interpolated table, an O(h^2)
        // error: quadrupling the nodes must shrink it about sixteenfold.
        let run = |nodes| {
            let opts = ExtractOptions {
                nodes,
                ..ExtractOptions::default()
            };
            let ex = TabulatedMicrofacet::from_brdf(&data, &opts).unwrap();
            assert!(ex.converged, "{} iterations", ex.iterations);
            let t = ex.model.ndf().clone();
            let (width, fitted) = match ndf {
                Ndf::Ggx(a) => (a, t.fit_ggx_alpha()),
                Ndf::Beckmann(m) => (m, t.fit_beckmann_alpha()),
            };
            let f_err = ex
                .model
                .params()
                .iter()
                .zip(&data.f)
                .map(|(got, want)| (got / want - 1.0).abs())
                .fold(0.0, f64::max);
            (table_error(&t, ndf), (fitted / width - 1.0).abs(), f_err, t)
        };
        let (coarse, coarse_w, _, _) = run(128);
        let (err, width_err, f_err, t) = run(512);
        eprintln!(
            "{:?}: D {coarse} -> {err}, width {coarse_w} -> {width_err}, F {f_err}",
            match ndf {
                Ndf::Ggx(a) => ("ggx", a),
                Ndf::Beckmann(m) => ("beckmann", m),
            }
        );
        assert!(
            err < 1e-4 && err < coarse / 8.0,
            "D error {err} (128 nodes: {coarse})"
        );
        assert!(
            width_err < 5e-5 && width_err < coarse_w / 8.0,
            "width error {width_err} ({coarse_w})"
        );
        assert!(f_err < 5e-5, "F error {f_err}");
        // The wrong family reads off a width, but does not fit as well:
        // the table is not a GGX when it came from Beckmann and back.
        if let Ndf::Beckmann(m) = ndf {
            assert!((t.fit_ggx_alpha() / m - 1.0).abs() > 1e-2);
        }
    }
}

#[test]
fn tabulated_model_reproduces_the_generating_brdf() {
    let ndf = Ndf::Ggx(0.3);
    let data = Microfacet { ndf, f: vec![0.7] };
    let ex = TabulatedMicrofacet::from_brdf(&data, &ExtractOptions::default()).unwrap();
    for (ti, pi_, to, po) in [
        (0.0, 0.0, 0.0, 0.0),
        (0.4, 0.0, 0.4, 3.0),
        (1.0, 0.5, 0.3, 2.0),
        (1.3, 0.0, 1.2, 3.0),
    ] {
        let l = brdf_core::spherical_to_cartesian(ti, pi_);
        let v = brdf_core::spherical_to_cartesian(to, po);
        let (mut a, mut b) = ([0.0], [0.0]);
        ex.model.eval(&l, &v, &mut a);
        data.eval(&l, &v, &mut b);
        assert!((a[0] / b[0] - 1.0).abs() < 1e-3, "{} vs {}", a[0], b[0]);
        let mut c = [0.0];
        ex.model.eval(&v, &l, &mut c);
        assert_eq!(a[0], c[0], "reciprocity");
    }
    // Derivatives in the channel factors.
    let p = ex.model.params().to_vec();
    let (l, v) = (
        brdf_core::spherical_to_cartesian(0.5, 0.0),
        brdf_core::spherical_to_cartesian(0.6, 2.5),
    );
    let (mut out, mut g, mut fd) = ([0.0], [0.0], [0.0]);
    ex.model.eval_grad_at(&p, &l, &v, &mut out, &mut g);
    central_difference_grad(&ex.model, &p, &l, &v, &mut fd);
    assert!((g[0] - fd[0]).abs() < 1e-8 * g[0].abs());
}

#[test]
fn extraction_from_a_sample_set_matches() {
    let ndf = Ndf::Ggx(0.25);
    let data = Microfacet { ndf, f: vec![0.6] };
    let mut set = SampleSet::new("ggx back-scattering", "generated", vec!["grey".into()]);
    let mut f = [0.0];
    for k in 0..400 {
        // Back-scattering at scattered azimuths (the table is isotropic),
        // plus an off-diagonal pair that must be ignored.
        let th = 1.5 * (k as f64 / 399.0);
        let w = Direction::from_spherical(th, 0.37 * k as f64).unwrap();
        data.eval(w.vector(), w.vector(), &mut f);
        set.push(&w, &w, &f, 1.0).unwrap();
    }
    let l = Direction::from_spherical(0.3, 0.0).unwrap();
    let v = Direction::from_spherical(0.5, 2.0).unwrap();
    set.push(&l, &v, &[1e3], 1.0).unwrap();
    let ex = TabulatedMicrofacet::from_samples(&set, &ExtractOptions::default()).unwrap();
    let alpha = ex.model.ndf().fit_ggx_alpha();
    assert!((alpha / 0.25 - 1.0).abs() < 1e-3, "{alpha}");
    assert!((ex.model.params()[0] / 0.6 - 1.0).abs() < 1e-3);
}

#[test]
fn too_few_samples_is_an_error_naming_the_set() {
    let mut set = SampleSet::new("tiny", "generated", vec!["grey".into()]);
    let w = Direction::from_spherical(0.3, 0.0).unwrap();
    set.push(&w, &w, &[0.5], 1.0).unwrap();
    let e = TabulatedMicrofacet::from_samples(&set, &ExtractOptions::default()).unwrap_err();
    assert!(
        matches!(&e, brdf_core::ParamError::Data { data, .. } if data == "tiny (generated)"),
        "{e}"
    );
    assert!(e.to_string().contains("has 1 of the 2 needed"), "{e}");
    assert!(e.to_string().contains("`--model std`"), "{e}");
    let e = TabulatedNdf::from_fn(4, |_| 1.0).unwrap_err();
    assert!(e.to_string().contains("at least 8 nodes"), "{e}");
}
