//! The page of one fit: everything about a saved model against its data,
//! analysed once ([`analyse`]) and rendered through the `fit.html`
//! template ([`fit_page`]).

use std::path::Path;

use std::sync::Arc;

use brdf_core::Brdf;
use brdf_fit::{Material, Termination};
use brdf_models::saved_model::SavedModel;
use brdf_render::judge::REPORT_SIZE;
use brdf_render::{ImageError, Judge};
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
    /// how the solver ended, in words
    pub termination: String,
    /// how the solver ended (`None`: not recorded, or not a sentence a
    /// fit prints)
    #[serde(skip)]
    pub ended: Option<Termination>,
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
    Analyser::new(sphere_size).analyse(input)
}

/// Analyses pages of one sphere size, keeping what consecutive pages share:
/// the judge's terms (they do not depend on the data) and the last data
/// set with its renders (a batch's lines come sorted by data, each
/// material's models in a row). A page is what [`analyse`] makes.
pub struct Analyser {
    size: usize,
    /// the judge's terms, made at the first dense data set
    terms: Option<Judge>,
    /// the last data set read, with its renders when dense
    data: Option<Arc<Material>>,
}

impl Analyser {
    /// An analyser of pages whose spheres are `size` pixels wide.
    pub fn new(size: usize) -> Self {
        Analyser {
            size,
            terms: None,
            data: None,
        }
    }

    /// An analyser of the pages of `material`, already loaded (and, for a
    /// fit's image errors, rendered): `brdf fit --report` hands over the
    /// material of its fit, so the page renders only the fit. Its spheres
    /// are the judge's [`REPORT_SIZE`] pixels wide.
    pub fn with_material(material: Arc<Material>) -> Self {
        Analyser {
            size: REPORT_SIZE,
            terms: None,
            data: Some(material),
        }
    }

    /// The data set `spec`, read (and rendered) unless it was the last one.
    fn load(&mut self, spec: &str) -> Result<Arc<Material>, ReportError> {
        if let Some(d) = self.data.as_ref().filter(|d| d.spec() == spec) {
            return Ok(Arc::clone(d));
        }
        let (size, terms) = (self.size, &mut self.terms);
        let material = Arc::new(Material::load_on(spec, || {
            terms.get_or_insert_with(|| Judge::new(size))
        })?);
        self.data = Some(Arc::clone(&material));
        Ok(material)
    }

    /// The analysis of one page.
    pub fn analyse(&mut self, input: &FitInput) -> Result<Analysis, ReportError> {
        let size = self.size;
        let data = self.load(input.data)?;
        // Loaded on this analyser's terms, or handed over with its own.
        let judge = data.judge()?;
        let model = input.saved.build().map_err(|e| ReportError::Model {
            what: input.fit_source.into(),
            reason: e.to_string(),
        })?;
        let model: &dyn Brdf = model.as_ref();
        let dense_ref = data.dense();
        let (image, spheres) = match judge {
            Some(judge) => {
                let (errors, renders) = judge.fit_renders(model)?;
                (Some(errors), spheres::rows_of(&renders)?)
            }
            None => (None, spheres::fitted_rows(model, size)?),
        };
        let termination = input.run.as_ref().and_then(|r| r.ended.as_ref());
        Ok(Analysis {
            samples: data.samples().len(),
            dense: dense_ref.is_some(),
            slices: polar::slices(data.samples(), dense_ref, model),
            coverage_svg: coverage::svg(data.samples())?,
            spheres,
            verdict: verdict(input.saved, image.as_ref(), termination),
            image,
        })
    }
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
    brdf_core::format::number(v, 4)
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
    fit_page_with(input, &mut Analyser::new(REPORT_SIZE))
}

/// [`fit_page`] analysed by `analyser` (one holding the data's renders,
/// [`Analyser::with_material`]).
pub fn fit_page_with(input: &FitInput, analyser: &mut Analyser) -> Result<String, ReportError> {
    let a = analyser.analyse(input)?;
    render(input, &a, None)
}

/// [`fit_page`] written to `out`.
pub fn write_fit_page(input: &FitInput, out: &Path) -> Result<(), ReportError> {
    write_fit_page_with(input, out, &mut Analyser::new(REPORT_SIZE))
}

/// [`fit_page_with`] written to `out`.
pub fn write_fit_page_with(
    input: &FitInput,
    out: &Path,
    analyser: &mut Analyser,
) -> Result<(), ReportError> {
    let html = fit_page_with(input, analyser)?;
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
        Some((v, path)) => Some(select_plot::selection(v, path, input.data)?),
        None => None,
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
