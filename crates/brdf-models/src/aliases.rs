//! Other names users call catalogue models by: the Disney BRDF is
//! `principled`, glTF's metallic-roughness material is `gltf`. A name
//! resolver suggests the catalogue name for an alias (`no model `disney`;
//! did you mean `principled`?`) rather than resolving it silently, so the
//! user learns the name the reports, saved models and exports use.

/// `(alias, catalogue name)`, aliases written as [`alias`] compares them:
/// lower case, `-` for spaces and `_`.
pub const ALIASES: &[(&str, &str)] = &[
    ("disney", "principled"),
    ("disney-principled", "principled"),
    ("disney-brdf", "principled"),
    ("burley", "principled"),
    ("principled-bsdf", "principled"),
    ("pbr", "gltf"),
    ("metallic-roughness", "gltf"),
    ("gltf-pbr", "gltf"),
    ("khr-materials", "gltf-ext"),
    ("lambertian", "lambert"),
    ("diffuse", "lambert"),
    ("trowbridge-reitz", "ggx"),
    ("blinn", "blinn-phong"),
];

/// A model name as the catalogue spells names: trimmed, lower case, `_`
/// and spaces as `-` (`"Disney Principled"` gives `disney-principled`).
pub fn normalise(name: &str) -> String {
    name.trim()
        .to_lowercase()
        .chars()
        .map(|c| {
            if c == '_' || c.is_whitespace() {
                '-'
            } else {
                c
            }
        })
        .collect()
}

/// The catalogue name `name` is another name for, if it is one (case,
/// spaces and `_` ignored: `"Disney Principled"` gives `principled`).
pub fn alias(name: &str) -> Option<&'static str> {
    let key = normalise(name);
    ALIASES.iter().find(|(a, _)| *a == key).map(|(_, m)| *m)
}
