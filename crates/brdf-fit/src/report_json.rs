//! What a fit reports to a program: the JSON of `brdf fit --json`, of
//! `brdf select --json` and of `brdf select --by-image --json` (also what
//! the Python module's `fit` and `select` return), and data-set names for
//! outputs, so every front end names fits and data the same way.

use brdf_core::SampleSet;
use brdf_render::ImageError;

use crate::judged::SCATTERED_NOTE;
use crate::select::{Search, SelectRow};
use crate::select_by_image::ImageChoice;
use crate::{FitError, FitReport};

/// The JSON report of the fits of one data set (one per channel set): the
/// fit summaries, and what the first fit's filters dropped; `data` is the
/// data set as loaded (its negative values are counted, they are kept).
pub fn fit_json(reports: &[FitReport], data: &SampleSet) -> Result<serde_json::Value, FitError> {
    let first = reports.first().ok_or_else(|| FitError::NoFit {
        data: data.name.clone(),
    })?;
    Ok(serde_json::json!({
        "fits": reports.iter().map(|r| &r.summary).collect::<Vec<_>>(),
        "notes": reports.iter().map(|r| &r.notes).collect::<Vec<_>>(),
        "image_errors": reports.iter().map(|r| &r.image_error).collect::<Vec<_>>(),
        // Why a fit has no image error (scattered data), or null.
        "image_notes": reports.iter().map(|r| &r.image_note).collect::<Vec<_>>(),
        "candidates": reports.iter().map(|r| &r.candidates).collect::<Vec<_>>(),
        "samples_present": first.samples_present,
        "dropped_invalid": first.dropped_invalid,
        "dropped_angle": first.dropped_angle,
        "negative_values_kept": data.count_negative(),
    }))
}

/// The JSON report of a selection (`brdf select --json`): every
/// candidate's row, the choice's, and the choice's image errors (`null`
/// on scattered data, with the note why; `image` as
/// a [`crate::SelectRequest`] gives it).
pub fn select_json(
    data: &SampleSet,
    tolerance: f64,
    search: Search,
    rows: &[SelectRow],
    choice: usize,
    image: Option<&ImageError>,
) -> Result<serde_json::Value, FitError> {
    let chosen = rows.get(choice).ok_or_else(|| FitError::NoChoice {
        data: data.name.clone(),
    })?;
    Ok(serde_json::json!({
        "data": data.name,
        "samples": data.len(),
        "tolerance": tolerance,
        "search": match search {
            Search::Exhaustive => "exhaustive",
            Search::CoarseToFine => "coarse to fine",
        },
        "choice": chosen,
        "choice_image_error": image,
        "image_note": image.is_none().then_some(SCATTERED_NOTE),
        "candidates": rows,
    }))
}

/// The JSON report of a selection by image error (`brdf select --by-image
/// --json`): the data set's name, the choice's row and every row, in the
/// order [`crate::select_by_image::select_by_image`] returns them. One function
/// so that the command and the Python module print the same shape; a
/// `choice` outside `rows` is an error naming the data rather than a panic.
pub fn select_by_image_json(
    data_name: &str,
    rows: &[ImageChoice],
    choice: usize,
) -> Result<serde_json::Value, FitError> {
    let chosen = rows.get(choice).ok_or_else(|| FitError::NoChoice {
        data: data_name.to_string(),
    })?;
    Ok(serde_json::json!({ "data": data_name, "choice": chosen, "candidates": rows }))
}

/// A data set's name for outputs: relative to `BRDF_DATA` when it lies
/// inside it, as given when relative, its file name otherwise — never an
/// absolute machine path.
pub fn data_name(spec: &str) -> String {
    let path = std::path::Path::new(spec);
    if let Some(root) = std::env::var_os("BRDF_DATA")
        && let Ok(rest) = path.strip_prefix(std::path::Path::new(&root))
    {
        return rest.display().to_string();
    }
    if path.is_relative() {
        return spec.to_string();
    }
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| spec.to_string())
}

#[cfg(test)]
mod tests {
    use brdf_core::Direction;

    use super::*;
    use crate::Fit;

    /// Lambert, kd = 0.3, at four pairs, one beyond 80 deg, one NaN and
    /// one negative value.
    fn samples() -> SampleSet {
        let mut s = SampleSet::new("toy", "hand-made", vec!["grey".into()]);
        let d = |t: f64| Direction::from_spherical(t.to_radians(), 0.0).unwrap();
        let v = 0.3 / std::f64::consts::PI;
        for (ti, to, f) in [(0.0, 10.0, v), (20.0, 30.0, v), (40.0, 50.0, -v)] {
            s.push(&d(ti), &d(to), &[f], 1.0).unwrap();
        }
        s.push(&d(85.0), &d(0.0), &[v], 1.0).unwrap();
        s.push(&d(10.0), &d(0.0), &[f64::NAN], 1.0).unwrap();
        s
    }

    #[test]
    fn report_counts_what_the_filters_did() {
        let data = samples();
        let rep = Fit::model("lambert").unwrap().run(&data).unwrap();
        let v = fit_json(&[rep], &data).unwrap();
        assert_eq!(v["samples_present"], 5);
        assert_eq!(v["dropped_invalid"], 1);
        assert_eq!(v["dropped_angle"], 1);
        assert_eq!(v["negative_values_kept"], 1);
        assert_eq!(v["fits"].as_array().unwrap().len(), 1);
        assert_eq!(v["fits"][0]["model"], "lambert");
        assert_eq!(v["fits"][0]["samples"], 3);
    }

    #[test]
    fn no_fit_is_an_error_naming_the_data() {
        let e = fit_json(&[], &samples()).unwrap_err();
        assert_eq!(e.to_string(), "`toy`: no fit to report");
    }

    #[test]
    fn by_image_report_without_its_choice_is_an_error_naming_the_data() {
        let e = select_by_image_json("toy", &[], 0).unwrap_err();
        assert_eq!(e.to_string(), "`toy`: no candidate chosen");
    }

    #[test]
    fn data_names_are_never_absolute() {
        assert_eq!(data_name("curet/abrdf.dat#25"), "curet/abrdf.dat#25");
        assert_eq!(data_name("/somewhere/else/paper.bsdf"), "paper.bsdf");
    }
}
