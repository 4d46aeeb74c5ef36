//! The render of a BRDF from its shading terms, evaluated a row of terms at
//! a time.
//!
//! [`ShadingPoints::render`] could call `Brdf::eval` once per term: for a
//! renderer model that is the scalar formula, millions of times per
//! 128-pixel image, and for measured data a table look-up that repeats the
//! incident direction's work at every term of a pixel. Here each image
//! row's terms are gathered into direction pairs and evaluated by one
//! [`Brdf::eval_pairs`] call (the models' batch kernels; the RGL reader's
//! per-direction caching), and each pixel sums its terms in term order, so
//! the image is the same for any number of threads.

use brdf_core::{Brdf, DirPairs};
use rayon::prelude::*;

use crate::Image;
use crate::film::filter;
use crate::shading::{ShadedPixel, ShadingPoints};

/// Image rows per parallel task: one scratch serves them all.
const ROWS_PER_TASK: usize = 8;

/// Per-task scratch: a row's pairs and their values.
struct RowWork {
    pairs: DirPairs,
    values: Vec<f64>,
}

impl ShadingPoints {
    /// Render `brdf` (1 channel: grey, 3 channels: RGB) as an RGB image,
    /// evaluated as renderers do: `brdf.eval(v_local, l_local)`, the
    /// direction towards the camera first (see [`crate::shading`]).
    pub fn render(&self, brdf: &(impl Brdf + ?Sized)) -> Image {
        self.render_with(brdf, false)
    }

    /// Render with the arguments exchanged in every evaluation,
    /// `brdf.eval(l_local, v_local)` (reciprocity check: a reciprocal BRDF
    /// gives the same image).
    pub fn render_swapped(&self, brdf: &(impl Brdf + ?Sized)) -> Image {
        self.render_with(brdf, true)
    }

    fn render_with<B: Brdf + ?Sized>(&self, brdf: &B, swap: bool) -> Image {
        let size = self.size;
        let mut data = if self.background.len() == size * size * 3 {
            self.background.clone()
        } else {
            vec![0.0; size * size * 3]
        };
        // Pixels are in pixel order: the first pixel of each row.
        let row_start: Vec<usize> = (0..=size)
            .map(|r| self.pixels.partition_point(|p| p.pixel < r * size))
            .collect();
        let nc = brdf.channels().max(1);
        data.par_chunks_mut(size * 3 * ROWS_PER_TASK)
            .enumerate()
            .for_each(|(task, out)| {
                let rows = task * ROWS_PER_TASK..((task + 1) * ROWS_PER_TASK).min(size);
                let terms = |r: usize| {
                    let px = &self.pixels[row_start[r]..row_start[r + 1]];
                    px.iter().map(|p| p.end - p.start).sum::<usize>()
                };
                let most = rows.clone().map(terms).max().unwrap_or(0);
                let mut work = RowWork {
                    pairs: DirPairs::with_capacity(most),
                    values: Vec::with_capacity(nc * most),
                };
                for (r, row) in rows.zip(out.chunks_mut(size * 3)) {
                    let pixels = &self.pixels[row_start[r]..row_start[r + 1]];
                    self.shade_row(brdf, pixels, swap, &mut work, row);
                }
            });
        let mut image = Image {
            width: size,
            height: size,
            channels: 3,
            data,
        };
        if !self.film_mask.is_empty() {
            filter(&mut image);
        }
        image
    }

    /// One image row: its pixels' terms evaluated at once and summed per
    /// pixel, in term order, into `out` (the row's RGB).
    fn shade_row<B: Brdf + ?Sized>(
        &self,
        brdf: &B,
        pixels: &[ShadedPixel],
        swap: bool,
        work: &mut RowWork,
        out: &mut [f64],
    ) {
        work.pairs.clear();
        for p in pixels {
            for l in &self.l_local[p.start..p.end] {
                if swap {
                    work.pairs.push(l, &p.v_local);
                } else {
                    work.pairs.push(&p.v_local, l);
                }
            }
        }
        let n = work.pairs.len();
        let nc = brdf.channels().max(1);
        work.values.clear();
        work.values.resize(nc * n, 0.0);
        brdf.eval_pairs(&work.pairs, &mut work.values);
        let grey = nc < 3;
        let mut j = 0;
        for p in pixels {
            let mut acc = [0.0; 3];
            for w in &self.weight[p.start..p.end] {
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
            let x = p.pixel % self.size;
            for (o, a) in out[x * 3..x * 3 + 3].iter_mut().zip(acc) {
                *o += a;
            }
        }
    }
}
