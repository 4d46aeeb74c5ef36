//! `brdf reproduce` as a library call: run the parts of [`crate::parts`]
//! (all by default; a selection by name or a spec file), write their
//! tables, plots and renderings into the output folder, and generate its
//! `README.md`. Nothing outside the selection is loaded or fitted.
//!
//! Data: [`Reproduce::data`] or `BRDF_DATA`; without measured data it runs
//! on the built-in synthetic materials into `OUT/synthetic/` (never over
//! measured results) and says so in every table.

use std::path::PathBuf;

use crate::StudyError;
use crate::context::spec::{LafortuneBox, StudySpec};
use crate::context::{Study, create_dir};
use crate::{parts, readme};

/// What to reproduce, where.
#[derive(Clone, Default)]
pub struct Reproduce {
    /// Folder with the measured data (`None`: `$BRDF_DATA`, else synthetic).
    pub data: Option<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// Run only these parts (empty: the spec's, or all).
    pub only: Vec<String>,
    /// A TOML spec file (see [`crate::context::spec`]).
    pub spec: Option<PathBuf>,
    /// Fit Lafortune in the wide box instead of Kurt's.
    pub lafortune_wide: bool,
    /// Worker threads for the fits (`None`: all cores); results are the
    /// same for any count.
    pub threads: Option<usize>,
    /// Who watches the parts' progress (`None`: nobody).
    pub progress: Option<std::sync::Arc<dyn brdf_core::progress::Progress>>,
}

/// What a run wrote.
#[derive(Clone, Debug)]
pub struct Reproduced {
    /// Entries written (each listed in the folder's `README.md`).
    pub written: usize,
    /// The folder they are in.
    pub out: PathBuf,
}

/// Every part: `(name, what it reproduces)`, in the order they run.
pub fn list() -> Vec<(&'static str, &'static str)> {
    parts::PARTS.iter().map(|p| (p.name, p.about)).collect()
}

fn spec_of(r: &Reproduce) -> Result<StudySpec, StudyError> {
    let names = parts::names();
    let mut spec = match &r.spec {
        Some(p) => StudySpec::read(p, &names)?,
        None => StudySpec::default(),
    };
    if !r.only.is_empty() {
        spec.tables = r.only.clone();
    }
    if r.lafortune_wide {
        spec.lafortune_box = LafortuneBox::Wide;
    }
    spec.check(&names)
        .map_err(|e| StudyError::Usage(format!("--only/--spec: {e}")))?;
    Ok(spec)
}

/// Run the selection and write its results and `README.md`.
pub fn run(r: &Reproduce) -> Result<Reproduced, StudyError> {
    if let Some(observer) = &r.progress {
        crate::context::progress::set_observer(observer.clone());
    }
    let spec = spec_of(r)?;
    let data = r
        .data
        .clone()
        .or_else(|| std::env::var_os("BRDF_DATA").map(PathBuf::from));
    // The synthetic demonstration never writes over measured results.
    let out = if data.is_none() {
        let out = r.out.join("synthetic");
        eprintln!(
            "brdf reproduce: no measured data (BRDF_DATA unset, no --data): running on built-in synthetic data into {}",
            out.display()
        );
        out
    } else {
        r.out.clone()
    };
    create_dir(&out)?;
    let mut study = Study::new(data, out, spec);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(r.threads.unwrap_or(0))
        .build()
        .map_err(|e| StudyError::Usage(format!("--threads: {e}")))?;
    pool.install(|| parts::run_all(&mut study))?;
    readme::write(&study, &command_line(r))?;
    Ok(Reproduced {
        written: study.written.len(),
        out: study.out.clone(),
    })
}

/// The command as it was run, for the README (no absolute paths: the data
/// folder is named by `BRDF_DATA`).
fn command_line(r: &Reproduce) -> String {
    let mut s = "brdf reproduce".to_string();
    if !r.only.is_empty() {
        s += &format!(" --only {}", r.only.join(","));
    }
    if let Some(p) = &r.spec {
        s += &format!(
            " --spec {}",
            crate::report::data_name(&p.display().to_string())
        );
    }
    if r.lafortune_wide {
        s += " --lafortune-wide";
    }
    s
}
