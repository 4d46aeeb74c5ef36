//! The named parts of the study. `brdf reproduce --only NAMES` (or
//! `tables` in a `--spec` file) runs a selection; the default runs them
//! all, in this order. Adding a part is one line in [`PARTS`]: a name, what
//! it writes, whether it is repeated for every metric and angle limit of
//! the spec, and the function that runs it on the shared [`Study`].

use crate::StudyError;
use crate::context::Study;

/// A part of the study.
pub struct Part {
    /// Name for `--only` and `tables`.
    pub name: &'static str,
    /// One line: what it reproduces.
    pub about: &'static str,
    /// Run once per metric x angle limit of the spec (the CUReT fits).
    pub per_variant: bool,
    /// Files or folders under the data root it cannot run without (a part
    /// whose data are absent is skipped and said to be).
    pub needs: &'static [&'static str],
    /// The work.
    pub run: fn(&mut Study) -> Result<(), StudyError>,
}

/// CUReT's measurements and the table of their directions.
const CURET: &[&str] = &["curet/abrdf.dat", "curet/table.txt"];

/// Every part, in the order the study runs them (one line each).
#[rustfmt::skip]
pub const PARTS: &[Part] = &[
    Part { name: "kurt_9_1", about: "Table 9.1: polynomial error against degree (cayman, quarry tile)", per_variant: true, needs: &["curet/abrdf.dat", "curet/table.txt", "cornell/cayman.brdf"], run: crate::kurt::table_9_1::run },
    Part { name: "kurt_9_2", about: "Table 9.2: nine models on five CUReT materials, fitted parameters", per_variant: true, needs: CURET, run: crate::kurt::table_9_2::run },
    Part { name: "kurt_9_4", about: "Figure 9.4: eight models on every CUReT material, polynomial wins (IRLS and OLS)", per_variant: true, needs: CURET, run: crate::kurt::figure_9_4::run },
    Part { name: "kurt_9_4_times", about: "Table 9.4: mean fit time per model; error against fit time (renderer models too) with the Pareto front", per_variant: true, needs: CURET, run: crate::kurt::table_9_4::run },
    Part { name: "kurt_9_5", about: "Figure 9.5: Koenderink and polynomial on every CUReT material", per_variant: true, needs: CURET, run: crate::kurt::figure_9_5::run },
    Part { name: "lafortune_box", about: "Lafortune in Kurt's box against the wide box on every CUReT material", per_variant: true, needs: CURET, run: crate::kurt::lafortune_box::run },
    Part { name: "fig_9_1", about: "Figure 9.1: spheres of the polynomial at degrees 1..6 beside the measured material", per_variant: false, needs: &["rgl"], run: crate::figures::figure_9_1 },
    Part { name: "fig_9_2", about: "Figure 9.2: spheres of the models fitted to the Table 9.2 materials", per_variant: true, needs: CURET, run: crate::figures::figure_9_2 },
    Part { name: "kurt_9_3", about: "Table 9.3 stand-in: dense materials, L2 and PSNR, renderer models beside Kurt's; Figures 9.3 and 9.6, renderer spheres", per_variant: false, needs: &["rgl"], run: crate::dense_tables::write },
    Part { name: "new_models", about: "New models (ABC, STD, SGD, Dupuy) against the classic and renderer models on the RGL materials: L2 and image FLIP of brdf fit's fits for L2 and for appearance", per_variant: false, needs: &["rgl"], run: crate::new_models::write },
    Part { name: "sopp", about: "Sopp's Appendix A.8/A.9 on the RGL materials, preview strips", per_variant: false, needs: &["rgl"], run: crate::sopp_tables::write },
    Part { name: "nist", about: "NIST StRD certification of the solver", per_variant: false, needs: &["nist_strd"], run: crate::nist::part },
    Part { name: "stability", about: "Stability: extreme and bad inputs, NIST from both starts", per_variant: false, needs: &[], run: crate::stability::part },
];

/// The part named `name`.
pub fn find(name: &str) -> Option<&'static Part> {
    PARTS.iter().find(|p| p.name == name)
}

/// Every part's name.
pub fn names() -> Vec<&'static str> {
    PARTS.iter().map(|p| p.name).collect()
}

/// Run the selected parts: the per-variant ones for every metric and
/// limit, the others once.
pub fn run_all(study: &mut Study) -> Result<(), StudyError> {
    let metrics = study.spec.metrics.clone();
    let limits = study.spec.limits.clone();
    let selected: Vec<&Part> = PARTS.iter().filter(|p| study.spec.runs(p.name)).collect();
    let mut ran = 0;
    for part in &selected {
        if let Some(why) = missing_data(study, part) {
            eprintln!("brdf reproduce: {} skipped: {why}", part.name);
            study.skipped.push((part.name.into(), why));
            continue;
        }
        ran += 1;
        let variants: Vec<(String, f64)> = if part.per_variant {
            metrics
                .iter()
                .flat_map(|m| limits.iter().map(move |l| (m.clone(), *l)))
                .collect()
        } else {
            vec![("ngan".into(), 80.0)]
        };
        for (metric, limit) in variants {
            study.variant = crate::context::Variant { metric, limit };
            eprintln!("brdf reproduce: {} ({})", part.name, part.about);
            (part.run)(study)?;
        }
    }
    if ran == 0 && !selected.is_empty() && study.data.is_none() {
        return Err(StudyError::Usage(
            "nothing to reproduce: the selected parts need measured data; set BRDF_DATA or pass --data (see README, Measured data)".into(),
        ));
    }
    if ran == 0 && !selected.is_empty() {
        let root = study
            .data
            .as_ref()
            .map_or("the data folder".into(), |d| d.display().to_string());
        return Err(StudyError::Usage(format!(
            "nothing to reproduce: {root} holds none of the data the selected parts need (curet/, cornell/, rgl/, nist_strd/; see README, Measured data)"
        )));
    }
    Ok(())
}

/// The data the built-in demonstration stands in for: CUReT and Cornell.
const SYNTHETIC_STANDS_IN_FOR: [&str; 2] = ["curet/", "cornell/"];

/// Why `part` cannot run on the study's data (`None` when it can). The
/// built-in demonstration stands in for CUReT and Cornell only, so a part
/// that needs other data is skipped before it is announced.
fn missing_data(study: &Study, part: &Part) -> Option<String> {
    if study.data.is_none() {
        let missing: Vec<String> = part
            .needs
            .iter()
            .filter(|rel| !SYNTHETIC_STANDS_IN_FOR.iter().any(|p| rel.starts_with(p)))
            .map(|rel| format!("$BRDF_DATA/{rel}"))
            .collect();
        return (!missing.is_empty()).then(|| {
            format!(
                "needs measured data ({}); the built-in synthetic data stand in for CUReT and Cornell only",
                missing.join(" and ")
            )
        });
    }
    let missing: Vec<String> = part
        .needs
        .iter()
        .filter(|rel| study.data_dir(rel).is_none())
        .map(|rel| format!("$BRDF_DATA/{rel}"))
        .collect();
    (!missing.is_empty()).then(|| format!("needs {}", missing.join(" and ")))
}
