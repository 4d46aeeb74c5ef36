//! The stability suite: extreme and bad input, each case run
//! in-process through the public API, with what happened — a fitted
//! result (parameters, bound status, termination, iterations, notes) or
//! the error message. [`write_stability_report`] writes
//! `stability.md` / `stability.csv` (and, with `BRDF_DATA` set, the NIST
//! StRD table from both certified starts as `stability_nist.*`).
//!
//! The synthetic data sets are deterministic: [`pairs`] gives CUReT's
//! count of 205 direction pairs (golden-ratio sequences, elevations up to
//! 75 deg), [`synthetic`] evaluates a catalogue model at them. The CLI
//! tests (`crates/brdf-cli/tests/cli/stability_cli.rs`) write the same sets as CSV files and
//! run the `brdf` binary on them.

use std::path::Path;

use brdf_core::format::number;
use brdf_core::{Direction, SampleSet};
use brdf_fit::{FitRequest, Material, Metric, Objective};
use brdf_models::ModelConfig;
use brdf_models::ModelEntry;

use crate::StudyError;
use crate::report::{Cell, Table};

/// `n` deterministic direction pairs, elevations in `[0, 75]` deg and
/// azimuths over the circle (additive golden-ratio sequences).
pub fn pairs(n: usize) -> Vec<(Direction, Direction)> {
    let frac = |x: f64| x - x.floor();
    let (g1, g2, g3, g4) = (
        0.618_033_988_749_894_9,
        0.754_877_666_246_692_7,
        0.569_840_290_998_053_2,
        0.381_966_011_250_105_1,
    );
    let top = 75f64.to_radians();
    (0..n)
        .map(|j| {
            let j = j as f64;
            let ti = top * frac(0.5 + j * g1);
            let to = top * frac(0.25 + j * g4);
            let pi = (2.0 * frac(0.5 + j * g2) - 1.0) * std::f64::consts::PI;
            let po = (2.0 * frac(0.5 + j * g3) - 1.0) * std::f64::consts::PI;
            (
                Direction::new_unchecked(brdf_core::spherical_to_cartesian(ti, pi)),
                Direction::new_unchecked(brdf_core::spherical_to_cartesian(to, po)),
            )
        })
        .collect()
}

/// The one-channel catalogue model `model` at its defaults overridden by
/// `params`, evaluated at [`pairs`]`(n)`, values times `value_scale`, all
/// weights `weight`.
pub fn synthetic(
    model: &str,
    params: &[(&str, f64)],
    n: usize,
    value_scale: f64,
    weight: f64,
) -> Result<SampleSet, StudyError> {
    let mut m = brdf_models::build(model, &ModelConfig::default())?;
    let assign: Vec<(String, f64)> = params.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let p = brdf_core::params::assign_by_name(model, m.param_specs(), &assign)?;
    m.set_params(&p)?;
    let mut s = SampleSet::new(
        format!("generated {model}"),
        "brdf-study stability suite",
        vec!["y".into()],
    );
    let mut out = [0.0];
    for (l, v) in pairs(n) {
        m.eval(l.vector(), v.vector(), &mut out);
        s.push(&l, &v, &[out[0] * value_scale], weight)?;
    }
    Ok(s)
}

/// A copy of `set` with its values given by `f(j, value)`.
pub fn map_values(set: &SampleSet, f: impl Fn(usize, f64) -> f64) -> Result<SampleSet, StudyError> {
    let mut s = SampleSet::new(
        set.name.clone(),
        set.provenance.clone(),
        set.channel_names.clone(),
    );
    let p = set.pairs();
    let mut row = vec![0.0; set.channels()];
    for j in 0..set.len() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = f(j, set.channel(c)[j]);
        }
        s.push(
            &Direction::new_unchecked(p.l(j)),
            &Direction::new_unchecked(p.v(j)),
            &row,
            set.weights()[j],
        )?;
    }
    Ok(s)
}

/// One case's outcome.
#[derive(Clone, Debug)]
pub struct CaseOutcome {
    /// Group (fit, scale, select, input, NIST).
    pub group: &'static str,
    /// What was tried.
    pub case: String,
    /// `fitted`, `error` or `read`.
    pub outcome: &'static str,
    /// Termination (fits).
    pub termination: String,
    /// Solver iterations (fits).
    pub iterations: Option<usize>,
    /// Ngan L2 (fits).
    pub ngan_l2: Option<f64>,
    /// Parameters with bound status, notes, or the error message.
    pub detail: String,
}

/// A fit of a stability case: the model and what the case changes from
/// `brdf fit`'s defaults.
#[derive(Clone, Copy)]
pub struct CaseFit {
    model: ModelEntry,
    metric: Metric,
    starts: Option<usize>,
    degree: Option<usize>,
}

impl CaseFit {
    /// Fit with this objective.
    pub fn objective(self, objective: Objective) -> Self {
        CaseFit {
            metric: Metric::Objective(objective),
            ..self
        }
    }

    /// Fit from this many starts.
    pub fn starts(self, starts: usize) -> Self {
        CaseFit {
            starts: Some(starts),
            ..self
        }
    }

    /// Fit the polynomial of this degree.
    pub fn degree(self, degree: usize) -> Self {
        CaseFit {
            degree: Some(degree),
            ..self
        }
    }

    /// Run it on `data` as `brdf fit` runs a request.
    fn run(self, case: &str, data: &SampleSet) -> Result<brdf_fit::FitReport, brdf_fit::FitError> {
        let material = Material::new(case, data.clone(), None);
        let mut request = FitRequest::new(&material, self.model);
        request.metric = self.metric;
        request.starts = self.starts.unwrap_or(request.starts);
        request.config.degree = self.degree.unwrap_or(request.config.degree);
        request.run()?.into_report()
    }
}

/// Fit `data` as `fit` says and describe the outcome.
pub fn fit_case(group: &'static str, case: &str, fit: CaseFit, data: &SampleSet) -> CaseOutcome {
    match fit.run(case, data) {
        Ok(r) => {
            let params: Vec<String> = r
                .summary
                .parameters
                .iter()
                .map(|p| {
                    format!(
                        "{} = {}{}",
                        p.name,
                        number(p.value, 6),
                        p.at_bound
                            .as_ref()
                            .map(|b| format!(" ({b} bound)"))
                            .unwrap_or_default()
                    )
                })
                .collect();
            let mut detail = params.join(", ");
            for n in &r.notes {
                detail.push_str("; note: ");
                detail.push_str(n);
            }
            CaseOutcome {
                group,
                case: case.into(),
                outcome: "fitted",
                termination: r.summary.termination.to_string(),
                iterations: Some(r.summary.iterations),
                ngan_l2: Some(r.summary.ngan_l2),
                detail,
            }
        }
        Err(e) => error_case(group, case, &e.to_string()),
    }
}

/// A fit of constant data of magnitude `scale` by a linear expansion, said
/// to be exact when its Ngan L2 is below `1e-12 scale`. Such a fit's
/// coefficients other than the constant are not determined beyond
/// rounding (Koenderink's 55 terms on these 205 pairs are ill-conditioned:
/// they came out up to 2% of the constant, their digits different between
/// two x86-64 machines' SIMD paths; the polynomial's are rounding noise
/// too), so they are not listed: `results/stability.md` must be what any
/// machine writes. A fit that is not exact keeps its row as [`fit_case`]
/// wrote it.
fn exact_or_listed(case: CaseOutcome, scale: f64) -> CaseOutcome {
    match case.ngan_l2 {
        Some(e) if case.outcome == "fitted" && e.is_finite() && e < 1e-12 * scale => CaseOutcome {
            ngan_l2: None,
            detail: format!(
                "exact up to rounding: Ngan L2 below 1e-12 of the data ({}); the coefficients beside the constant are not determined beyond rounding and are not listed",
                number(scale, 6)
            ),
            ..case
        },
        _ => case,
    }
}

fn error_case(group: &'static str, case: &str, message: &str) -> CaseOutcome {
    CaseOutcome {
        group,
        case: case.into(),
        outcome: "error",
        termination: String::new(),
        iterations: None,
        ngan_l2: None,
        detail: message.to_string(),
    }
}

fn model(name: &str) -> Result<CaseFit, StudyError> {
    Ok(CaseFit {
        model: brdf_fit::resolve(name)?,
        metric: Metric::Objective(Objective::Ngan),
        starts: None,
        degree: None,
    })
}

/// The fitting cases: degenerate data, extreme magnitudes, stiff lobes.
pub fn fit_cases() -> Result<Vec<CaseOutcome>, StudyError> {
    let ct = synthetic(
        "cook-torrance",
        &[("kd", 0.3), ("ks1", 0.4), ("m1", 0.15)],
        205,
        1.0,
        1.0,
    )?;
    let bp = synthetic(
        "blinn-phong",
        &[("kd", 0.3), ("ks", 0.5), ("n", 40.0)],
        205,
        1.0,
        1.0,
    )?;
    let mut v = degenerate_cases(&ct, &bp)?;
    v.extend(stiff_cases()?);
    v.extend(request_cases(&ct, &bp)?);
    v.extend(scale_cases(&ct)?);
    Ok(v)
}

/// Data that cannot determine the model: all zero, constant, fewer
/// samples than parameters, every sample twice.
fn degenerate_cases(ct: &SampleSet, bp: &SampleSet) -> Result<Vec<CaseOutcome>, StudyError> {
    let zero = map_values(bp, |_, _| 0.0)?;
    let constant = map_values(bp, |_, _| 0.3)?;
    let one = bp.select(&(0..bp.len()).map(|j| j == 0).collect::<Vec<_>>());
    let three = ct.select(&(0..ct.len()).map(|j| j < 3).collect::<Vec<_>>());
    let doubled = twice(ct)?;
    Ok(vec![
        fit_case("fit", "all-zero data, Lambert", model("lambert")?, &zero),
        fit_case(
            "fit",
            "all-zero data, Blinn-Phong",
            model("blinn-phong")?,
            &zero,
        ),
        fit_case(
            "fit",
            "all-zero data, Cook-Torrance",
            model("cook-torrance")?,
            &zero,
        ),
        fit_case(
            "fit",
            "constant data 0.3, Blinn-Phong",
            model("blinn-phong")?,
            &constant,
        ),
        fit_case("fit", "one sample, Lambert", model("lambert")?, &one),
        fit_case(
            "fit",
            "one sample, Blinn-Phong",
            model("blinn-phong")?,
            &one,
        ),
        fit_case(
            "fit",
            "3 samples, Cook-Torrance (4 parameters)",
            model("cook-torrance")?,
            &three,
        ),
        fit_case(
            "fit",
            "every sample twice, Cook-Torrance",
            model("cook-torrance")?,
            &doubled,
        ),
    ])
}

/// `set` with every sample pushed a second time (weight 1).
fn twice(set: &SampleSet) -> Result<SampleSet, StudyError> {
    let mut d = set.clone();
    let p = set.pairs();
    for j in 0..set.len() {
        d.push(
            &Direction::new_unchecked(p.l(j)),
            &Direction::new_unchecked(p.v(j)),
            &[set.channel(0)[j]],
            1.0,
        )?;
    }
    Ok(d)
}

/// Blinn-Phong data at the edges of its box: a near-mirror lobe, an
/// almost black material, a sharp lobe beside a tiny albedo.
fn stiff_cases() -> Result<Vec<CaseOutcome>, StudyError> {
    let mirror = synthetic(
        "blinn-phong",
        &[("kd", 0.1), ("ks", 0.5), ("n", 1e5)],
        205,
        1.0,
        1.0,
    )?;
    let black = synthetic(
        "blinn-phong",
        &[("kd", 1e-4), ("ks", 1e-4), ("n", 20.0)],
        205,
        1.0,
        1.0,
    )?;
    let stiff = synthetic(
        "blinn-phong",
        &[("kd", 1e-3), ("ks", 0.5), ("n", 1e4)],
        205,
        1.0,
        1.0,
    )?;
    Ok(vec![
        fit_case(
            "fit",
            "near-mirror Blinn-Phong n = 1e5 data, Blinn-Phong",
            model("blinn-phong")?,
            &mirror,
        ),
        fit_case(
            "fit",
            "black (kd = ks = 1e-4) data, Blinn-Phong",
            model("blinn-phong")?,
            &black,
        ),
        fit_case(
            "fit",
            "exponent 1e4 next to albedo 1e-3, Blinn-Phong",
            model("blinn-phong")?,
            &stiff,
        ),
    ])
}

/// Well-posed data met by an unusual request: another model than the
/// data's, a high-degree polynomial, one outlier beyond the box, a metric
/// without a solver named, no starts.
fn request_cases(ct: &SampleSet, bp: &SampleSet) -> Result<Vec<CaseOutcome>, StudyError> {
    let spike = map_values(bp, |j, v| if j == 7 { 1e6 } else { v })?;
    Ok(vec![
        fit_case(
            "fit",
            "Cook-Torrance data, Ward (other model)",
            model("ward")?,
            ct,
        ),
        fit_case(
            "fit",
            "Cook-Torrance data, polynomial degree 12",
            model("polynomial")?.degree(12),
            ct,
        ),
        fit_case(
            "fit",
            "one value 1e6 among 205, Lambert (kd <= 1)",
            model("lambert")?,
            &spike,
        ),
        fit_case(
            "fit",
            "Lambert with the log metric (no solver given)",
            model("lambert")?.objective(Objective::Log),
            bp,
        ),
        fit_case("fit", "--starts 0", model("blinn-phong")?.starts(0), bp),
    ])
}

/// `set` divided by its largest magnitude (largest value exactly 1: the
/// form every scaled data set takes inside a fit).
pub fn unit(set: &SampleSet) -> Result<SampleSet, StudyError> {
    let top = (0..set.channels())
        .flat_map(|c| set.channel(c).iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    map_values(set, |_, x| if top > 0.0 { x / top } else { x })
}

/// Unit data (largest value 1) scaled by `1e-300`, `1e300`, `2^-1000` and
/// with weights of `1e300`: the same fit up to the scale.
pub fn scale_cases(ct: &SampleSet) -> Result<Vec<CaseOutcome>, StudyError> {
    let ct = &unit(ct)?;
    let mut v = Vec::new();
    for (label, s) in [
        ("unit", 1.0),
        ("x 1e-300", 1e-300),
        ("x 1e300", 1e300),
        ("x 2^-1000", 2f64.powi(-1000)),
    ] {
        let d = map_values(ct, |_, x| x * s)?;
        v.push(fit_case(
            "scale",
            &format!("Cook-Torrance data {label}, Cook-Torrance"),
            model("cook-torrance")?,
            &d,
        ));
    }
    let mut heavy = ct.clone();
    heavy.set_weights(vec![1e300; ct.len()])?;
    v.push(fit_case(
        "scale",
        "Cook-Torrance data, weights 1e300, Cook-Torrance",
        model("cook-torrance")?,
        &heavy,
    ));
    let big = map_values(ct, |_, _| 1e300)?;
    v.push(fit_case(
        "scale",
        "all values 1e300, Phong, log metric",
        model("phong")?.objective(Objective::Log),
        &big,
    ));
    v.push(fit_case(
        "scale",
        "all values 1e300, Cook-Torrance",
        model("cook-torrance")?,
        &big,
    ));
    v.push(fit_case(
        "scale",
        "all values 1e300, Lambert",
        model("lambert")?,
        &big,
    ));
    v.push(exact_or_listed(
        fit_case(
            "scale",
            "all values 1e300, polynomial",
            model("polynomial")?,
            &big,
        ),
        1e300,
    ));
    v.push(exact_or_listed(
        fit_case(
            "scale",
            "all values 1e300, Koenderink",
            model("koenderink")?,
            &big,
        ),
        1e300,
    ));
    let tiny = map_values(ct, |_, x| x * 1e-300)?;
    v.push(select_case("all values 1e300", &big));
    v.push(select_case("Cook-Torrance data x 1e-300", &tiny));
    Ok(v)
}

fn select_case(label: &str, data: &SampleSet) -> CaseOutcome {
    // Exhaustive: the study's rows are those of every candidate fitted to
    // all samples (as before the coarse-to-fine default).
    match brdf_fit::select::select_with(
        data,
        0.1,
        &brdf_fit::FitOptions::default(),
        &brdf_fit::select::Among::default(),
        brdf_fit::select::Search::Exhaustive,
    ) {
        Ok((rows, choice)) => {
            let failed = rows.iter().filter(|r| !r.error.is_finite()).count();
            CaseOutcome {
                group: "select",
                case: format!("select on {label}"),
                outcome: "fitted",
                termination: rows[choice].termination.clone(),
                iterations: None,
                ngan_l2: Some(rows[choice].error),
                detail: format!(
                    "chosen: {} ({} stored numbers) of {} candidates ({failed} failed)",
                    rows[choice].label,
                    rows[choice].stored_numbers,
                    rows.len()
                ),
            }
        }
        Err(e) => error_case("select", &format!("select on {label}"), &e.to_string()),
    }
}

/// Bad input files, written into `dir` and read through `brdf_io`.
pub fn input_cases(dir: &Path) -> Result<Vec<CaseOutcome>, StudyError> {
    std::fs::create_dir_all(dir).map_err(io_error(dir))?;
    let bp = synthetic("blinn-phong", &[], 205, 1.0, 1.0)?;
    let mut v = csv_cases(dir, &bp)?;
    v.push(rat43_case(dir)?);
    v.push(truncated_model_case(dir, &bp)?);
    Ok(v)
}

/// The error of a failed read or write of `p`, naming it.
fn io_error(p: &Path) -> impl FnOnce(std::io::Error) -> StudyError {
    let p = p.to_path_buf();
    move |source| StudyError::Io {
        path: p.display().to_string(),
        source,
    }
}

/// The file at `path` read as samples: how many, or the error (its
/// messages without the temporary folder `dir`).
fn read_case(label: &str, path: &Path, dir: &Path) -> CaseOutcome {
    match brdf_io::load(&path.display().to_string()) {
        Ok(s) => CaseOutcome {
            group: "input",
            case: label.into(),
            outcome: "read",
            termination: String::new(),
            iterations: None,
            ngan_l2: None,
            detail: format!("{} samples", s.len()),
        },
        Err(e) => error_case("input", label, &relative(&e.to_string(), dir)),
    }
}

/// CSV files of `bp` that a reader could get wrong: angles in degrees
/// (under a radian header and under a `_deg` one), and a `#` in a folder
/// name.
fn csv_cases(dir: &Path, bp: &SampleSet) -> Result<Vec<CaseOutcome>, StudyError> {
    let mut v = Vec::new();
    // Angles in degrees under a radian header.
    let csv = dir.join("degrees.csv");
    brdf_io::csv_samples::write(&csv, bp)?;
    let text = std::fs::read_to_string(&csv).map_err(io_error(&csv))?;
    let degrees = to_degrees_csv(&text, false);
    std::fs::write(&csv, &degrees).map_err(io_error(&csv))?;
    v.push(read_case(
        "CSV with angles in degrees, radian header",
        &csv,
        dir,
    ));
    let csv_deg = dir.join("degrees_named.csv");
    std::fs::write(&csv_deg, to_degrees_csv(&text, true)).map_err(io_error(&csv_deg))?;
    v.push(read_case(
        "CSV with angles in degrees, `_deg` header",
        &csv_deg,
        dir,
    ));
    // `#` inside a folder name.
    let hash = dir.join("set#1");
    std::fs::create_dir_all(&hash).map_err(io_error(&hash))?;
    let hashed = hash.join("samples.csv");
    brdf_io::csv_samples::write(&hashed, bp)?;
    v.push(read_case("`#` in a folder name", &hashed, dir));
    Ok(v)
}

/// NIST's Rat43 file, whose header says 9 degrees of freedom (for 15 - 4):
/// how many were used and the reader's warning.
fn rat43_case(dir: &Path) -> Result<CaseOutcome, StudyError> {
    let rat43 = dir.join("Rat43.dat");
    std::fs::write(&rat43, RAT43).map_err(io_error(&rat43))?;
    Ok(match brdf_io::nist::read(&rat43) {
        Ok(d) => CaseOutcome {
            group: "input",
            case: "NIST Rat43.dat (header: 9 degrees of freedom)".into(),
            outcome: "read",
            termination: String::new(),
            iterations: None,
            ngan_l2: None,
            detail: format!(
                "{} degrees of freedom used; warning: {}",
                d.dof,
                relative(&d.warnings.join("; "), dir)
            ),
        },
        Err(e) => error_case("input", "NIST Rat43.dat", &relative(&e.to_string(), dir)),
    })
}

/// A saved model (of a fit to `bp`) cut in half, then loaded: what the
/// load says.
fn truncated_model_case(dir: &Path, bp: &SampleSet) -> Result<CaseOutcome, StudyError> {
    let fit = model("blinn-phong")?.run("synthetic", bp)?;
    let saved = dir.join("model.json");
    fit.saved_model("synthetic")?.save(&saved)?;
    let text = std::fs::read_to_string(&saved).map_err(io_error(&saved))?;
    let truncated = dir.join("truncated.json");
    std::fs::write(&truncated, &text[..text.len() / 2]).map_err(io_error(&truncated))?;
    Ok(
        match brdf_models::saved_model::SavedModel::load_model(&truncated) {
            Ok(_) => error_case("input", "truncated saved model", "read (unexpected)"),
            Err(e) => error_case(
                "input",
                "truncated saved model",
                &relative(&e.to_string(), dir),
            ),
        },
    )
}

/// NIST's `Rat43.dat` as published (public domain, NIST ITL StRD).
const RAT43: &str = include_str!("../../brdf-io/tests/fixtures/nist/Rat43.dat");

/// The CSV `text` (radian angles) with its angles in degrees; `named`:
/// with the `_deg` header.
pub fn to_degrees_csv(text: &str, named: bool) -> String {
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if i == 0 {
            if named {
                out.push_str(&line.replacen(
                    "theta_i,phi_i,theta_o,phi_o",
                    "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg",
                    1,
                ));
            } else {
                out.push_str(line);
            }
        } else {
            let f: Vec<String> = line
                .split(',')
                .enumerate()
                .map(|(k, t)| match (k < 4, t.parse::<f64>()) {
                    (true, Ok(x)) => x.to_degrees().to_string(),
                    _ => t.to_string(),
                })
                .collect();
            out.push_str(&f.join(","));
        }
        out.push('\n');
    }
    out
}

/// A message with the temporary folder removed (no machine path in
/// results).
fn relative(message: &str, dir: &Path) -> String {
    message.replace(&format!("{}/", dir.display()), "")
}

/// Every case, as a table.
pub fn table(cases: &[CaseOutcome]) -> Table {
    let mut t = Table::new(
        "Stability: extreme and bad input",
        &[
            "group",
            "case",
            "outcome",
            "termination",
            "iterations",
            "Ngan L2",
            "parameters, notes or error",
        ],
    );
    t.note = "Generated by `brdf reproduce --only stability` (crates/brdf-study/src/stability.rs), every case run in-process through the public API on deterministic generated data (205 direction pairs, elevations up to 75 deg). A case ends in a finite result whose report says what happened, or in an error naming the file, parameter or value. Scale cases: Cook-Torrance data divided by their largest value (unit data), then multiplied by 1e-300, 1e300 or 2^-1000: values outside 2^+-16 are divided internally by their largest magnitude, so the fit of data times 2^-1000 is the unit fit bit for bit and data times 1e-300 fit in the same iterations to the same parameters up to the scale; data of 1e300 reach the box of the linear parameters (kd, ks <= 1), which is reported.".into();
    for c in cases {
        t.rows.push(vec![
            Cell::Text(c.group.into()),
            Cell::Text(c.case.clone()),
            Cell::Text(c.outcome.into()),
            Cell::Text(c.termination.clone()),
            Cell::Text(c.iterations.map(|i| i.to_string()).unwrap_or_default()),
            c.ngan_l2
                .map(|e| Cell::Text(number(e, 6)))
                .unwrap_or(Cell::Empty),
            Cell::Text(c.detail.replace('|', "/")),
        ]);
    }
    t
}

/// Run every case and write `stability.md` / `stability.csv` into
/// `out_dir`; with `BRDF_DATA` set, also the NIST StRD table from both
/// certified starts (`stability_nist.md` / `.csv`).
pub fn write_stability_report(out_dir: &Path) -> Result<(), StudyError> {
    std::fs::create_dir_all(out_dir).map_err(|source| StudyError::Io {
        path: out_dir.display().to_string(),
        source,
    })?;
    // Two reports written at once in one process (tests run in parallel) must not share, and remove, each
    // other's scratch files.
    static CALL: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALL.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let scratch =
        std::env::temp_dir().join(format!("brdf-stability-{}-{call}", std::process::id()));
    let mut cases = fit_cases()?;
    cases.extend(input_cases(&scratch)?);
    let _ = std::fs::remove_dir_all(&scratch);
    table(&cases).write(out_dir, "stability")?;
    if let Some(dir) = nist_dir() {
        let runs = crate::nist::run_dir(&dir, &crate::nist::strategies())?;
        let mut t = crate::nist::table(&runs, &dir);
        t.title = "Stability: NIST StRD from both certified starts".into();
        t.note = format!(
            "Generated by `brdf reproduce --only stability` (the runs of `brdf nist`, both certified starts of every problem). {}",
            t.note
        );
        t.write(out_dir, "stability_nist")?;
    }
    Ok(())
}

/// `$BRDF_DATA/nist_strd` when it exists.
fn nist_dir() -> Option<std::path::PathBuf> {
    let root = std::env::var_os("BRDF_DATA")?;
    Some(Path::new(&root).join("nist_strd")).filter(|d| d.is_dir())
}

/// The `stability` part of `brdf reproduce`: [`write_stability_report`]
/// into the study's output folder, listed in its README.
pub fn part(study: &mut crate::context::Study) -> Result<(), StudyError> {
    write_stability_report(&study.out)?;
    study.wrote_with(crate::context::Written {
        file: "stability.{csv,md}".into(),
        what: "Stability: every extreme and bad input case (fits of generated data, malformed files) with what happened".into(),
        data: "generated in the run (deterministic)".into(),
        metric: "ngan".into(),
        limit: "80 deg (75 deg for the grazing cases)".into(),
    });
    if nist_dir().is_some() {
        study.wrote_with(crate::context::Written {
            file: "stability_nist.{csv,md}".into(),
            what: "Stability: NIST StRD from both certified starts".into(),
            data: "`nist_strd/*.dat`".into(),
            metric: "LRE (digits agreeing with the certified values)".into(),
            limit: "n/a".into(),
        });
    }
    Ok(())
}
