//! Conversion by fitting: where a model has no exact equivalent in a
//! target, fit a model the target does have so that it *looks* like the
//! source, and report how far the converted material is from the source,
//! in BRDF space and in the image.
//!
//! The source is sampled at `pairs` direction pairs (a quasi-random
//! sequence over Rusinkiewicz's half/difference angles with `theta_h`
//! warped towards the specular peak, both directions within `limit_deg` of
//! the normal). The target's model is fitted to those values by
//! [`brdf_fit::appearance::fit_for_appearance`]: BRDF-space candidates
//! (log and cube root; optional lobes only when they pay) ranked by
//! their image error, the winner refined in the image objective
//! (`Objective::Image`, the source rendered through the judge's shading
//! terms: the source is a model, evaluable at any pair). With
//! `appearance: false` the conversion is the plain BRDF-space fit (Ngan's
//! objective). The result is measured on the sampled pairs (Ngan's L2 and
//! that L2 relative to the source's own, `0` = identical) and in the image
//! ([`brdf_render::Judge`] at `judge_size` pixels: HDR-FLIP per
//! light set and the CIEDE2000 difference of the mean sphere colours).
//!
//! ## When a conversion warns, and when it is refused
//!
//! A conversion is written, never silently: [`crate::export_or_convert`]
//! warns when its FLIP under any light set exceeds [`FLIP_WARN`] (0.02) or
//! its largest mean-colour CIEDE2000 exceeds [`DELTA_E_WARN`] (3), the
//! warning stating the image error and the `--for` route that renders the
//! data exactly; it refuses only a conversion beyond [`FLIP_REFUSE`] (0.1)
//! or [`DELTA_E_REFUSE`] (10), unless `force` (and `--exact` refuses every
//! conversion). 0.02 bounds what a conversion may change unnoticed: both
//! renders are brdf-render's, deterministic quadratures without Monte
//! Carlo noise, so 0.02 is a difference of the materials, not of the
//! renders (two Mitsuba renders of one measurement differ by about as
//! much from noise alone, `docs/appearance.md`); 3 is just above the
//! just-noticeable colour difference (2.3). A conversion between the two
//! tiers is a slightly different look, usable (on paper_white, principled
//! to glTF changes the sky render by 0.034: Burley's diffuse has a grazing
//! rise Lambert's lacks); 0.1 or a colour difference of 10 is another
//! material, which a user exports only on purpose.
//!
//! pbrt-v4's `mix` (below) is not a catalogue model: its BRDF-space fit
//! (Ngan's objective) is refined in the image objective and the
//! refinement kept when its image error is lower.
//!
//! | target | model fitted by default | why |
//! | --- | --- | --- |
//! | Mitsuba 3 | `principled` | Mitsuba's own BSDF, written exactly |
//! | pbrt-v4 | `ggx-dielectric` | a `mix` of `diffuse` and `conductor` with `k = 0`, written exactly once `ks` is grey |
//! | glTF 2.0 | `gltf` (`gltf-iridescence` for a thin film) | the metallic-roughness material (with glTF's own film) |
//!
//! A coloured-lobe model goes to its twin in the target's form where the
//! catalogue has one ([`via_for`]): `-mitsuba`, `-cycles` and `-materialx`
//! differ only in masking and compensation.
//! | MaterialX | `gltf` | written as `gltf_pbr` |
//!
//! pbrt-v4's `mix` takes one amount for all channels and a diffuse
//! reflectance of at most 1, so for pbrt (with a `ggx-conductor` or
//! `ggx-dielectric` lobe, isotropic or `-aniso`) the model fitted is the mix
//! itself ([`crate::pbrt_mix`]) and then written as its catalogue model.

use brdf_core::half_diff::HalfDiff;
use brdf_core::{Brdf, DirPairs, Direction, Parametric, SampleSet};
use std::sync::Arc;

use brdf_fit::image_objective::{ImageTarget, image_terms};
use brdf_fit::{
    ChannelMode, FitOptions, FitOutcome, FitReport, FitRequest, Material, Metric, Objective,
    pipeline,
};
use brdf_models::{GgxForm, GgxFresnel, ModelConfig, RendererForm};
use brdf_render::ImageError;
use brdf_render::judge::{FIT_SIZE, Judge, REPORT_SIZE};

use crate::pbrt_mix::PbrtMix;
use crate::{ExportError, Target};

/// How to convert.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvertOptions {
    /// The target's model to fit (`None`: [`via_for`]).
    pub via: Option<String>,
    /// Direction pairs sampled from the source (default 2048).
    pub pairs: usize,
    /// Largest `theta_i`, `theta_o` sampled, in degrees (default 80).
    pub limit_deg: f64,
    /// Multi-starts of the fit (default 12).
    pub starts: usize,
    /// Fit for appearance (candidates ranked by image error, refined in
    /// the image objective; default) or in BRDF space only.
    pub appearance: bool,
    /// Pixels per side of the images the conversion is judged on
    /// (default [`REPORT_SIZE`], the judge's film).
    pub judge_size: usize,
    /// Export even when the conversion exceeds [`FLIP_REFUSE`] or
    /// [`DELTA_E_REFUSE`].
    pub force: bool,
}

/// FLIP under any light set above which a conversion is written with a
/// warning (see the module doc).
pub const FLIP_WARN: f64 = 0.02;
/// Largest mean-colour CIEDE2000 above which a conversion is written with
/// a warning.
pub const DELTA_E_WARN: f64 = 3.0;
/// FLIP under any light set above which a conversion is refused unless
/// forced: another material, not a conversion.
pub const FLIP_REFUSE: f64 = 0.1;
/// Largest mean-colour CIEDE2000 above which a conversion is refused
/// unless forced.
pub const DELTA_E_REFUSE: f64 = 10.0;

/// When a conversion warns and when it is refused, in words for help
/// texts and tables (from the constants, so the texts follow the code).
pub fn limits_text() -> String {
    format!(
        "written with a warning above HDR-FLIP {FLIP_WARN} under any light set or mean-colour CIEDE2000 {DELTA_E_WARN}, refused above HDR-FLIP {FLIP_REFUSE} or CIEDE2000 {DELTA_E_REFUSE}"
    )
}

impl Default for ConvertOptions {
    fn default() -> Self {
        ConvertOptions {
            via: None,
            pairs: 2048,
            limit_deg: 80.0,
            starts: 12,
            appearance: true,
            judge_size: REPORT_SIZE,
            force: false,
        }
    }
}

/// How far a converted material is from its source, on the sampled pairs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConversionError {
    /// Direction pairs compared.
    pub samples: usize,
    /// Largest `theta_i`, `theta_o` of the pairs, in degrees.
    pub limit_deg: f64,
    /// Ngan's L2 between source and converted values (1/sr).
    pub ngan_l2: f64,
    /// `ngan_l2` divided by the source's own Ngan norm (0 = identical).
    pub relative_l2: f64,
}

/// A converted model.
pub struct Conversion {
    /// The source's catalogue name.
    pub source: String,
    /// The target's model at the fitted parameters.
    pub model: Box<dyn Parametric>,
    /// Its structural configuration.
    pub config: ModelConfig,
    /// The direction pairs it was fitted at.
    pub pairs: DirPairs,
    /// How far it is from the source.
    pub error: ConversionError,
    /// How far its renders are from the source's.
    pub image: ImageError,
    /// Fitted for appearance (image objective), or in BRDF space only.
    pub appearance: bool,
}

impl Conversion {
    /// One line for a file header or a report.
    pub fn note(&self) -> String {
        let e = &self.error;
        format!(
            "converted by fitting: `{}` has no exact equivalent here, so `{}` was fitted to its values at {} direction pairs up to {} deg; Ngan L2 {:.4e} 1/sr, relative L2 {:.4e}; {}",
            self.source,
            self.model.name(),
            e.samples,
            e.limit_deg,
            e.ngan_l2,
            e.relative_l2,
            image_note(&self.image)
        )
    }

    /// Whether the conversion may be written: `Err` naming the better
    /// route when it exceeds [`FLIP_REFUSE`] or [`DELTA_E_REFUSE`].
    pub fn check(&self, target: Target) -> Result<(), ExportError> {
        let (flip, delta_e) = (self.image.max_flip(), self.image.max_delta_e());
        if flip <= FLIP_REFUSE && delta_e <= DELTA_E_REFUSE {
            return Ok(());
        }
        Err(ExportError::LooksDifferent {
            model: self.source.clone(),
            target,
            via: self.model.name().to_string(),
            flip,
            delta_e,
            front: crate::FrontEnd::Cli,
        })
    }
}

/// The image errors in one clause: FLIP per light set, CIEDE2000.
pub fn image_note(image: &ImageError) -> String {
    let flips: Vec<String> = image
        .lights
        .iter()
        .map(|l| format!("{} {:.4}", l.light, l.flip))
        .collect();
    format!(
        "image error at {} px: HDR-FLIP {} (mean {:.4}), mean-colour CIEDE2000 at most {:.2}",
        image.size,
        flips.join(", "),
        image.mean_flip(),
        image.max_delta_e()
    )
}

/// The model fitted for `target` when none is named.
pub fn default_via(target: Target) -> &'static str {
    match target {
        Target::Mitsuba => "principled",
        Target::Pbrt => "ggx-dielectric",
        Target::Gltf | Target::MaterialX | Target::Usd | Target::Blender => "gltf",
    }
}

/// The model a conversion of `source` to `target` fits unless told: a
/// coloured-lobe model goes to its twin in the target's form
/// (`lobes-cycles` to MaterialX as `lobes-materialx`: the same terms with
/// the target's masking and compensation, so the conversion changes
/// little), a thin film to glTF as glTF's own film
/// (`KHR_materials_iridescence`); everything else to the target's
/// [`default_via`]. A thin film does not go to its twin: the films'
/// formulas put their fringes at other thicknesses, and the conversion of
/// the iris fixture's Cycles film to MaterialX's renders at HDR-FLIP 0.20
/// (through `gltf` 0.19), so either is refused as another material.
pub fn via_for(source: &dyn Parametric, target: Target) -> &'static str {
    match brdf_models::entry(source.name()).map(|e| e.form) {
        Some(RendererForm::ColouredLobes) => twin(source.name(), target),
        Some(RendererForm::ThinFilm) if target == Target::Gltf => Some("gltf-iridescence"),
        _ => None,
    }
    .unwrap_or(default_via(target))
}

/// The catalogue twin of coloured-lobe model `name` in `target`'s form, if
/// the catalogue has one.
fn twin(name: &str, target: Target) -> Option<&'static str> {
    let suffix = match target {
        Target::Mitsuba => "-mitsuba",
        Target::Blender => "-cycles",
        // USD takes the MaterialX graph.
        Target::MaterialX | Target::Usd => "-materialx",
        _ => return None,
    };
    let stem = ["-mitsuba", "-cycles", "-materialx"]
        .iter()
        .find_map(|s| name.strip_suffix(s))?;
    brdf_models::entry(&format!("{stem}{suffix}")).map(|e| e.name)
}

/// Fit the target's model to `source` (see the module doc).
pub fn convert(
    source: &dyn Parametric,
    target: Target,
    opts: &ConvertOptions,
) -> Result<Conversion, ExportError> {
    // Forgiving names (`--via GGX_Dielectric`), resolved as wherever a
    // model is named.
    let via_name = opts.via.as_deref().unwrap_or(via_for(source, target));
    let via_entry = brdf_fit::resolve(via_name).map_err(|e| ExportError::Conversion {
        model: source.name().to_string(),
        target,
        via: via_name.to_string(),
        reason: e.to_string(),
    })?;
    let via = via_entry.name;
    let fail = |reason: String| ExportError::Conversion {
        model: source.name().to_string(),
        target,
        via: via.to_string(),
        reason,
    };
    if !(opts.limit_deg > 0.0 && opts.limit_deg < 90.0) {
        return Err(fail(format!(
            "limit {} deg: must be in (0, 90)",
            opts.limit_deg
        )));
    }
    if opts.pairs < 16 {
        return Err(fail(format!("{} pairs: need at least 16", opts.pairs)));
    }
    let samples = sample_source(source, opts).map_err(fail)?;
    // pbrt-v4's conductor and dielectric materials: one height-correlated
    // GGX lobe with an exact Fresnel term, mixed with a diffuse one.
    let pbrt_lobe = matches!(
        via_entry.form,
        RendererForm::Ggx(GgxForm {
            fresnel: GgxFresnel::Conductor | GgxFresnel::Dielectric,
            separable: false,
            numbered: false,
            ..
        })
    );
    let (model, config, judged) = if target == Target::Pbrt && pbrt_lobe {
        let mix = fit_mix(source, via, &samples, opts).map_err(fail)?;
        let config = ModelConfig {
            channels: source.channels(),
            ..ModelConfig::default()
        };
        (
            mix.catalogue().map_err(|e| fail(e.to_string()))?,
            config,
            None,
        )
    } else {
        let report = fit_target(source, via, &samples, opts).map_err(fail)?;
        (report.model, report.config, report.image_error)
    };
    let error = measure(source, model.as_ref(), &samples, opts.limit_deg).map_err(fail)?;
    let image = match judged {
        Some(image) if opts.judge_size == REPORT_SIZE => image,
        _ => Judge::new(opts.judge_size.max(8))
            .errors(source as &dyn Brdf, model.as_ref() as &dyn Brdf)
            .map_err(|e| fail(e.to_string()))?,
    };
    Ok(Conversion {
        source: source.name().to_string(),
        model,
        config,
        pairs: samples.pairs().clone(),
        error,
        image,
        appearance: opts.appearance,
    })
}

/// Fit pbrt-v4's mix with lobe `via` to the samples of `source` in BRDF
/// space, then (for appearance) refine it in the image objective, kept
/// when its image error is lower.
fn fit_mix(
    source: &dyn Parametric,
    via: &str,
    samples: &SampleSet,
    opts: &ConvertOptions,
) -> Result<PbrtMix, String> {
    let mut mix = PbrtMix::new(via, source.channels()).map_err(|e| e.to_string())?;
    let mut fit_opts = FitOptions {
        starts: opts.starts,
        ..FitOptions::default()
    };
    pipeline::fit(&mut mix, samples, &fit_opts).map_err(|e| e.to_string())?;
    if !opts.appearance {
        return Ok(mix);
    }
    let judge = Judge::new(FIT_SIZE);
    let flip = |m: &PbrtMix| {
        judge
            .errors(source as &dyn Brdf, m as &dyn Brdf)
            .map(|e| e.mean_flip())
            .map_err(|e| e.to_string())
    };
    let before = flip(&mix)?;
    let start = mix.params().to_vec();
    let target = ImageTarget::new(
        image_terms(FIT_SIZE).map_err(|e| e.to_string())?,
        source,
        mix.channels(),
        start,
    );
    let mut refined = mix.clone();
    fit_opts.objective = Objective::Image;
    fit_opts.image = Some(Arc::new(target));
    // A failed refinement keeps the BRDF-space fit.
    if pipeline::fit(&mut refined, samples, &fit_opts).is_ok() && flip(&refined)? < before {
        return Ok(refined);
    }
    Ok(mix)
}

/// Fit the catalogue model `via` to the samples of `source`: for
/// appearance (see the module doc) or in BRDF space. With the judge's
/// report size, the report holds the fit's image errors against the
/// source (the conversion is judged on them).
fn fit_target(
    source: &dyn Parametric,
    via: &str,
    samples: &SampleSet,
    opts: &ConvertOptions,
) -> Result<FitReport, String> {
    let material = Material::new(
        source.name(),
        samples.clone(),
        Some(source.clone_box() as Box<dyn Brdf>),
    );
    let request = FitRequest {
        metric: if opts.appearance {
            Metric::Appearance
        } else {
            Metric::Objective(Objective::Ngan)
        },
        channels: ChannelMode::Rgb,
        starts: opts.starts,
        // Every pair already lies inside the limit; 90 keeps them all.
        limit_deg: 90.0,
        // A conversion is judged by its render (its BRDF-space L2 is
        // printed beside): no limit on the refinement's L2.
        refine_l2_growth: f64::INFINITY,
        ..FitRequest::new(
            &material,
            brdf_fit::resolve(via).map_err(|e| e.to_string())?,
        )
    };
    let mut request = request;
    // A coloured-lobe twin keeps the source's number of lobes.
    if request.model.has_lobes {
        let lobes = (1..)
            .take_while(|k| {
                source
                    .param_specs()
                    .iter()
                    .any(|s| s.name == format!("alpha{k}"))
            })
            .count();
        request.config.lobes = lobes.max(1);
    }
    request
        .run()
        .and_then(FitOutcome::into_report)
        .map_err(|e| e.to_string())
}

/// Element `i` of a 4-D quasi-random (Kronecker) sequence in `[0, 1)^4`
/// (Roberts' R4: the steps are powers of the inverse of the root of
/// `x^5 = x + 1`).
fn quasi_random(i: usize) -> [f64; 4] {
    const G: f64 = 1.167_303_978_261_418_7;
    std::array::from_fn(|k| (0.5 + i as f64 / G.powi(k as i32 + 1)).fract())
}

/// The source's values at `opts.pairs` pairs inside the limit.
pub fn sample_source(source: &dyn Parametric, opts: &ConvertOptions) -> Result<SampleSet, String> {
    let nc = source.channels();
    let names = if nc == 1 {
        vec!["grey".to_string()]
    } else {
        (0..nc)
            .map(|c| ["r", "g", "b"][c % 3].to_string())
            .collect()
    };
    let mut set = SampleSet::new(
        format!("{} (sampled)", source.name()),
        "conversion by fitting",
        names,
    );
    let cos_limit = opts.limit_deg.to_radians().cos();
    let half_pi = std::f64::consts::FRAC_PI_2;
    let mut f = vec![0.0; nc];
    // Half the candidates fall below the horizon or beyond the limit; give
    // up (an error, not a hang) long after that.
    for i in 0..opts.pairs * 64 {
        if set.len() == opts.pairs {
            return Ok(set);
        }
        let u = quasi_random(i);
        let hd = HalfDiff {
            theta_h: half_pi * u[0] * u[0],
            phi_h: 2.0 * std::f64::consts::PI * u[1],
            theta_d: half_pi * u[2],
            phi_d: 2.0 * std::f64::consts::PI * u[3],
        };
        let (l, v) = hd.to_directions();
        if l.z < cos_limit || v.z < cos_limit {
            continue;
        }
        let (Ok(dl), Ok(dv)) = (Direction::try_new(l), Direction::try_new(v)) else {
            continue;
        };
        source.eval(&l, &v, &mut f);
        if let Some(x) = f.iter().find(|x| !x.is_finite()) {
            return Err(format!(
                "the source evaluates to {x} at L = {l:?}, V = {v:?}"
            ));
        }
        set.push(&dl, &dv, &f, 1.0).map_err(|e| e.to_string())?;
    }
    Err(format!(
        "only {} of {} pairs lie within {} deg",
        set.len(),
        opts.pairs,
        opts.limit_deg
    ))
}

/// How far `converted` is from `source` on the pairs [`sample_source`]
/// draws for `opts` (what [`convert()`] reports).
pub fn conversion_error(
    source: &dyn Parametric,
    converted: &dyn Parametric,
    opts: &ConvertOptions,
) -> Result<ConversionError, String> {
    let samples = sample_source(source, opts)?;
    measure(source, converted, &samples, opts.limit_deg)
}

/// Values of `m` at the pairs of `s`, channel-major.
fn values(m: &dyn Parametric, s: &SampleSet) -> Vec<f64> {
    let (n, nc) = (s.len(), m.channels());
    let mut out = vec![0.0; n * nc];
    let mut f = vec![0.0; nc];
    for j in 0..n {
        m.eval(&s.pairs().l(j), &s.pairs().v(j), &mut f);
        for c in 0..nc {
            out[c * n + j] = f[c];
        }
    }
    out
}

/// Ngan's L2 of converted vs source values, absolute and relative.
fn measure(
    source: &dyn Parametric,
    converted: &dyn Parametric,
    s: &SampleSet,
    limit_deg: f64,
) -> Result<ConversionError, String> {
    let src = values(source, s);
    let conv = values(converted, s);
    let cos_i: Vec<f64> = (0..s.len()).map(|j| s.pairs().l(j).z).collect();
    let l2 = |model: &[f64]| {
        brdf_core::metrics::ngan_l2(&src, model, &cos_i, s.weights())
            .map(|m| m.total)
            .map_err(|e| e.to_string())
    };
    let ngan_l2 = l2(&conv)?;
    let norm = l2(&vec![0.0; src.len()])?;
    Ok(ConversionError {
        samples: s.len(),
        limit_deg,
        ngan_l2,
        relative_l2: if norm > 0.0 { ngan_l2 / norm } else { 0.0 },
    })
}
