//! The candidates `brdf select` fits: every catalogue model (with 1 and 2
//! lobes where it has lobes), Koenderink orders 2..8, polynomial degrees
//! 1..12, narrowed by [`Among`], each built for the data it will be fitted
//! to, and the stored numbers each counts.

use brdf_core::{Parametric, SampleSet};
use brdf_models::{ModelConfig, catalogue};

use super::SelectRow;
use crate::FitError;

/// The candidates: `(label, model, config)`.
pub fn candidates(channels: usize) -> Vec<(String, &'static str, ModelConfig)> {
    let base = ModelConfig {
        channels,
        ..ModelConfig::default()
    };
    let mut v = Vec::new();
    for e in catalogue() {
        // The coloured-lobe variants are the same model written for each
        // renderer: a selection by L2 would fit it ten times over.
        if brdf_models::coloured_lobes::variant_named(e.name).is_some() {
            continue;
        }
        match e.name {
            "koenderink" => {
                for order in 2..=8 {
                    v.push((
                        format!("koenderink order {order}"),
                        e.name,
                        ModelConfig { order, ..base },
                    ));
                }
            }
            "polynomial" => {
                for degree in 1..=12 {
                    v.push((
                        format!("polynomial degree {degree}"),
                        e.name,
                        ModelConfig { degree, ..base },
                    ));
                }
            }
            "polynomial-aniso" => {}
            _ if e.has_lobes => {
                for lobes in 1..=2 {
                    v.push((
                        format!(
                            "{} ({lobes} lobe{})",
                            e.name,
                            if lobes > 1 { "s" } else { "" }
                        ),
                        e.name,
                        ModelConfig { lobes, ..base },
                    ));
                }
            }
            _ => v.push((e.name.to_string(), e.name, base)),
        }
    }
    v
}

/// Which candidates to fit: only these models (forgiving names; all when
/// empty), only those with at most this many stored numbers.
#[derive(Clone, Debug, Default)]
pub struct Among {
    /// Model names (`--models`); every catalogue model when empty.
    pub models: Vec<String>,
    /// The most stored numbers a candidate may have (`--max-parameters`).
    pub max_parameters: Option<usize>,
}

impl Among {
    /// The resolved model names, without repeats; `None` for all.
    fn names(&self) -> Result<Option<Vec<&'static str>>, FitError> {
        if self.models.is_empty() {
            return Ok(None);
        }
        let mut out: Vec<&'static str> = Vec::new();
        for m in &self.models {
            let name = crate::names::resolve(m)?.name;
            if !out.contains(&name) {
                out.push(name);
            }
        }
        Ok(Some(out))
    }
}

/// Stored numbers of a model of `name` with `n_params` parameters: the
/// polynomial's PCA transform and Dupuy's table of `D` count too.
pub(super) fn stored_numbers(name: &str, n_params: usize) -> usize {
    n_params
        + match name {
            "polynomial" => 4,
            brdf_models::dupuy::NAME => brdf_models::dupuy::DUPUY_NODES,
            _ => 0,
        }
}

/// One admitted candidate, built for all of the data (a model read off the
/// data, or built for its directions, is the same model whichever
/// samples it is then fitted to).
pub(super) struct Candidate {
    /// Row label.
    pub label: String,
    /// Catalogue name.
    pub name: &'static str,
    /// The model, at its default parameters.
    pub model: Box<dyn Parametric>,
}

/// An admitted candidate: to be fitted, or already a failed row.
pub(super) enum Todo {
    /// Built: to be fitted.
    Fit(Candidate),
    /// Could not be built from the samples: its row says why.
    Failed(SelectRow),
}

/// The candidates `among` admits for `data`, in candidate order: a model
/// that cannot be built from these samples (Dupuy's table needs
/// back-scattering ones) is a failed row in its place.
pub(super) fn admitted(data: &SampleSet, among: &Among) -> Result<Vec<Todo>, FitError> {
    let names = among.names()?;
    let mut todo = Vec::new();
    for (label, name, config) in candidates(data.channels()) {
        if names.as_ref().is_some_and(|v| !v.contains(&name)) {
            continue;
        }
        let Some(e) = brdf_models::entry(name) else {
            continue;
        };
        let model = match e.build_from(&config, data) {
            Ok(m) => m,
            Err(err) if e.from_samples.is_some() => {
                todo.push(Todo::Failed(SelectRow::failed(
                    label,
                    name,
                    0,
                    data.len(),
                    &err,
                )));
                continue;
            }
            Err(err) => return Err(err.into()),
        };
        if model.n_params() >= data.len() * data.channels() {
            continue;
        }
        if among
            .max_parameters
            .is_some_and(|m| stored_numbers(name, model.n_params()) > m)
        {
            continue;
        }
        todo.push(Todo::Fit(Candidate { label, name, model }));
    }
    Ok(todo)
}
