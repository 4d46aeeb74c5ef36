//! Mitsuba 3 XML of the coloured-lobe models with separable masking (the
//! `lobes*-mitsuba` configurations of `brdf_models::coloured_lobes`),
//! exact: every term is a Mitsuba BSDF with the same formula.
//!
//! - the Lambert term `kd / pi` is a `diffuse`;
//! - a lobe of Fresnel law none, `ks S(alpha)`, is a `roughconductor`
//!   (`distribution = ggx`, its `alpha`, `material = none`, whose Fresnel
//!   is exactly 1) with `specular_reflectance` the colour;
//! - a conductor lobe is a `roughconductor` with per-channel `eta` and `k`
//!   (Mitsuba's exact unpolarised conductor Fresnel, the model's);
//! - the coat is a `roughconductor` with `eta = coat_ior`, `k = 0`: the
//!   conductor Fresnel at zero extinction is the dielectric's.
//!
//! Mitsuba 3's `roughconductor` uses GGX with the separable Smith masking,
//! the `-mitsuba` configurations' `G`.
//!
//! Mitsuba has no sum of BSDFs, only `blendbsdf`, `(1 - w) f0 + w f1` with
//! `w` clamped to `[0, 1]`. The sum is a nest of them in which term `i`
//! gets the effective weight `w_i = m_i / M` (`m_i` its largest amplitude
//! over the channels: the colour's largest value, 1 for a Fresnel-coloured
//! lobe; `M` the sum of the `m_i`), the weights adding to 1, and its
//! colour divided by its weight, `c_i M / m_i`: `sum_i w_i (c_i / w_i) =
//! sum_i c_i`, the model's sum, at every amplitude. Those colours are at
//! most `M`; where `M > 1` (always with a coat or a conductor lobe beside
//! a diffuse) they are written as `srgb` textures with `unbounded = true`,
//! which Mitsuba accepts as a reflectance above 1 (a plain `<rgb>`
//! reflectance is refused there), and the file says so in a comment.
//!
//! The height-correlated (`-cycles`) configurations have no Mitsuba
//! equivalent (an error naming the `-mitsuba` configuration to fit, and a
//! conversion by fitting through [`crate::export_or_convert`]); nor has
//! the F82 tint, which Mitsuba's BSDFs do not implement.

use crate::fitted::Fitted;
use crate::lobes_fit::{LobeColour, LobesFit};
use crate::mitsuba_nodes::{float, rgb};
use crate::xml::Node;
use crate::{ExportError, Target};

const T: Target = Target::Mitsuba;

/// One term of the sum, before nesting.
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    /// Effective weight in the nest (the weights add to 1).
    pub weight: f64,
    /// The reflectance written (`diffuse`'s `reflectance`,
    /// `roughconductor`'s `specular_reflectance`): the term's colour
    /// divided by `weight`.
    pub reflectance: [f64; 3],
    /// The term's own colour (the model's amplitude; 1 per channel for a
    /// Fresnel-coloured lobe).
    pub colour: [f64; 3],
    /// What the term is: `diffuse` or `roughconductor`, with its Fresnel.
    pub kind: Kind,
}

/// The BSDF of a term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// `diffuse`.
    Diffuse,
    /// `roughconductor` of width `alpha` with Fresnel exactly 1.
    Mirror {
        /// GGX width
        alpha: f64,
    },
    /// `roughconductor` of width `alpha`, index `eta + i k` per channel.
    Conductor {
        /// GGX width
        alpha: f64,
        /// real index
        eta: [f64; 3],
        /// extinction
        k: [f64; 3],
    },
}

fn max3(c: &[f64; 3]) -> f64 {
    c.iter().fold(0.0, |a: f64, &b| a.max(b))
}

/// The terms of `lobes` with their nest weights (see the module
/// documentation); an error for a configuration Mitsuba lacks.
pub fn terms(fit: &Fitted, lobes: &LobesFit) -> Result<Vec<Term>, ExportError> {
    if !lobes.separable() {
        let twin = lobes
            .variant
            .name
            .replace("-cycles", "-mitsuba")
            .replace("-materialx", "-mitsuba");
        let reason = if brdf_models::coloured_lobes::variant_named(&twin).is_some() {
            format!(
                "Mitsuba 3's GGX uses the separable Smith G, this configuration the height-correlated one; fit `{twin}` for an exact Mitsuba export"
            )
        } else {
            "Mitsuba 3's GGX uses the separable Smith G and no Mitsuba BSDF has the F82-tint Fresnel; fit `lobes-conductor-mitsuba` or `lobes-mitsuba` for an exact Mitsuba export".to_string()
        };
        return Err(fit.no_equivalent(T, reason));
    }
    let mut parts: Vec<([f64; 3], Kind)> = Vec::new();
    if max3(&lobes.kd) > 0.0 {
        parts.push((lobes.kd, Kind::Diffuse));
    }
    for lobe in &lobes.lobes {
        match lobe.colour {
            LobeColour::Plain(ks) => {
                if max3(&ks) > 0.0 {
                    parts.push((ks, Kind::Mirror { alpha: lobe.alpha }));
                }
            }
            LobeColour::Conductor { eta, kappa } => parts.push((
                [1.0; 3],
                Kind::Conductor {
                    alpha: lobe.alpha,
                    eta,
                    k: kappa,
                },
            )),
            LobeColour::F82 { .. } => {
                return Err(fit.no_equivalent(
                    T,
                    "no Mitsuba 3 BSDF has the F82-tint Fresnel; fit `lobes-conductor-mitsuba`",
                ));
            }
        }
    }
    if let Some(c) = lobes.coat {
        parts.push((
            [1.0; 3],
            Kind::Conductor {
                alpha: c.alpha,
                eta: [c.ior; 3],
                k: [0.0; 3],
            },
        ));
    }
    let total: f64 = parts.iter().map(|(c, _)| max3(c)).sum();
    Ok(parts
        .into_iter()
        .map(|(colour, kind)| {
            let m = max3(&colour);
            let weight = m / total;
            Term {
                weight,
                reflectance: colour.map(|x| x * total / m),
                colour,
                kind,
            }
        })
        .collect())
}

/// A reflectance: `<rgb>` within `[0, 1]`, else an unbounded `srgb`
/// texture.
fn reflectance(name: &str, c: &[f64; 3]) -> Node {
    if c.iter().all(|&x| (0.0..=1.0).contains(&x)) {
        return rgb(name, c);
    }
    Node::new("texture")
        .attr("type", "srgb")
        .attr("name", name)
        .child(rgb("color", c))
        .child(
            Node::new("boolean")
                .attr("name", "unbounded")
                .attr("value", "true"),
        )
}

fn ggx(alpha: f64) -> Node {
    Node::new("bsdf")
        .attr("type", "roughconductor")
        .child(
            Node::new("string")
                .attr("name", "distribution")
                .attr("value", "ggx"),
        )
        .child(float("alpha", alpha))
}

fn term_node(t: &Term) -> Node {
    match t.kind {
        Kind::Diffuse => Node::new("bsdf")
            .attr("type", "diffuse")
            .child(reflectance("reflectance", &t.reflectance)),
        Kind::Mirror { alpha } => ggx(alpha)
            .child(
                Node::new("string")
                    .attr("name", "material")
                    .attr("value", "none"),
            )
            .child(reflectance("specular_reflectance", &t.reflectance)),
        Kind::Conductor { alpha, eta, k } => ggx(alpha)
            .child(rgb("eta", &eta))
            .child(rgb("k", &k))
            .child(reflectance("specular_reflectance", &t.reflectance)),
    }
}

/// The nest of `blendbsdf`s giving each term its effective weight:
/// `blendbsdf(w) = (1 - w) first + w rest`, `w = 1 - w_first`, the rest's
/// weights renormalised.
fn nest(terms: &[Term]) -> Node {
    match terms {
        [] => Node::new("bsdf")
            .attr("type", "diffuse")
            .child(rgb("reflectance", &[0.0; 3])),
        [only] => term_node(only),
        [first, rest @ ..] => {
            let t = 1.0 - first.weight;
            let rest: Vec<Term> = rest
                .iter()
                .map(|r| Term {
                    weight: r.weight / t,
                    ..r.clone()
                })
                .collect();
            Node::new("bsdf")
                .attr("type", "blendbsdf")
                .child(float("weight", t))
                .child(term_node(first))
                .child(nest(&rest))
        }
    }
}

/// The Mitsuba BSDF of `lobes` and the comment line it needs (the
/// unbounded reflectances), if any.
pub(crate) fn bsdf(fit: &Fitted, lobes: &LobesFit) -> Result<(Node, Option<String>), ExportError> {
    let terms = terms(fit, lobes)?;
    let unbounded = terms.iter().any(|t| t.reflectance.iter().any(|&x| x > 1.0));
    let note = unbounded.then(|| {
        let m = terms
            .iter()
            .map(|t| max3(&t.reflectance))
            .fold(0.0, f64::max);
        format!(
            "Exact sum of the model's terms as nested blendbsdfs: each term's reflectance is its colour over its blend weight; their amplitudes add to {m}, so reflectances above 1 are unbounded srgb textures"
        )
    });
    Ok((nest(&terms), note))
}
