//! The exact exports of the coloured-lobe models (`lobes*`): the Mitsuba
//! nest of `blendbsdf`s read back from its XML (each leaf's effective
//! weight times its reflectance gives the model's colour of that term),
//! the Blender script's node values, the refusals across renderers, and
//! the checks by Mitsuba 3 itself on the fixtures of
//! `tests/reference/lobes/` (written by `LOBES_WRITE=1 cargo test
//! --release -p brdf-export --test export lobes::`, checked by
//! `tests/reference/lobes_check.sh`):
//!
//! - `mitsuba_values.json`: Mitsuba's `eval` of each `.xml` at 300
//!   direction pairs and at the normal, which the model must equal to 1e-4
//!   relative (single precision in Mitsuba);
//! - `render_check.json`: Mitsuba's render of each `.xml` (studio and sky
//!   light sets) and Cycles' render of each `.py` (studio) on the judge
//!   sphere beside `brdf-render`'s render of the model; under the studio
//!   set HDR-FLIP at most [`MITSUBA_FLIP`] (Mitsuba) and [`CYCLES_FLIP`]
//!   (Cycles), the bounds of the other exact exports
//!   (`tests/export/render_check.rs`).

use std::path::PathBuf;

use brdf_core::Parametric;
use brdf_export::{ConvertOptions, ExportError, Target, convert, export};
use brdf_models::saved_model::SavedModel;
use brdf_render::{LightSet, ShadingPoints};
use quick_xml::events::Event;

/// HDR-FLIP bound of a Mitsuba render of an exact export (as in
/// `tests/export/render_check.rs`).
const MITSUBA_FLIP: f64 = 0.02;
/// HDR-FLIP bound of a Cycles render of a Blender export (as in
/// `tests/export/render_check.rs`).
const CYCLES_FLIP: f64 = 0.03;
/// HDR-FLIP bound of MaterialX's GLSL render of an exact MaterialX export:
/// the `-materialx` models carry MaterialX's energy compensation, so the
/// bound of an exact export applies (the looser one of
/// `tests/export/render_check.rs` covers `gltf_pbr`, whose GLSL is not the glTF
/// formula).
const MATERIALX_FLIP: f64 = 0.02;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/lobes")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(dir().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn load(name: &str) -> Box<dyn Parametric> {
    let saved = SavedModel::load(&dir().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    saved.build().unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Build catalogue model `name` (3 channels, `lobes` lobes) at `params`
/// given by name.
fn model(name: &str, lobes: usize, params: &[(&str, f64)]) -> Box<dyn Parametric> {
    let config = brdf_models::ModelConfig {
        channels: 3,
        lobes,
        ..Default::default()
    };
    let mut m = brdf_models::build(name, &config).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut p = m.params().to_vec();
    for (n, v) in params {
        let i = m
            .param_specs()
            .iter()
            .position(|s| s.name == *n)
            .unwrap_or_else(|| panic!("{name} has no {n}"));
        p[i] = *v;
    }
    m.set_params(&p).unwrap();
    m
}

fn rgb(base: &str, c: [f64; 3]) -> Vec<(String, f64)> {
    ["r", "g", "b"]
        .iter()
        .zip(c)
        .map(|(s, v)| (format!("{base}_{s}"), v))
        .collect()
}

fn named(v: &[(String, f64)]) -> Vec<(&str, f64)> {
    v.iter().map(|(n, x)| (n.as_str(), *x)).collect()
}

/// A leaf BSDF of a Mitsuba nest: its type, effective weight (the product
/// of the blend weights on its path), reflectance, `alpha`, `eta`, `k`.
#[derive(Debug, Default, Clone)]
struct Leaf {
    kind: String,
    weight: f64,
    reflectance: Option<[f64; 3]>,
    alpha: Option<f64>,
    eta: Option<[f64; 3]>,
    k: Option<[f64; 3]>,
    material: Option<String>,
}

fn triple(s: &str) -> [f64; 3] {
    let v: Vec<f64> = s.split(',').map(|x| x.trim().parse().unwrap()).collect();
    match v.as_slice() {
        [x] => [*x; 3],
        [r, g, b] => [*r, *g, *b],
        _ => panic!("not a colour: {s}"),
    }
}

/// The leaves of the XML's `bsdf` nest, read with an XML parser (not the
/// writer's own terms).
fn leaves(xml: &str) -> Vec<Leaf> {
    struct Frame {
        kind: String,
        weight: f64,
        blend: f64,
        children: usize,
        leaf: Leaf,
    }
    let mut r = quick_xml::Reader::from_str(xml);
    let mut stack: Vec<Frame> = Vec::new();
    let mut out = Vec::new();
    let mut texture_for: Option<String> = None;
    loop {
        let ev = r.read_event().unwrap();
        let (start, empty) = match &ev {
            Event::Start(e) => (Some(e.clone()), false),
            Event::Empty(e) => (Some(e.clone()), true),
            Event::End(e) => {
                let tag = String::from_utf8_lossy(e.name().as_ref()).into_owned();
                if tag == "texture" {
                    texture_for = None;
                }
                if tag == "bsdf" {
                    let f = stack.pop().unwrap();
                    if f.kind != "blendbsdf" {
                        out.push(f.leaf);
                    }
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let e = start.unwrap();
        let tag = String::from_utf8_lossy(e.name().as_ref()).into_owned();
        let attr = |k: &str| {
            e.attributes()
                .flatten()
                .find(|a| a.key.as_ref() == k.as_bytes())
                .map(|a| a.unescape_value().unwrap().into_owned())
        };
        if tag == "bsdf" {
            let kind = attr("type").unwrap();
            // Effective weight: the parent's times this child's share.
            let weight = match stack.last_mut() {
                None => 1.0,
                Some(p) => {
                    p.children += 1;
                    if p.children == 1 {
                        p.weight * (1.0 - p.blend)
                    } else {
                        p.weight * p.blend
                    }
                }
            };
            let f = Frame {
                kind: kind.clone(),
                weight,
                blend: 0.0,
                children: 0,
                leaf: Leaf {
                    kind,
                    weight,
                    ..Default::default()
                },
            };
            if empty {
                out.push(f.leaf);
            } else {
                stack.push(f);
            }
            continue;
        }
        if tag == "texture" {
            texture_for = attr("name");
            continue;
        }
        let Some(top) = stack.last_mut() else {
            continue;
        };
        let name = attr("name").unwrap_or_default();
        let value = attr("value").unwrap_or_default();
        match (tag.as_str(), name.as_str()) {
            ("float", "weight") if top.kind == "blendbsdf" => top.blend = value.parse().unwrap(),
            ("float", "alpha") => top.leaf.alpha = Some(value.parse().unwrap()),
            ("rgb" | "float", "eta") => top.leaf.eta = Some(triple(&value)),
            ("rgb" | "float", "k") => top.leaf.k = Some(triple(&value)),
            ("string", "material") => top.leaf.material = Some(value),
            ("rgb", "reflectance" | "specular_reflectance") => {
                top.leaf.reflectance = Some(triple(&value))
            }
            ("rgb", "color") if texture_for.is_some() => {
                top.leaf.reflectance = Some(triple(&value))
            }
            _ => {}
        }
    }
    out
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|c| (a[c] - b[c]).abs() <= tol)
}

fn plain_params() -> Vec<(String, f64)> {
    let mut p = rgb("kd", [0.35, 0.2, 0.08]);
    p.extend(rgb("ks1", [0.05, 0.25, 0.3]));
    p.extend(rgb("ks2", [0.2, 0.12, 0.05]));
    p.push(("alpha1".into(), 0.08));
    p.push(("alpha2".into(), 0.35));
    p
}

#[test]
fn mitsuba_nest_weights_reproduce_each_terms_colour() {
    let m = model("lobes-mitsuba", 2, &named(&plain_params()));
    let xml = export(m.as_ref(), Target::Mitsuba).unwrap();
    let l = leaves(&xml);
    assert_eq!(l.len(), 3, "{xml}");
    let total: f64 = l.iter().map(|x| x.weight).sum();
    assert!((total - 1.0).abs() < 1e-12, "weights add to {total}");
    let eff = |x: &Leaf| x.reflectance.unwrap().map(|c| c * x.weight);
    let d = l.iter().find(|x| x.kind == "diffuse").unwrap();
    assert!(close(eff(d), [0.35, 0.2, 0.08], 1e-12), "{d:?}");
    for (alpha, ks) in [(0.08, [0.05, 0.25, 0.3]), (0.35, [0.2, 0.12, 0.05])] {
        let g = l.iter().find(|x| x.alpha == Some(alpha)).unwrap();
        assert_eq!(g.kind, "roughconductor");
        assert_eq!(g.material.as_deref(), Some("none"), "Fresnel exactly 1");
        assert!(close(eff(g), ks, 1e-12), "{g:?}");
    }
    // Amplitudes add to 0.85 <= 1: every reflectance is a plain <rgb>.
    assert!(!xml.contains("unbounded"), "{xml}");
}

fn conductor_coat_params() -> Vec<(String, f64)> {
    let mut p = rgb("kd", [0.1, 0.05, 0.02]);
    p.extend(rgb("eta1", [0.18, 0.42, 1.37]));
    p.extend(rgb("kappa1", [3.42, 2.35, 1.77]));
    p.extend(rgb("ks2", [0.05, 0.1, 0.2]));
    p.extend([
        ("alpha1".into(), 0.15),
        ("alpha2".into(), 0.4),
        ("coat_ior".into(), 1.6),
        ("coat_alpha".into(), 0.03),
    ]);
    p
}

#[test]
fn mitsuba_conductor_and_coat_lobes_keep_their_fresnel_at_full_amplitude() {
    let m = model(
        "lobes-conductor-coat-mitsuba",
        2,
        &named(&conductor_coat_params()),
    );
    let xml = export(m.as_ref(), Target::Mitsuba).unwrap();
    let l = leaves(&xml);
    assert_eq!(l.len(), 4, "{xml}");
    let total: f64 = l.iter().map(|x| x.weight).sum();
    assert!((total - 1.0).abs() < 1e-12);
    let eff = |x: &Leaf| x.reflectance.unwrap().map(|c| c * x.weight);
    let cond = l.iter().find(|x| x.alpha == Some(0.15)).unwrap();
    assert_eq!(cond.eta, Some([0.18, 0.42, 1.37]));
    assert_eq!(cond.k, Some([3.42, 2.35, 1.77]));
    assert!(close(eff(cond), [1.0; 3], 1e-12), "{cond:?}");
    let coat = l.iter().find(|x| x.alpha == Some(0.03)).unwrap();
    assert_eq!(coat.eta, Some([1.6; 3]));
    assert_eq!(coat.k, Some([0.0; 3]));
    assert!(close(eff(coat), [1.0; 3], 1e-12), "{coat:?}");
    let lobe = l.iter().find(|x| x.alpha == Some(0.4)).unwrap();
    assert!(close(eff(lobe), [0.05, 0.1, 0.2], 1e-12), "{lobe:?}");
    let d = l.iter().find(|x| x.kind == "diffuse").unwrap();
    assert!(close(eff(d), [0.1, 0.05, 0.02], 1e-12), "{d:?}");
    // Amplitudes add to 0.1 + 1 + 0.2 + 1 = 2.3: reflectances above 1
    // are unbounded srgb textures, and the file says why.
    assert!(xml.contains(r#"<boolean name="unbounded" value="true"/>"#));
    assert!(xml.contains("unbounded srgb"), "{xml}");
}

/// An F82-tinted lobe, a plain one and the coat (the Blender and MaterialX
/// writers' checks).
fn f82_coat_params() -> Vec<(String, f64)> {
    let mut p = rgb("kd", [0.35, 0.2, 0.08]);
    p.extend(rgb("f01", [0.9, 0.6, 0.3]));
    p.extend(rgb("tint1", [0.8, 0.9, 1.0]));
    p.extend(rgb("ks2", [0.2, 0.12, 0.05]));
    p.extend([
        ("alpha1".into(), 0.09),
        ("alpha2".into(), 0.25),
        ("coat_ior".into(), 1.5),
        ("coat_alpha".into(), 0.04),
    ]);
    p
}

#[test]
fn blender_script_sets_each_nodes_values() {
    let p = f82_coat_params();
    let m = model("lobes-f82-coat-cycles", 2, &named(&p));
    let py = export(m.as_ref(), Target::Blender).unwrap();
    for want in [
        r#""ShaderNodeBsdfDiffuse",
        {},
        {"Color": (0.35, 0.2, 0.08, 1.0), "Roughness": 0.0},"#,
        // Cycles' Roughness is sqrt(alpha): 0.3 for 0.09, 0.5 for 0.25, 0.2 for 0.04.
        r#""ShaderNodeBsdfMetallic",
        {"distribution": "GGX", "fresnel_type": "F82"},
        {"Base Color": (0.9, 0.6, 0.3, 1.0), "Edge Tint": (0.8, 0.9, 1.0, 1.0), "Roughness": 0.3},"#,
        r#""ShaderNodeBsdfAnisotropic",
        {"distribution": "GGX"},
        {"Color": (0.2, 0.12, 0.05, 1.0), "Roughness": 0.5, "Anisotropy": 0.0},"#,
        r#""ShaderNodeBsdfMetallic",
        {"distribution": "GGX", "fresnel_type": "PHYSICAL_CONDUCTOR"},
        {"IOR": (1.5, 1.5, 1.5), "Extinction": (0.0, 0.0, 0.0), "Roughness": 0.2},"#,
        "ShaderNodeAddShader",
    ] {
        assert!(py.contains(want), "missing {want} in\n{py}");
    }
    assert!(!py.contains("MULTI_GGX"));
}

/// A thin film goes to Cycles as a Metallic BSDF of the base's index and
/// zero extinction carrying the film, scaled by `w` through a Mix Shader;
/// the rest of the renderers have no film and convert; a one-channel film
/// (its luminance) has no Cycles node.
#[test]
fn blender_script_carries_the_film_and_its_weight() {
    let mut p = rgb("kd", [0.02, 0.03, 0.2]);
    p.extend([
        ("w".into(), 0.6),
        ("alpha".into(), 0.09),
        ("film_d".into(), 210.0),
        ("film_ior".into(), 1.7),
        ("base_ior".into(), 1.4),
        ("coat_ior".into(), 1.5),
        ("coat_alpha".into(), 0.04),
    ]);
    let m = model("film-coat-cycles", 1, &named(&p));
    let py = export(m.as_ref(), Target::Blender).unwrap();
    for want in [
        r#""ShaderNodeBsdfMetallic",
        {"distribution": "GGX", "fresnel_type": "PHYSICAL_CONDUCTOR"},
        {"IOR": (1.4, 1.4, 1.4), "Extinction": (0.0, 0.0, 0.0), "Roughness": 0.3, "Thin Film Thickness": 210.0, "Thin Film IOR": 1.7},
        0.6,"#,
        // The coat: unweighted, no film.
        r#"{"IOR": (1.5, 1.5, 1.5), "Extinction": (0.0, 0.0, 0.0), "Roughness": 0.2},
        None,"#,
        "ShaderNodeMixShader",
    ] {
        assert!(py.contains(want), "missing {want} in\n{py}");
    }
    assert!(matches!(
        export(m.as_ref(), Target::Mitsuba),
        Err(ExportError::NoEquivalent { .. })
    ));
    let grey = brdf_models::build("film-cycles", &brdf_models::ModelConfig::default()).unwrap();
    match export(grey.as_ref(), Target::Blender) {
        Err(ExportError::NoEquivalent { reason, .. }) => {
            assert!(reason.contains("fit RGB data"), "{reason}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
}

/// A MaterialX node read back: its kind, name, and inputs as (name, value
/// or the node it links to).
type MxNode = (String, String, Vec<(String, String)>);

/// The MaterialX graph: one pbrlib node per term with the model's values,
/// summed by `add` nodes into a `surface`, read back with an XML parser.
#[test]
fn materialx_graph_has_one_node_per_term_with_its_values() {
    let p = f82_coat_params();
    let m = model("lobes-f82-coat-materialx", 2, &named(&p));
    let doc = export(m.as_ref(), Target::MaterialX).unwrap();
    let mut nodes: Vec<MxNode> = Vec::new();
    let mut r = quick_xml::Reader::from_str(&doc);
    loop {
        let ev = r.read_event().unwrap();
        let (e, _) = match &ev {
            Event::Start(e) => (e.clone(), false),
            Event::Empty(e) => (e.clone(), true),
            Event::Eof => break,
            _ => continue,
        };
        let attr = |k: &str| {
            e.attributes()
                .flatten()
                .find(|a| a.key.as_ref() == k.as_bytes())
                .map(|a| a.unescape_value().unwrap().into_owned())
                .unwrap_or_default()
        };
        let tag = String::from_utf8_lossy(e.name().as_ref()).into_owned();
        if tag == "input" {
            let v = attr("value") + &attr("nodename");
            nodes.last_mut().unwrap().2.push((attr("name"), v));
        } else if tag != "materialx" {
            nodes.push((tag, attr("name"), Vec::new()));
        }
    }
    let inputs = |kind: &str, k: usize| -> Vec<(String, String)> {
        nodes
            .iter()
            .filter(|n| n.0 == kind)
            .nth(k)
            .unwrap()
            .2
            .clone()
    };
    let pairs = |v: &[(&str, &str)]| -> Vec<(String, String)> {
        v.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    };
    assert_eq!(
        inputs("oren_nayar_diffuse_bsdf", 0),
        pairs(&[("color", "0.35, 0.2, 0.08"), ("roughness", "0")])
    );
    assert_eq!(
        inputs("generalized_schlick_bsdf", 0),
        pairs(&[
            ("color0", "0.9, 0.6, 0.3"),
            ("color82", "0.8, 0.9, 1"),
            ("color90", "1, 1, 1"),
            ("exponent", "5"),
            ("roughness", "0.09, 0.09"),
        ])
    );
    // A plain lobe: F is its colour at every angle.
    assert_eq!(
        inputs("generalized_schlick_bsdf", 1),
        pairs(&[
            ("color0", "0.2, 0.12, 0.05"),
            ("color82", "1, 1, 1"),
            ("color90", "0.2, 0.12, 0.05"),
            ("roughness", "0.25, 0.25"),
        ])
    );
    assert_eq!(
        inputs("dielectric_bsdf", 0),
        pairs(&[
            ("ior", "1.5"),
            ("roughness", "0.04, 0.04"),
            ("scatter_mode", "R")
        ])
    );
    // Four terms, three additions, one surface, one material.
    assert_eq!(nodes.iter().filter(|n| n.0 == "add").count(), 3);
    let surface = nodes.iter().find(|n| n.0 == "surface").unwrap();
    let last_add = nodes.iter().rfind(|n| n.0 == "add").unwrap();
    assert_eq!(surface.2, vec![("bsdf".to_string(), last_add.1.clone())]);
    assert!(nodes.iter().any(|n| n.0 == "surfacematerial"));
    // The Cycles form lacks MaterialX's compensation: refused, naming this one.
    let cycles = model("lobes-f82-coat-cycles", 2, &named(&p));
    match export(cycles.as_ref(), Target::MaterialX) {
        Err(ExportError::NoEquivalent { reason, .. }) => {
            assert!(reason.contains("`lobes-f82-coat-materialx`"), "{reason}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
}

/// A coloured-lobe fit converts to another renderer as its twin there (the
/// same terms with that renderer's masking and compensation), keeping its
/// lobes: the Cycles fixture goes to MaterialX as
/// `lobes-conductor-coat-materialx` at HDR-FLIP 0.019 sky / 0.015 studio
/// (through `gltf`, the default for models MaterialX lacks, 0.133:
/// refused as another material).
#[test]
fn a_coloured_lobe_fit_converts_to_its_twin() {
    let m = load("conductor_coat_cycles.json");
    let c = convert(m.as_ref(), Target::MaterialX, &ConvertOptions::default()).unwrap();
    assert_eq!(c.model.name(), "lobes-conductor-coat-materialx");
    assert_eq!(c.model.n_params(), m.n_params(), "the same lobes");
    let flip = c.image.max_flip();
    eprintln!("twin conversion: HDR-FLIP {flip}");
    assert!(flip <= 0.03, "{flip}");
}

/// USD takes MaterialX's graph: the `-materialx` configurations are exact
/// there, the others convert to their MaterialX twin.
#[test]
fn usd_writes_the_materialx_configurations_exactly_and_converts_the_others_to_them() {
    use brdf_export::table::{Support, support};
    for name in [
        "lobes-materialx",
        "lobes-conductor-coat-materialx",
        "film-materialx",
    ] {
        assert_eq!(support(name, Target::Usd), Support::Exact, "{name}");
    }
    assert_eq!(
        support("lobes-cycles", Target::Usd),
        Support::Converted("lobes-materialx".into())
    );
    let m = load("conductor_coat_cycles.json");
    assert_eq!(
        brdf_export::convert::via_for(m.as_ref(), Target::Usd),
        "lobes-conductor-coat-materialx"
    );
}

#[test]
fn each_renderer_refuses_the_other_masking_naming_the_variant_to_fit() {
    let m = model("lobes-cycles", 2, &named(&plain_params()));
    match export(m.as_ref(), Target::Mitsuba) {
        Err(ExportError::NoEquivalent { reason, .. }) => {
            assert!(reason.contains("`lobes-mitsuba`"), "{reason}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    let m = model(
        "lobes-conductor-coat-mitsuba",
        2,
        &named(&conductor_coat_params()),
    );
    match export(m.as_ref(), Target::Blender) {
        Err(ExportError::NoEquivalent { reason, .. }) => {
            assert!(reason.contains("`lobes-conductor-coat-cycles`"), "{reason}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    let m = model("lobes-f82-cycles", 1, &[]);
    assert!(matches!(
        export(m.as_ref(), Target::Mitsuba),
        Err(ExportError::NoEquivalent { .. })
    ));
}

/// The fixtures `tests/reference/lobes/M.xml` (`-mitsuba` models) and
/// `M.py` (`-cycles` models) and `M.mtlx` (`-materialx` models) are the exports of the models `M.json` as
/// written now (`LOBES_WRITE=1` rewrites them).
#[test]
fn fixtures_are_the_current_exports() {
    let mut names: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| is_model(n))
        .collect();
    names.sort();
    assert!(!names.is_empty());
    for n in names {
        let m = load(&n);
        // Each configuration goes to the renderer whose GGX it has.
        let (target, ext) = if m.name().ends_with("-mitsuba") {
            (Target::Mitsuba, ".xml")
        } else if m.name().ends_with("-materialx") {
            (Target::MaterialX, ".mtlx")
        } else {
            (Target::Blender, ".py")
        };
        let mut files = vec![(n.replace(".json", ext), target)];
        // USD takes MaterialX's graph.
        if target == Target::MaterialX {
            files.push((n.replace(".json", ".usda"), Target::Usd));
        }
        for (file, target) in files {
            let text = export(m.as_ref(), target).unwrap();
            if std::env::var_os("LOBES_WRITE").is_some() {
                std::fs::write(dir().join(&file), &text).unwrap();
            }
            assert_eq!(
                read(&file),
                text,
                "{file}: rerun with LOBES_WRITE=1, then lobes_check.sh"
            );
        }
    }
}

/// USD (usd-core) and MaterialX (its Python package and standard library)
/// read each `-materialx` fixture's USD layer and its MaterialX document
/// (`usd_materialx_check.py`, run by `lobes_check.sh`): the layer is a
/// material whose `mtlx` surface is the document's graph, node for node
/// (each prim's `info:id` the node definition MaterialX resolves), input
/// for input (USD's type of the definition's type, the same value or
/// link). The answers are for the fixtures as written now.
#[test]
fn usd_and_materialx_read_each_usd_layer_as_the_materialx_document() {
    let answers: serde_json::Value =
        serde_json::from_str(&read("usd_check.json")).expect("usd_check.json");
    let answers = answers.as_array().expect("a list");
    let layers: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".usda"))
        .collect();
    assert!(!layers.is_empty());
    assert_eq!(answers.len(), layers.len(), "rerun lobes_check.sh");
    for a in answers {
        let file = a["file"].as_str().expect("file");
        let name = file.trim_start_matches("lobes/");
        assert_eq!(
            a["text"].as_str(),
            Some(read(name).as_str()),
            "{file}: the answer is for another text; rerun lobes_check.sh"
        );
        assert_eq!(a["valid"], true, "{file}: {}", a["problems"]);
        let defs: Vec<&str> = a["node_definitions"]
            .as_array()
            .expect("node definitions")
            .iter()
            .filter_map(|d| d.as_str())
            .collect();
        // The diffuse term, a lobe, the sums and the surface at least.
        assert!(defs.contains(&"ND_oren_nayar_diffuse_bsdf"), "{defs:?}");
        assert!(
            defs.contains(&"ND_add_bsdf") && defs.contains(&"ND_surface"),
            "{defs:?}"
        );
    }
}

fn is_model(n: &str) -> bool {
    n.ends_with(".json")
        && !matches!(
            n,
            "render_check.json" | "mitsuba_values.json" | "usd_check.json"
        )
}

fn ours(m: &dyn Parametric, wi: &[f64; 3], wo: &[f64; 3]) -> [f64; 3] {
    let (l, v) = (nalgebra::Vector3::from(*wo), nalgebra::Vector3::from(*wi));
    let mut f = vec![0.0; m.channels()];
    m.eval(&l, &v, &mut f);
    [f[0], f[1], f[2]]
}

#[derive(serde::Deserialize)]
struct Values {
    cases: Vec<Case>,
}

#[derive(serde::Deserialize)]
struct Case {
    file: String,
    xml: String,
    pairs: Vec<([f64; 3], [f64; 3])>,
    values: Vec<[f64; 3]>,
    peak: [f64; 3],
}

#[test]
fn mitsuba_evaluates_each_fixture_as_the_model() {
    let v: Values = serde_json::from_str(&read("mitsuba_values.json")).unwrap();
    assert!(!v.cases.is_empty());
    for c in &v.cases {
        let file = c.file.trim_start_matches("lobes/");
        assert_eq!(c.xml, read(file), "{file} changed: rerun lobes_check.sh");
        let m = load(&file.replace(".xml", ".json"));
        assert_eq!(c.pairs.len(), 300);
        let mut worst = 0.0f64;
        for ((wi, wo), mv) in c
            .pairs
            .iter()
            .zip(&c.values)
            .chain([(&([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), &c.peak)])
        {
            let f = ours(m.as_ref(), wi, wo);
            for k in 0..3 {
                worst = worst.max((f[k] - mv[k]).abs() / f[k].abs().max(1e-3));
            }
        }
        eprintln!("{file}: worst relative deviation from Mitsuba {worst:.3e}");
        assert!(worst <= 1e-4, "{file}: {worst}");
    }
}

#[test]
fn the_renderers_render_each_fixture_as_brdf_render_does() {
    let a: serde_json::Value = serde_json::from_str(&read("render_check.json")).unwrap();
    let checks = a["checks"].as_array().unwrap();
    assert!(!checks.is_empty());
    for c in checks {
        let file = c["file"].as_str().unwrap().trim_start_matches("lobes/");
        assert_eq!(
            c["text"].as_str().unwrap(),
            read(file),
            "{file}: rerun lobes_check.sh"
        );
        let renderer = if file.ends_with(".xml") {
            "mitsuba"
        } else if file.ends_with(".mtlx") {
            "materialx"
        } else {
            "cycles"
        };
        assert_eq!(c["renderer"], renderer, "{file}");
        let m = load(
            &file
                .replace(".xml", ".json")
                .replace(".py", ".json")
                .replace(".mtlx", ".json"),
        );
        let lights = c["lights"].as_object().unwrap();
        assert!(lights.contains_key("studio"), "{file}");
        for (light, r) in lights {
            let flip = r["flip_held"].as_f64().unwrap();
            let floor = r["flip_reseeded"].as_f64().unwrap();
            eprintln!("{file} {light}: HDR-FLIP {flip} (noise floor {floor})");
            let bound = match renderer {
                "mitsuba" => MITSUBA_FLIP,
                "materialx" => MATERIALX_FLIP,
                _ => CYCLES_FLIP,
            };
            // The bound holds under the studio set. Under the sky the
            // record is kept but not bounded: at the check's 1024 samples
            // the sun's highlight on the narrow lobes leaves Mitsuba's
            // noise near the bound (`lobes.xml`: HDR-FLIP 0.020, its
            // reseeded floor 0.015; 0.017 at 4096 samples), and
            // brdf-render's sky, a tabulation of Mitsuba's sunsky, differs
            // on its own (0.017 on the paper_white `ggx` export, floor
            // 0.011). Mitsuba's evaluation equals the model to 1e-6
            // (`mitsuba_evaluates_each_fixture_as_the_model`).
            if light == "studio" {
                assert!(flip <= bound, "{file} {light}: HDR-FLIP {flip}");
            }
            // The picture compared with is brdf-render's of this model now.
            let set = LightSet::parse(light).unwrap();
            let img = ShadingPoints::judge_with_background(&set, 128).render(m.as_ref());
            let n = (img.width * img.height) as f64;
            for (k, want) in r["brdf_render_mean"].as_array().unwrap().iter().enumerate() {
                let want = want.as_f64().unwrap();
                let mean: f64 = img.data.chunks(3).map(|p| p[k]).sum::<f64>() / n;
                assert!(
                    (mean - want).abs() <= 1e-5 * want.abs().max(1e-3),
                    "{file} {light}: brdf-render mean {mean} vs {want}: rerun lobes_check.sh"
                );
            }
        }
    }
}
