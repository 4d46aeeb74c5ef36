//! The fit for appearance fits the candidates of each stage in parallel and
//! decides in their fixed order: its choice, every candidate and the fitted
//! parameters are the same for any thread count.

use brdf_core::Parametric;
use brdf_fit::appearance::{Candidate, fit_for_appearance};

use crate::common;
use common::{principled_at, rgb_fit, rgb_samples};

/// What a fit for appearance decides: the parameters and, per candidate,
/// everything but its seconds.
fn decided(threads: usize, data: &dyn Parametric) -> (Vec<f64>, Vec<Candidate>) {
    let s = rgb_samples(data, 1500);
    let fit = rgb_fit("principled");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool");
    let (report, mut candidates) = pool
        .install(|| fit_for_appearance(&fit, &s, data))
        .expect("fit");
    for c in &mut candidates {
        c.seconds = 0.0;
    }
    (report.model.params().to_vec(), candidates)
}

#[test]
fn one_thread_and_three_decide_the_same() {
    // A glossy dielectric with a faint sheen: the lobe trials run too.
    let data = principled_at(&[0.5, 0.2, 0.6, 0.0, 0.5, 0.0, 0.3, 0.0, 0.4, 0.5, 0.0, 0.0]);
    let (p1, c1) = decided(1, data.as_ref());
    let (p3, c3) = decided(3, data.as_ref());
    // Stages of several candidates: a thread count could reorder them.
    assert!(c1.len() >= 6, "{} candidates", c1.len());
    assert_eq!(p1, p3);
    assert_eq!(c1.len(), c3.len());
    for (a, b) in c1.iter().zip(&c3) {
        assert_eq!(a.objective, b.objective);
        assert_eq!(a.lobes, b.lobes);
        assert_eq!(a.chosen, b.chosen);
        assert_eq!(a.ngan_l2.to_bits(), b.ngan_l2.to_bits());
        assert_eq!(a.image, b.image);
    }
}
