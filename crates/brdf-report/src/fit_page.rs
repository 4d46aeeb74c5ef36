//! The page of one fit: everything about a saved model against its data,
//! analysed once ([`analyse`]) and rendered through the `fit.html`
//! template ([`fit_page`]).

use std::path::Path;

use brdf_core::Brdf;
use brdf_fit::appearance::{ImageError, Judge};
use brdf_models::saved_model::SavedModel;
use serde::Serialize;
use serde_json::Value;

use crate::polar::{self, Slice};
use crate::spheres::{self, SphereRow};
use crate::verdict::{Verdict, verdict};
use crate::{ReportError, coverage, select_plot, templates};

/// How the fit ran, when known (`brdf fit` and `fits.jsonl` know it; a
/// saved model alone does not record it).
#[derive(Clone, Debug, Serialize)]
pub struct RunInfo {
    /// wall time of the fit
    pub seconds: f64,
    /// how the solver ended
    pub termination: String,
    /// solver iterations
    pub iterations: Option<usize>,
}

/// What a fit page shows.
#[derive(Clone, Debug)]
pub struct FitInput<'a> {
    /// the data set (`PATH` or `PATH#SAMPLE`)
    pub data: &'a str,
    /// the fitted model
    pub saved: &'a SavedModel,
    /// where the model came from (a file, or `brdf fit`)
    pub fit_source: &'a str,
    /// how the fit ran
    pub run: Option<RunInfo>,
    /// a `brdf select --json` output and its file name
    pub selection: Option<(&'a Value, &'a str)>,
}

/// The pictures and numbers of a fit.
pub struct Analysis {
    /// samples present in the data
    pub samples: usize,
    /// whether the data are dense (evaluable at any direction pair)
    pub dense: bool,
    /// incidence-plane slices
    pub slices: Vec<Slice>,
    /// coverage plot (SVG)
    pub coverage_svg: String,
    /// spheres per light set
    pub spheres: Vec<SphereRow>,
    /// image errors (dense data only)
    pub image: Option<ImageError>,
    /// the verdict
    pub verdict: Verdict,
}

/// Load the data, rebuild the model, render and measure everything.
pub fn analyse(input: &FitInput, sphere_size: usize) -> Result<Analysis, ReportError> {
    let data = brdf_io::load(input.data)?;
    let dense = brdf_io::load_dense(input.data)?;
    let model = input.saved.build().map_err(|e| ReportError::Model {
        what: input.fit_source.into(),
        reason: e.to_string(),
    })?;
    let model: &dyn Brdf = model.as_ref();
    let dense_ref = dense.as_deref();
    let image = match dense_ref {
        Some(d) => Some(Judge::new(sphere_size).errors(d, model)?),
        None => None,
    };
    let termination = input.run.as_ref().map(|r| r.termination.as_str());
    Ok(Analysis {
        samples: data.len(),
        dense: dense.is_some(),
        slices: polar::slices(&data, dense_ref, model),
        coverage_svg: coverage::svg(&data)?,
        spheres: spheres::rows(dense_ref, model, sphere_size)?,
        verdict: verdict(input.saved, image.as_ref(), termination),
        image,
    })
}

/// One parameter row.
#[derive(Serialize)]
struct ParamRow {
    name: String,
    value: String,
    std_error: String,
    at_bound: String,
}

/// One image-error row.
#[derive(Serialize)]
struct ErrorRow {
    light: String,
    flip: String,
    psnr: String,
    delta_e: String,
    exposure: String,
}

fn sig(v: f64) -> String {
    brdf_render::fmt_sig(v, 4)
}

fn params(saved: &SavedModel) -> Vec<ParamRow> {
    saved
        .parameters
        .iter()
        .map(|p| ParamRow {
            name: p.name.clone(),
            value: sig(p.value),
            std_error: p.std_error.map_or("–".into(), sig),
            at_bound: p.at_bound.clone().unwrap_or_default(),
        })
        .collect()
}

fn errors(image: Option<&ImageError>) -> Vec<ErrorRow> {
    image.map_or(Vec::new(), |im| {
        im.lights
            .iter()
            .map(|l| ErrorRow {
                light: l.light.clone(),
                flip: format!("{:.3}", l.flip),
                psnr: format!("{:.1} dB", l.psnr),
                delta_e: format!("{:.2}", l.delta_e),
                exposure: sig(l.exposure),
            })
            .collect()
    })
}

/// The material's name: the data file's stem and its sample, if any
/// (`paper_white_rgb`, `abrdf#25`).
pub fn material(spec: &str) -> String {
    let (path, sample) = brdf_io::split_sample(spec);
    let stem = path
        .file_stem()
        .map_or(spec.to_string(), |s| s.to_string_lossy().into_owned());
    match sample {
        Some(s) => format!("{stem}#{s}"),
        None => stem,
    }
}

/// The self-contained HTML page of a fit.
pub fn fit_page(input: &FitInput) -> Result<String, ReportError> {
    let a = analyse(input, spheres::SIZE)?;
    render(input, &a, None)
}

/// [`fit_page`] written to `out`.
pub fn write_fit_page(input: &FitInput, out: &Path) -> Result<(), ReportError> {
    let html = fit_page(input)?;
    std::fs::write(out, html).map_err(ReportError::io(out))
}

/// Render the page of an analysed fit; `back` links to an index page.
pub fn render(input: &FitInput, a: &Analysis, back: Option<&str>) -> Result<String, ReportError> {
    let s = input.saved;
    let p = &s.provenance;
    let mut polar_svgs = Vec::new();
    for sl in &a.slices {
        polar_svgs.push((polar::svg(sl, false)?, polar::svg(sl, true)?));
    }
    let selection = match input.selection {
        Some((v, path)) => select_plot::svgs(v, path)?,
        None => Vec::new(),
    };
    let material = material(input.data);
    let ctx = minijinja::context! {
        title => format!("{} fitted to {}", s.model, material),
        material, data => brdf_fit::data_name(input.data), fit_source => input.fit_source,
        model => s.model, channels => s.structure.channels,
        samples_used => p.samples_used, samples_present => p.samples_present,
        samples_loaded => a.samples, objective => p.objective, error => sig(p.error),
        limit_deg => p.limit_deg, solver => p.solver, software => p.software,
        run => input.run, params => params(s), dense => a.dense,
        polar => polar_svgs, coverage => a.coverage_svg, spheres => a.spheres,
        errors => errors(a.image.as_ref()), verdict => a.verdict,
        selection, back,
        theta_tol => polar::THETA_TOL_DEG, decades => polar::LOG_DECADES, phi_tol => polar::PHI_TOL_DEG,
    };
    templates::render("fit.html", ctx)
}
