//! Kurt's Table 9.3 stand-in and his renderings (Figures 9.1-9.3, 9.6) on
//! the dense measured materials available here: the nine models of Table
//! 9.2 fitted (RGB, automatic starts) to each RGL material (resampled onto
//! Sopp's grid, 80-degree limit, cell weights, every 5th node) and to each Cornell paint
//! (its scattered samples); L2 error for all, and for the RGL materials the
//! PSNR of a sphere rendered with the fit against the sphere rendered with
//! the measured data (Cornell data are scattered and cannot be rendered
//! without an interpolation the project does not invent). The reciprocity
//! check of Fig. 9.6: the polynomial fit rendered with `L` and `V` swapped
//! must give the same image.

use std::path::Path;

use brdf_core::metrics::psnr;

use brdf_models::ModelConfig;
use nalgebra::Vector3;

use crate::StudyError;
use crate::kurt_tables::{fit_catalogue, nine_models};
use crate::render::{Image, render_sphere};
use crate::report::{Cell, Table};

const SIZE: usize = 96;

fn light() -> Vector3<f64> {
    Vector3::new(0.5, 0.5, 0.707).normalize()
}

/// Fit, render and score every material; returns the files written.
pub fn write(data_root: &Path, out: &Path) -> Result<Vec<String>, StudyError> {
    let models = nine_models();
    let mut hdr = vec!["material".to_string()];
    for (label, _, _) in &models {
        hdr.push(format!("{label} L2"));
        hdr.push(format!("{label} PSNR (dB)"));
    }
    let hdr_ref: Vec<&str> = hdr.iter().map(String::as_str).collect();
    let mut t = Table::new(
        "Kurt Table 9.3 stand-in: dense materials, L2 error and rendering PSNR",
        &hdr_ref,
    );
    let mut written = Vec::new();
    let mut reciprocity_max = 0.0f64;
    // RGL materials: rendered and scored.
    for name in crate::sopp_tables::MATERIALS {
        let path = data_root.join("rgl").join(format!("{name}.bsdf"));
        if !path.exists() {
            continue;
        }
        let rgl = brdf_io::rgl::Rgl::read(&path)?;
        let full = brdf_io::sopp_grid::SoppGrid::resample(&rgl).to_samples(name, 80.0, true);
        // Every 5th grid sample (about 4,000): the fits of nine models on
        // five materials stay within minutes; the rendering compares the
        // fitted models with the full measured material.
        let keep: Vec<bool> = (0..full.len()).map(|j| j % 5 == 0).collect();
        let set = full.select(&keep);
        let reference = render_sphere(&rgl, SIZE, &light(), &Vector3::z(), false);
        let peak = reference.peak().max(1e-12);
        let mut row = vec![Cell::Text(name.to_string())];
        let mut images = vec![reference.clone()];
        for (label, model, config) in &models {
            let (m, r) = fit_catalogue(
                model,
                ModelConfig {
                    channels: 3,
                    ..*config
                },
                &set,
            )?;
            let l2 = r.ngan_l2;
            let img = render_sphere(m.as_ref(), SIZE, &light(), &Vector3::z(), false);
            row.push(Cell::Num(l2, 4));
            row.push(Cell::Num(psnr(&reference.data, &img.data, peak)?, 4));
            if *label == "Polynomial (p = 7)" {
                let swapped = render_sphere(m.as_ref(), SIZE, &light(), &Vector3::z(), true);
                let d = img.abs_difference(&swapped);
                reciprocity_max = reciprocity_max.max(d.peak());
            }
            images.push(img);
        }
        t.rows.push(row);
        let refs: Vec<&Image> = images.iter().collect();
        let strip = Image::hstack(&refs);
        let file = format!("render_{name}.png");
        strip.write_png(&out.join(&file), 0.8 / peak)?;
        written.push(file);
    }
    // Cornell paints: fitted and scored by L2 only.
    for name in ["cayman", "mystique", "krylon_blue", "acryl_blue"] {
        let path = data_root.join("cornell").join(format!("{name}.brdf"));
        if !path.exists() {
            continue;
        }
        let set = brdf_io::cornell::read(&path, brdf_io::cornell::CornellColour::Rgb)?;
        let (set, _) = set.filter_angle_limit(80f64.to_radians());
        let mut row = vec![Cell::Text(format!("cornell {name}"))];
        for (_, model, config) in &models {
            let l2 = fit_catalogue(
                model,
                ModelConfig {
                    channels: 3,
                    ..*config
                },
                &set,
            )?
            .1
            .ngan_l2;
            row.push(Cell::Num(l2, 4));
            row.push(Cell::Text("n/a (scattered)".into()));
        }
        t.rows.push(row);
    }
    if t.rows.is_empty() {
        return Ok(written);
    }
    t.note = format!(
        "Kurt used five MERL materials (not available); the RGL materials and Cornell paints stand in. RGB fits, automatic starts; RGL materials sampled on Sopp's grid (every 5th node within 80 deg). Renderings: a sphere of {SIZE} px lit from (0.5, 0.5, 0.707), seen from +z, pixel value f(L, V) cos_i; PSNR against the sphere rendered from the measured RGL data (peak = its largest value). Images `render_<material>.png`: measured, then the nine models in table order. Fig. 9.6 reciprocity check: the polynomial fits rendered with L and V swapped differ from the unswapped renderings by at most {reciprocity_max:.3e}. Generated by `brdf reproduce`."
    );
    t.write(out, "kurt_9_3")?;
    written.push("kurt_9_3.{csv,md}".into());
    Ok(written)
}
