//! The page of one fit: everything about a saved model against its data,
//! analysed once ([`analyse`]) and rendered through the `fit.html`
//! template ([`fit_page`]).

use std::path::Path;

use brdf_core::{Brdf, SampleSet};
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
    /// the last data set read
    data: Option<Loaded>,
}

/// A data set as read for its pages.
struct Loaded {
    spec: String,
    samples: SampleSet,
    dense: Option<Box<dyn Brdf>>,
    /// the judge with the dense data's renders
    judge: Option<Judge>,
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

    /// An analyser of the pages of `spec`, a dense data set that `judge`
    /// has rendered ([`Judge::with_data`]): `brdf fit --report` hands over
    /// the judge of its fit's image errors, so the page renders only the
    /// fit. Its spheres are `judge.size()` pixels wide.
    pub fn with_judge(spec: &str, judge: Judge) -> Result<Self, ReportError> {
        let samples = brdf_io::load(spec)?;
        let dense = brdf_io::load_dense(spec)?;
        if dense.is_none() {
            return Err(ReportError::Input {
                path: spec.to_string(),
                reason: "a judge was given for data that cannot be rendered".into(),
            });
        }
        Ok(Analyser {
            size: judge.size(),
            terms: None,
            data: Some(Loaded {
                spec: spec.to_string(),
                samples,
                dense,
                judge: Some(judge),
            }),
        })
    }

    /// The data set `spec`, read (and rendered) unless it was the last one.
    fn load(&mut self, spec: &str) -> Result<&Loaded, ReportError> {
        let loaded = match self.data.take() {
            Some(d) if d.spec == spec => d,
            _ => self.read(spec)?,
        };
        Ok(self.data.insert(loaded))
    }

    /// Read `spec` and render it on the judge's terms when it is dense.
    fn read(&mut self, spec: &str) -> Result<Loaded, ReportError> {
        let samples = brdf_io::load(spec)?;
        let dense = brdf_io::load_dense(spec)?;
        let judge = match dense.as_deref() {
            Some(d) => {
                let terms = self.terms.get_or_insert_with(|| Judge::new(self.size));
                Some(terms.rendering(d)?)
            }
            None => None,
        };
        Ok(Loaded {
            spec: spec.to_string(),
            samples,
            dense,
            judge,
        })
    }

    /// The analysis of one page.
    pub fn analyse(&mut self, input: &FitInput) -> Result<Analysis, ReportError> {
        let size = self.size;
        let data = self.load(input.data)?;
        let model = input.saved.build().map_err(|e| ReportError::Model {
            what: input.fit_source.into(),
            reason: e.to_string(),
        })?;
        let model: &dyn Brdf = model.as_ref();
        let dense_ref = data.dense.as_deref();
        let (image, spheres) = match &data.judge {
            Some(judge) => {
                let (errors, renders) = judge.fit_renders(model)?;
                (Some(errors), spheres::rows_of(&renders)?)
            }
            None => (None, spheres::fitted_rows(model, size)?),
        };
        let termination = input.run.as_ref().map(|r| r.termination.as_str());
        Ok(Analysis {
            samples: data.samples.len(),
            dense: dense_ref.is_some(),
            slices: polar::slices(&data.samples, dense_ref, model),
            coverage_svg: coverage::svg(&data.samples)?,
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
    fit_page_with(input, &mut Analyser::new(spheres::SIZE))
}

/// [`fit_page`] analysed by `analyser` (one holding the data's renders,
/// [`Analyser::with_judge`]).
pub fn fit_page_with(input: &FitInput, analyser: &mut Analyser) -> Result<String, ReportError> {
    let a = analyser.analyse(input)?;
    render(input, &a, None)
}

/// [`fit_page`] written to `out`.
pub fn write_fit_page(input: &FitInput, out: &Path) -> Result<(), ReportError> {
    write_fit_page_with(input, out, &mut Analyser::new(spheres::SIZE))
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
