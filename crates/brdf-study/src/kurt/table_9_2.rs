//! Kurt's Table 9.2: the nine models on five CUReT materials, and the
//! fitted non-linear parameters beside Kurt's (a switched-off lobe's shape
//! parameters reported as undetermined).

use brdf_core::SampleSet;
use brdf_fit::FitSummary;
use brdf_models::ModelConfig;

use super::common::{KURT_9_2, TABLE_9_2_MATERIALS, err, lafortune_note, nine_index};
use crate::StudyError;
use crate::context::Study;
use crate::context::models::FitHow;
use crate::report::{Cell, Table};
use brdf_fit::report_text::undetermined;

/// Kurt's fitted parameters (RGB; Kurt 2007), per model label, in the
/// material order of [`TABLE_9_2_MATERIALS`].
const KURT_PARAMS: [(&str, [&str; 5]); 7] = [
    (
        "Ashikhmin-Shirley",
        [
            "F0 0.999, n 1.301",
            "F0 0.999, n 11.769",
            "F0 0.999, n 4.7531",
            "F0 0.999, n 3.9363",
            "F0 0.999, n 6.5853",
        ],
    ),
    (
        "Blinn-Phong",
        ["n 18.881", "n 29.152", "n 17.166", "n 16.218", "n 22.618"],
    ),
    (
        "Cook-Torrance",
        [
            "F0 0.7394, m 0.4379",
            "F0 0.999, m 0.3067",
            "F0 0.999, m 0.4270",
            "F0 0.999, m 0.4758",
            "F0 0.999, m 0.3669",
        ],
    ),
    (
        "Lafortune",
        [
            "Cxy -0.479, Cz 0.169, n 8.616",
            "Cxy -0.627, Cz 0.390, n 14.99",
            "Cxy -0.749, Cz 0.338, n 7.69",
            "Cxy -0.657, Cz 0.325, n 4.72",
            "Cxy -0.823, Cz 0.529, n 12.12",
        ],
    ),
    ("Oren-Nayar", ["sigma 0.000"; 5]),
    (
        "Ward",
        ["a 0.3888", "a 0.2840", "a 0.4170", "a 0.4512", "a 0.3386"],
    ),
    (
        "Ward-Duer",
        ["a 0.4448", "a 0.3233", "a 0.4811", "a 0.500", "a 0.3904"],
    ),
];

/// The Table 9.2 materials present in `sets`: (column index, set).
pub fn columns(sets: &[SampleSet]) -> Vec<(usize, SampleSet)> {
    TABLE_9_2_MATERIALS
        .iter()
        .enumerate()
        .filter_map(|(k, (n, name))| {
            sets.iter()
                .find(|s| {
                    crate::context::sample_number(s) == Some(*n)
                        || s.name.starts_with(&format!("{name} (synthetic)"))
                })
                .map(|s| (k, s.clone()))
        })
        .collect()
}

/// The non-linear parameters of a fit as text, undetermined ones marked.
pub fn parameter_text(r: &FitSummary) -> String {
    let off = undetermined(r);
    r.parameters
        .iter()
        .filter(|q| !q.projected)
        .map(|q| {
            if off.contains(&q.name) {
                format!("{} undetermined (lobe off: ks = 0)", q.name)
            } else {
                let bound = q
                    .at_bound
                    .as_ref()
                    .map(|b| format!(" [{b}]"))
                    .unwrap_or_default();
                format!("{} {:.4}{bound}", q.name, q.value)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A model of the study: `(label, catalogue name, config)`.
type Model = (&'static str, &'static str, ModelConfig);

/// Run the part.
pub fn run(study: &mut Study) -> Result<(), StudyError> {
    let all = study.curet()?;
    let cols = columns(&all);
    if cols.is_empty() {
        study.skipped.push((
            "kurt_9_2".into(),
            "none of its five materials selected".into(),
        ));
        return Ok(());
    }
    let sets: Vec<SampleSet> = cols.iter().map(|c| c.1.clone()).collect();
    let models = study.models();
    let how = study.how()?;
    let results = study.fits(&models, &sets, how)?;
    let t = errors_table(study, &models, &cols, &results, how);
    let stem = study.stem("kurt_9_2");
    t.write(&study.out, &stem)?;
    let data = "`curet/abrdf.dat` #1, 55, 25, 33, 34 (grey)";
    study.wrote(
        format!("{stem}.{{csv,md}}"),
        "Table 9.2: nine models on five CUReT materials, Kurt's values beside",
        data,
    );

    let p = parameters_table(&models, &cols, &results, how);
    let stem = study.stem("kurt_9_2_parameters");
    p.write(&study.out, &stem)?;
    study.wrote(format!("{stem}.{{csv,md}}"), "Table 9.2: fitted non-linear parameters beside Kurt's; switched-off lobes marked undetermined", data);
    Ok(())
}

/// Table 9.2 proper: a row per model, its error on each material of `cols`
/// (`results[model][column]`) beside Kurt's.
fn errors_table(
    study: &Study,
    models: &[Model],
    cols: &[(usize, SampleSet)],
    results: &[Vec<FitSummary>],
    how: FitHow,
) -> Table {
    let mut header = vec!["model".to_string()];
    for (k, _) in cols {
        let n = TABLE_9_2_MATERIALS[*k].1;
        header.push(format!("{n} (ours)"));
        header.push(format!("{n} (Kurt)"));
    }
    let hdr: Vec<&str> = header.iter().map(String::as_str).collect();
    let metric = how.objective.name();
    let mut t = Table::new(
        &format!("Kurt Table 9.2: nine models on five CUReT materials ({metric})"),
        &hdr,
    );
    t.note = format!(
        "Data: {}. Ours are grey fits (only the RGB-averaged CUReT file is available), Kurt's RGB: compare rankings and shapes, not values. Fits: automatic multi-start, linear parameters projected out (NNLS), bounded SQP-style solver; polynomial by IRLS (bisquare) as Kurt fitted it. {} Generated by `brdf reproduce`.",
        study.curet_source(),
        lafortune_note(how.lbox)
    );
    for (m, (label, _, _)) in models.iter().enumerate() {
        let mut r = vec![Cell::Text(label.to_string())];
        for (c, (k, _)) in cols.iter().enumerate() {
            r.push(Cell::Num(err(&results[m][c]), 3));
            r.push(nine_index(label).map_or(Cell::Empty, |i| Cell::Num(KURT_9_2[i][*k], 3)));
        }
        t.rows.push(r);
    }
    t
}

/// The fitted non-linear parameters beside Kurt's: a row per model he
/// listed them for and material of `cols`.
fn parameters_table(
    models: &[Model],
    cols: &[(usize, SampleSet)],
    results: &[Vec<FitSummary>],
    how: FitHow,
) -> Table {
    let mut p = Table::new(
        "Kurt Table 9.2: fitted non-linear parameters (ours, grey) and Kurt's (RGB)",
        &[
            "model",
            "material",
            "parameters (value, [at bound])",
            "Kurt 2007 (RGB)",
            "termination",
        ],
    );
    p.note = format!(
        "A lobe whose strengths all fit to 0 (switched off) leaves its shape parameters undetermined: the model does not depend on them, and they are marked so instead of printing the solver's last value. {} Generated by `brdf reproduce`.",
        lafortune_note(how.lbox)
    );
    for (m, (label, _, _)) in models.iter().enumerate() {
        let Some(kurt) = KURT_PARAMS.iter().find(|k| k.0 == *label) else {
            continue;
        };
        for (c, (k, _)) in cols.iter().enumerate() {
            let r = &results[m][c];
            p.rows.push(vec![
                Cell::Text(label.to_string()),
                Cell::Text(TABLE_9_2_MATERIALS[*k].1.to_string()),
                Cell::Text(parameter_text(r)),
                Cell::Text(kurt.1[*k].to_string()),
                Cell::Text(r.termination.to_string()),
            ]);
        }
    }
    p
}
