//! Renders of the judge sphere through batch evaluation, and the image
//! errors of a fit against a data render made once.
//!
//! `brdf_render::ShadingPoints::render` calls `Brdf::eval` once per shading
//! term: for a renderer model that is the scalar (dual-number) formula,
//! millions of times per 128-pixel image. Here each image row's terms are
//! gathered into direction pairs and evaluated by one
//! [`Brdf::eval_pairs`] call (the models' batch kernels), and each pixel
//! sums its terms in the same order as `ShadingPoints::render`, so the
//! image is the same for any number of threads. The data's render does not
//! depend on the fit: [`Reference`] keeps it, so ranking candidates renders
//! the data once, not once per candidate.

use brdf_core::{Brdf, DirPairs};
use brdf_render::colour::{delta_e_mean_colours, mean_colour};
use brdf_render::compare::ImageErrors;
use brdf_render::flip::hdr_flip;
use brdf_render::psnr::psnr;
use brdf_render::tonemap::p99_exposure;
use brdf_render::{Image, RenderError, ShadingPoints};
use rayon::prelude::*;

/// Per-task scratch of [`render`]: a row's pairs and their values.
struct RowWork {
    pairs: DirPairs,
    values: Vec<f64>,
}

/// Image rows per parallel task of [`render`].
const ROWS_PER_TASK: usize = 8;

/// One image row: its pixels' terms gathered into pairs, evaluated at
/// once, and summed per pixel in term order into `out` (the row's RGB).
fn shade_row(
    sp: &ShadingPoints,
    brdf: &dyn Brdf,
    pixels: &[brdf_render::shading::ShadedPixel],
    nc: usize,
    work: &mut RowWork,
    out: &mut [f64],
) {
    work.pairs.clear();
    for p in pixels {
        // The renderers' order, as ShadingPoints::render (camera first).
        for l in &sp.l_local[p.start..p.end] {
            work.pairs.push(&p.v_local, l);
        }
    }
    let n = work.pairs.len();
    work.values.clear();
    work.values.resize(nc * n, 0.0);
    brdf.eval_pairs(&work.pairs, &mut work.values);
    let grey = nc < 3;
    let size = sp.size;
    let mut j = 0;
    for p in pixels {
        let mut acc = [0.0; 3];
        for w in &sp.weight[p.start..p.end] {
            for (c, a) in acc.iter_mut().enumerate() {
                let f = if grey {
                    work.values[j]
                } else {
                    work.values[c * n + j]
                };
                *a += w[c] * f;
            }
            j += 1;
        }
        // Added, not stored: with Mitsuba's film a silhouette pixel has
        // several entries (its sub-samples), on top of the background.
        let x = p.pixel % size;
        for (o, a) in out[x * 3..x * 3 + 3].iter_mut().zip(acc) {
            *o += a;
        }
    }
}

/// `brdf` rendered on the shading terms `sp` (as `sp.render(brdf)`, with
/// the BRDF evaluated a row of terms at a time).
pub fn render(sp: &ShadingPoints, brdf: &dyn Brdf) -> Image {
    let size = sp.size;
    let mut data = if sp.background.len() == size * size * 3 {
        sp.background.clone()
    } else {
        vec![0.0; size * size * 3]
    };
    let row_start: Vec<usize> = (0..=size)
        .map(|r| sp.pixels.partition_point(|p| p.pixel < r * size))
        .collect();
    let nc = brdf.channels().max(1);
    // Tasks of several rows, each with one scratch sized for its rows.
    data.par_chunks_mut(size * 3 * ROWS_PER_TASK)
        .enumerate()
        .for_each(|(task, out)| {
            let rows = task * ROWS_PER_TASK..((task + 1) * ROWS_PER_TASK).min(size);
            let terms = |r: usize| {
                let px = &sp.pixels[row_start[r]..row_start[r + 1]];
                px.iter().map(|p| p.end - p.start).sum::<usize>()
            };
            let most = rows.clone().map(terms).max().unwrap_or(0);
            let mut work = RowWork {
                pairs: DirPairs::with_capacity(most),
                values: Vec::with_capacity(nc * most),
            };
            for (r, row) in rows.zip(out.chunks_mut(size * 3)) {
                let pixels = &sp.pixels[row_start[r]..row_start[r + 1]];
                shade_row(sp, brdf, pixels, nc, &mut work, row);
            }
        });
    let mut image = Image {
        width: size,
        height: size,
        channels: 3,
        data,
    };
    // Mitsuba's pixel filter, as `ShadingPoints::render` applies it.
    if !sp.film_mask.is_empty() {
        brdf_render::film::filter(&mut image);
    }
    image
}

/// The data's render under one light set, with what every comparison
/// against it needs (sphere mask, exposure, mean colour).
pub struct Reference {
    image: Image,
    mask: Vec<bool>,
    exposure: f64,
    mean_colour: [f64; 3],
}

impl Reference {
    /// Render `data` on `sp`.
    pub fn new(sp: &ShadingPoints, data: &dyn Brdf) -> Result<Self, RenderError> {
        let image = render(sp, data);
        let mask = sp.mask();
        let exposure = p99_exposure(&image, Some(&mask))?;
        let mean_colour = mean_colour(&image, &mask);
        Ok(Reference {
            image,
            mask,
            exposure,
            mean_colour,
        })
    }

    /// The image errors of `fit` rendered on `sp` (the terms this
    /// reference was rendered on), as `brdf_render::compare::compare_with`.
    pub fn errors(&self, sp: &ShadingPoints, fit: &dyn Brdf) -> Result<ImageErrors, RenderError> {
        let t = render(sp, fit);
        let mean_colour_test = mean_colour(&t, &self.mask);
        Ok(ImageErrors {
            flip: hdr_flip(&self.image, &t)?,
            psnr: psnr(&self.image, &t, self.exposure)?,
            delta_e_mean_colour: delta_e_mean_colours(self.mean_colour, mean_colour_test),
            mean_colour_ref: self.mean_colour,
            mean_colour_test,
            exposure: self.exposure,
        })
    }
}

#[cfg(test)]
mod tests {
    use brdf_render::LightSet;

    use super::*;

    /// The batched render is the scalar render (to rounding: the batch
    /// kernels and the scalar formulas differ in operation order).
    #[test]
    fn batched_render_matches_the_scalar_render() {
        let config = brdf_models::catalogue::ModelConfig {
            channels: 3,
            ..Default::default()
        };
        let mut m = brdf_models::catalogue::build("principled", &config).expect("model");
        let mut p = m.params().to_vec();
        p[0] = 0.7;
        p[6] = 0.3;
        m.set_params(&p).expect("params");
        let brdf: &dyn Brdf = m.as_ref();
        for light in [LightSet::sky(), LightSet::studio()] {
            let sp = ShadingPoints::judge_with_background(&light, 24);
            let (a, b) = (sp.render(brdf), render(&sp, brdf));
            let peak = a.data.iter().fold(0.0f64, |x, y| x.max(y.abs()));
            assert!(peak > 0.0);
            for (x, y) in a.data.iter().zip(&b.data) {
                assert!((x - y).abs() <= 1e-12 * peak, "{x} vs {y}");
            }
        }
    }
}
