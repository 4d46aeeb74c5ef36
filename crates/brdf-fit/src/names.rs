//! Forgiving model names: case-insensitive, `_` and spaces equal to `-`,
//! display names ("Blinn-Phong", "Cook Torrance") accepted; an unknown name
//! gets the nearest catalogue names as a suggestion.

use brdf_models::aliases::normalise;
use brdf_models::{ModelEntry, catalogue};

use crate::FitError;

/// Levenshtein distance (for suggestions).
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The catalogue entry a user's name means.
pub fn resolve(name: &str) -> Result<ModelEntry, FitError> {
    let want = normalise(name);
    let all = catalogue();
    if let Some(e) = all.iter().find(|e| e.name == want) {
        return Ok(*e);
    }
    let mut near: Vec<(usize, &str)> = all
        .iter()
        .map(|e| (distance(&want, e.name), e.name))
        .collect();
    near.sort();
    let mut suggest: Vec<&str> = near
        .iter()
        .filter(|(d, n)| *d <= 3.max(want.len() / 3) || n.starts_with(&want))
        .take(3)
        .map(|(_, n)| *n)
        .collect();
    // Another name of a catalogue model ("disney") is the best suggestion.
    if let Some(a) = brdf_models::aliases::alias(name) {
        suggest.retain(|s| *s != a);
        suggest.insert(0, a);
    }
    Err(FitError::UnknownModel {
        name: name.to_string(),
        suggestions: suggest.iter().map(|s| s.to_string()).collect(),
    })
}
