//! Every alias names a catalogue model and is not itself one; spelling
//! variants of an alias resolve alike.

use brdf_models::aliases::{ALIASES, alias};

#[test]
fn every_alias_points_at_a_catalogue_model_and_shadows_none() {
    let names: Vec<&str> = brdf_models::catalogue().iter().map(|e| e.name).collect();
    for (a, m) in ALIASES {
        assert!(
            names.contains(m),
            "{a} -> {m}: not in the catalogue {names:?}"
        );
        assert!(!names.contains(a), "{a} is a catalogue name itself");
    }
}

#[test]
fn disney_and_pbr_are_recognised_in_any_spelling() {
    assert_eq!(alias("disney"), Some("principled"));
    assert_eq!(alias(" Disney Principled "), Some("principled"));
    assert_eq!(alias("DISNEY_BRDF"), Some("principled"));
    assert_eq!(alias("pbr"), Some("gltf"));
    assert_eq!(alias("principled"), None);
    assert_eq!(alias("no-such-model"), None);
}
