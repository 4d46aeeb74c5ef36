//! What `brdf reproduce` runs: the parts, materials, models, degrees, lobes,
//! metrics and angle limits, from `--only`, `--spec FILE` (TOML) or the
//! defaults (everything, as the theses did it).
//!
//! ```toml
//! tables = ["kurt_9_1", "kurt_9_2"]   # parts (default: all)
//! materials = ["25", "cayman"]         # CUReT numbers or name parts (default: all)
//! models = ["ward", "ggx"]             # catalogue names or labels (default: nine + renderer)
//! degrees = [1, 2, 3]                  # Table 9.1 / Fig. 9.1 degrees (default 1..=12)
//! lobes = 1                            # Lafortune / Cook-Torrance / GGX lobes
//! metrics = ["ngan"]                   # objectives of the CUReT fits
//! limits = [80.0]                      # angle limits (deg) of the CUReT fits
//! lafortune_box = "kurt"               # or "wide" (Cxy, Cz in [-1, 1])
//! ```

use std::path::Path;

use serde::Deserialize;

use crate::StudyError;

pub use super::models::LafortuneBox;

/// The selection of a study run.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StudySpec {
    /// Parts to run (names of `crate::parts::PARTS`, checked against the
    /// names passed to [`StudySpec::check`]); empty = all.
    pub tables: Vec<String>,
    /// Materials: CUReT sample numbers or case-insensitive parts of a
    /// material's name; empty = all.
    pub materials: Vec<String>,
    /// Models of Kurt's comparison and the renderer models beside them:
    /// catalogue names or table labels; empty = all.
    pub models: Vec<String>,
    /// Polynomial degrees of Table 9.1 (and Fig. 9.1, up to 6).
    pub degrees: Vec<usize>,
    /// Lobes of Lafortune, Cook-Torrance and GGX.
    pub lobes: usize,
    /// Objectives of the CUReT fits (`ngan`, `lafortune`, `log`, ...).
    pub metrics: Vec<String>,
    /// Angle limits (degrees) of the CUReT fits.
    pub limits: Vec<f64>,
    /// Lafortune's box in the thesis tables.
    pub lafortune_box: LafortuneBox,
}

impl Default for StudySpec {
    fn default() -> Self {
        StudySpec {
            tables: Vec::new(),
            materials: Vec::new(),
            models: Vec::new(),
            degrees: (1..=12).collect(),
            lobes: 1,
            metrics: vec!["ngan".into()],
            limits: vec![80.0],
            lafortune_box: LafortuneBox::Kurt,
        }
    }
}

impl StudySpec {
    /// Read a spec file; every error names the file. `parts`: the names of
    /// the study's parts (`crate::parts::names()`), which `tables` may name.
    pub fn read(path: &Path, parts: &[&str]) -> Result<Self, StudyError> {
        let text = std::fs::read_to_string(path).map_err(|e| StudyError::Io {
            path: path.display().to_string(),
            source: e,
        })?;
        Self::parse(&text, parts).map_err(|e| StudyError::Usage(format!("{}: {e}", path.display())))
    }

    /// Parse and check spec text (`parts` as for [`StudySpec::read`]).
    pub fn parse(text: &str, parts: &[&str]) -> Result<Self, String> {
        let spec: StudySpec = toml::from_str(text).map_err(|e| e.message().to_string())?;
        spec.check(parts)?;
        Ok(spec)
    }

    /// Reject impossible selections with a message naming the field.
    /// `parts`: the names of the study's parts. They are passed in, not
    /// looked up, so the selection does not know the part list (the list
    /// knows the parts, and the parts know this selection).
    pub fn check(&self, parts: &[&str]) -> Result<(), String> {
        for t in &self.tables {
            if !parts.contains(&t.as_str()) {
                return Err(format!(
                    "tables: unknown part `{t}` (known: {})",
                    parts.join(", ")
                ));
            }
        }
        if let Some(d) = self.degrees.iter().find(|d| **d == 0 || **d > 20) {
            return Err(format!("degrees: {d} is outside 1..=20"));
        }
        if self.degrees.is_empty() {
            return Err("degrees: the list is empty".into());
        }
        if self.lobes == 0 || self.lobes > 4 {
            return Err(format!("lobes: {} is outside 1..=4", self.lobes));
        }
        if self.metrics.is_empty() || self.limits.is_empty() {
            return Err("metrics and limits need at least one value each".into());
        }
        for m in &self.metrics {
            brdf_fit::Objective::parse(m).map_err(|e| format!("metrics: {e}"))?;
        }
        if let Some(l) = self.limits.iter().find(|l| !(**l > 0.0 && **l <= 90.0)) {
            return Err(format!("limits: {l} is outside (0, 90] degrees"));
        }
        for m in &self.models {
            let known = super::models::nine_models(1)
                .into_iter()
                .chain(super::models::renderer_models(1));
            if !known
                .into_iter()
                .any(|(label, name, _)| names_model(m, label, name))
            {
                // An unknown name gets the resolver's suggestions, as
                // `brdf fit --model` gives them.
                return Err(match brdf_fit::resolve(m) {
                    Err(e) => format!("models: {e}"),
                    Ok(_) => format!(
                        "models: `{m}` is none of Kurt's nine or the renderer models (catalogue names or labels)"
                    ),
                });
            }
        }
        Ok(())
    }

    /// Whether part `name` is selected.
    pub fn runs(&self, name: &str) -> bool {
        self.tables.is_empty() || self.tables.iter().any(|t| t == name)
    }

    /// Whether a material (its set name) is selected.
    pub fn has_material(&self, name: &str) -> bool {
        if self.materials.is_empty() {
            return true;
        }
        let lower = name.to_lowercase();
        let number = name
            .strip_prefix("curet#")
            .and_then(|r| r.split(' ').next())
            .map(str::to_string);
        // A number names a CUReT sample only; other text is part of a name.
        self.materials.iter().any(|m| match m.parse::<u32>() {
            Ok(_) => number.as_deref() == Some(m.as_str()),
            Err(_) => lower.contains(&m.to_lowercase()),
        })
    }

    /// Whether a model (label and catalogue name) is selected.
    pub fn has_model(&self, label: &str, name: &str) -> bool {
        self.models.is_empty() || self.models.iter().any(|m| names_model(m, label, name))
    }
}

/// Whether the user's model name `m` selects the study's model with table
/// label `label` and catalogue name `name`: the label (any case), or any
/// spelling of the name `brdf fit --model` accepts (`brdf_fit::resolve`:
/// any case, `_` or a space for `-`), so the study and the fit take the
/// same names.
fn names_model(m: &str, label: &str, name: &str) -> bool {
    m.eq_ignore_ascii_case(label) || brdf_fit::resolve(m).is_ok_and(|e| e.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The part names as `crate::parts::names()` gives them (not imported:
    /// the selection does not know the part list).
    const PARTS: &[&str] = &[
        "kurt_9_1",
        "kurt_9_2",
        "kurt_9_4",
        "kurt_9_4_times",
        "kurt_9_5",
        "lafortune_box",
        "fig_9_1",
        "fig_9_2",
        "kurt_9_3",
        "sopp",
        "nist",
        "stability",
    ];

    #[test]
    fn parses_a_reduced_spec_and_selects() {
        let s = StudySpec::parse(
            "tables = [\"kurt_9_1\"]\nmaterials = [\"25\", \"felt\"]\nmodels = [\"ward\"]\ndegrees = [1, 2]\n",
            PARTS,
        )
        .unwrap();
        assert!(s.runs("kurt_9_1") && !s.runs("kurt_9_2"));
        assert!(s.has_material("curet#25 Quarry Tile"));
        assert!(!s.has_material("curet#2 Polyester"));
        assert!(
            !s.has_material("curet#10 Plaster_a"),
            "a number matches only the sample number"
        );
        assert!(s.has_material("curet#1 Felt"));
        assert!(s.has_model("Ward", "ward") && !s.has_model("Blinn-Phong", "blinn-phong"));
        assert_eq!(s.lafortune_box, LafortuneBox::Kurt);
        assert_eq!(s.limits, vec![80.0]);
    }

    #[test]
    fn renderer_models_are_selected_by_name_or_label() {
        let s = StudySpec::parse("models = [\"ggx\", \"Principled\"]\n", PARTS).unwrap();
        assert!(s.has_model("GGX", "ggx") && s.has_model("Principled", "principled"));
        assert!(!s.has_model("glTF", "gltf") && !s.has_model("Ward", "ward"));
        assert!(StudySpec::parse("models = [\"gltf-ext\"]\n", PARTS).is_ok());
    }

    #[test]
    fn models_take_the_names_brdf_fit_takes() {
        for spelling in ["blinn_phong", "Blinn Phong", "BLINN-PHONG", "blinn-phong"] {
            let s = StudySpec::parse(&format!("models = [\"{spelling}\"]\n"), PARTS)
                .unwrap_or_else(|e| panic!("{spelling}: {e}"));
            assert!(s.has_model("Blinn-Phong", "blinn-phong"), "{spelling}");
            assert!(!s.has_model("Phong", "phong"), "{spelling}");
        }
        let s = StudySpec::parse("models = [\"cook_torrance\", \"GLTF_EXT\"]\n", PARTS).unwrap();
        assert!(s.has_model("glTF + KHR", "gltf-ext"));
        assert!(!s.has_model("glTF", "gltf"));
        let e = StudySpec::parse("models = [\"blinn_phongg\"]\n", PARTS).unwrap_err();
        assert!(e.contains("models") && e.contains("`blinn-phong`"), "{e}");
    }

    #[test]
    fn bad_specs_name_the_field() {
        for (text, word) in [
            ("tables = [\"kurt_9_9\"]", "tables"),
            ("degrees = [0]", "degrees"),
            ("lobes = 0", "lobes"),
            ("metrics = [\"l3\"]", "metrics"),
            ("limits = [95.0]", "limits"),
            ("models = [\"phong-x\"]", "models"),
            ("colour = 1", "colour"),
            ("lafortune_box = \"narrow\"", "narrow"),
        ] {
            let e = StudySpec::parse(text, PARTS).unwrap_err();
            assert!(e.contains(word), "{text}: {e}");
        }
    }
}
