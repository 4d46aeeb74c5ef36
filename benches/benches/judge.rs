//! What every fit of renderable data pays besides its solves:
//! the judge's quadrature of the standard light sets (`judge/setup/<px>`,
//! independent of the data), the data rendered through it
//! (`judge/render-data/<px>`, here a principled model standing in for a
//! measured file: the RGL files are not needed to build or run this), and
//! one Jacobian pass of the image objective at the fit size
//! (`judge/image-objective/gram`: the model's values and derivatives at
//! every shading term, summed into pixels, and the normal equations).
//! `results/performance.md` has the whole commands; these are their parts.

use std::hint::black_box;
use std::time::Duration;

use brdf_core::Parametric;
use brdf_fit::appearance::{FIT_SIZE, Judge, REPORT_SIZE, image_terms};
use brdf_fit::image_objective::{ImageProblem, ImageTarget};
use brdf_models::Principled;
use brdf_solve::LeastSquaresProblem;
use criterion::{Criterion, criterion_group, criterion_main};

/// A principled material with every lobe on (no branch skipped).
fn material() -> Option<Principled> {
    let p = [0.6, 0.4, 0.2, 0.3, 0.5, 0.4, 0.5, 0.2, 0.3, 0.5, 0.3, 0.6];
    Principled::new(3, &p)
        .map_err(|e| eprintln!("principled: {e}"))
        .ok()
}

fn judge(c: &mut Criterion) {
    let Some(model) = material() else { return };
    let mut g = c.benchmark_group("judge");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    for size in [FIT_SIZE, REPORT_SIZE] {
        g.bench_function(format!("setup/{size}"), |b| {
            b.iter(|| black_box(Judge::new(black_box(size)).size()))
        });
        let judge = Judge::new(size);
        g.bench_function(format!("render-data/{size}"), |b| {
            b.iter(|| black_box(judge.rendering(&model).map(|j| j.size())))
        });
    }
    match image_terms(FIT_SIZE) {
        Ok(terms) => {
            let target = ImageTarget::new(terms, &model, 3, model.params().to_vec());
            match ImageProblem::new(&model, &target.terms, &target.reference, &target.exposures) {
                Ok(problem) => {
                    let (m, w) = (problem.n_residuals(), problem.n_params() + 1);
                    let (mut r, mut gram) = (vec![0.0; m], vec![0.0; w * w]);
                    let p = model.params().to_vec();
                    g.bench_function("image-objective/gram", |b| {
                        b.iter(|| black_box(problem.residuals_and_gram(&p, &mut r, &mut gram)))
                    });
                }
                Err(e) => eprintln!("image problem: {e}"),
            }
        }
        Err(e) => eprintln!("image terms: {e}"),
    }
    g.finish();
}

criterion_group!(benches, judge);
criterion_main!(benches);
