//! MaterialX documents of the coloured-lobe and thin-film models as
//! MaterialX evaluates them (the `lobes*-materialx` configurations of
//! `brdf_models::coloured_lobes` and `film*-materialx` of
//! `brdf_models::thin_film`): a graph of pbrlib BSDF nodes summed by `add`
//! nodes into a `surface` shader, exact because each node's formula is the
//! model's term, energy compensation included.
//!
//! - the Lambert term is an `oren_nayar_diffuse_bsdf` of roughness 0
//!   (Lambert) with the diffuse colour;
//! - a lobe of Fresnel law none is a `generalized_schlick_bsdf` with
//!   `color0 = color90` = the lobe's colour and `color82` white (its F82
//!   correction vanishes: `F` is the colour at every angle);
//! - an F82-tint lobe is a `generalized_schlick_bsdf` with `color0 = f0`,
//!   `color82 = tint`, `color90` white, exponent 5 (MaterialX's law is the
//!   model's: Hoffman's, referenced at `cos = 1/7`);
//! - a conductor lobe is a `conductor_bsdf` with `ior = eta`, `extinction
//!   = kappa`;
//! - the coat is a `dielectric_bsdf` in reflection (`scatter_mode` R), its
//!   tint white;
//! - a thin film's lobe is a `dielectric_bsdf` in reflection of IOR
//!   `base_ior`, weight `w`, `thinfilm_thickness` `film_d` (nm) and
//!   `thinfilm_ior` `film_ior`: MaterialX then computes the film's colour
//!   by its own series, which the `film*-materialx` models are.
//!
//! Every node gets `roughness = (alpha, alpha)`: MaterialX's BSDF nodes
//! take the GGX width itself (its surface shaders square a perceptual
//! roughness before passing it on). Each of these nodes multiplies its lobe
//! by the energy compensation the `-materialx` configurations carry, so the
//! Cycles and Mitsuba configurations, which lack it, are refused with the
//! configuration to fit instead (`brdf export` then converts).

use crate::fitted::{Fitted, rgb_string};
use crate::lobes_fit::{LobeColour, LobesFit};
use crate::xml::Node;
use crate::{ExportError, Target, WriteOptions};

fn input(name: &str, kind: &str, value: String) -> Node {
    Node::new("input")
        .attr("name", name)
        .attr("type", kind)
        .attr("value", value)
}

fn colour(name: &str, c: &[f64; 3]) -> Node {
    input(name, "color3", rgb_string(c))
}

fn roughness(alpha: f64) -> Node {
    input("roughness", "vector2", format!("{alpha}, {alpha}"))
}

fn bsdf(kind: &str, name: String, inputs: Vec<Node>) -> Node {
    inputs.into_iter().fold(
        Node::new(kind).attr("name", name).attr("type", "BSDF"),
        Node::child,
    )
}

fn link(input: &str, kind: &str, node: &str) -> Node {
    Node::new("input")
        .attr("name", input)
        .attr("type", kind)
        .attr("nodename", node)
}

/// The BSDF nodes of `lobes`, in the model's order, named after `base`.
fn terms(lobes: &LobesFit, base: &str) -> Vec<Node> {
    let mut v = vec![bsdf(
        "oren_nayar_diffuse_bsdf",
        format!("{base}_diffuse"),
        vec![
            colour("color", &lobes.kd),
            input("roughness", "float", "0".into()),
        ],
    )];
    let white = [1.0; 3];
    for (i, lobe) in lobes.lobes.iter().enumerate() {
        let name = format!("{base}_lobe{}", i + 1);
        let r = roughness(lobe.alpha);
        v.push(match lobe.colour {
            LobeColour::Plain(ks) => bsdf(
                "generalized_schlick_bsdf",
                name,
                vec![
                    colour("color0", &ks),
                    colour("color82", &white),
                    colour("color90", &ks),
                    r,
                ],
            ),
            LobeColour::F82 { f0, tint } => bsdf(
                "generalized_schlick_bsdf",
                name,
                vec![
                    colour("color0", &f0),
                    colour("color82", &tint),
                    colour("color90", &white),
                    input("exponent", "float", "5".into()),
                    r,
                ],
            ),
            LobeColour::Conductor { eta, kappa } => bsdf(
                "conductor_bsdf",
                name,
                vec![colour("ior", &eta), colour("extinction", &kappa), r],
            ),
        });
    }
    if let Some(c) = lobes.coat {
        v.push(coat(base, c.ior, c.alpha));
    }
    v
}

fn coat(base: &str, ior: f64, alpha: f64) -> Node {
    bsdf(
        "dielectric_bsdf",
        format!("{base}_coat"),
        vec![
            input("ior", "float", ior.to_string()),
            roughness(alpha),
            input("scatter_mode", "string", "R".into()),
        ],
    )
}

/// The MaterialX document of a thin-film fit (`film*-materialx`) for
/// `target` (MaterialX, or USD through MaterialX); an error for Cycles'
/// film, naming the model to fit, and for one channel (the film's
/// luminance, where MaterialX's film is coloured).
pub(crate) fn film_graph(
    fit: &Fitted,
    target: Target,
    opts: &WriteOptions,
) -> Result<Node, ExportError> {
    let Some(stem) = fit.name.strip_suffix("-cycles") else {
        return film_nodes(fit, target, &opts.name).map(|n| document(n, &opts.name));
    };
    Err(fit.no_equivalent(
        target,
        format!(
            "this is Cycles' film (spectral Airy, no energy compensation), not MaterialX's; fit `{stem}-materialx` for an exact MaterialX export"
        ),
    ))
}

fn film_nodes(fit: &Fitted, target: Target, base: &str) -> Result<Vec<Node>, ExportError> {
    if fit.channels != 3 {
        return Err(fit.no_equivalent(
            target,
            "a one-channel thin film is the film's luminance, MaterialX's film is coloured; fit RGB data",
        ));
    }
    let mut v = vec![bsdf(
        "oren_nayar_diffuse_bsdf",
        format!("{base}_diffuse"),
        vec![
            colour("color", &fit.colour("kd")?),
            input("roughness", "float", "0".into()),
        ],
    )];
    v.push(bsdf(
        "dielectric_bsdf",
        format!("{base}_film"),
        vec![
            input("weight", "float", fit.get("w")?.to_string()),
            input("ior", "float", fit.get("base_ior")?.to_string()),
            roughness(fit.get("alpha")?),
            input(
                "thinfilm_thickness",
                "float",
                fit.get("film_d")?.to_string(),
            ),
            input("thinfilm_ior", "float", fit.get("film_ior")?.to_string()),
            input("scatter_mode", "string", "R".into()),
        ],
    ));
    if let (Ok(ior), Ok(alpha)) = (fit.get("coat_ior"), fit.get("coat_alpha")) {
        v.push(coat(base, ior, alpha));
    }
    Ok(v)
}

/// The MaterialX document of a coloured-lobe fit for `target` (MaterialX,
/// or USD through MaterialX); an error for a configuration without
/// MaterialX's energy compensation, naming the one to fit.
pub(crate) fn graph(
    fit: &Fitted,
    lobes: &LobesFit,
    target: Target,
    opts: &WriteOptions,
) -> Result<Node, ExportError> {
    if !lobes.variant.compensated {
        let twin = lobes
            .variant
            .name
            .replace("-mitsuba", "-materialx")
            .replace("-cycles", "-materialx");
        return Err(fit.no_equivalent(
            target,
            format!(
                "MaterialX's GGX nodes add an energy compensation this configuration lacks; fit `{twin}` for an exact {target} export"
            ),
        ));
    }
    Ok(document(terms(lobes, &opts.name), &opts.name))
}

/// The document summing the BSDF `nodes` (a left fold of `add` nodes:
/// `((n0 + n1) + n2) + ...`) into material `base`'s `surface`.
fn document(nodes: Vec<Node>, base: &str) -> Node {
    let names: Vec<String> = nodes.iter().map(|n| n.name().to_string()).collect();
    let mut doc = Node::new("materialx").attr("version", "1.39");
    for n in nodes {
        doc = doc.child(n);
    }
    let mut sum = names[0].clone();
    for (i, term) in names.iter().enumerate().skip(1) {
        let add = format!("{base}_sum{i}");
        doc = doc.child(
            Node::new("add")
                .attr("name", &add)
                .attr("type", "BSDF")
                .child(link("in1", "BSDF", &sum))
                .child(link("in2", "BSDF", term)),
        );
        sum = add;
    }
    let shader = format!("{base}_shader");
    doc.child(
        Node::new("surface")
            .attr("name", &shader)
            .attr("type", "surfaceshader")
            .child(link("bsdf", "BSDF", &sum)),
    )
    .child(
        Node::new("surfacematerial")
            .attr("name", base)
            .attr("type", "material")
            .child(link("surfaceshader", "surfaceshader", &shader)),
    )
}
