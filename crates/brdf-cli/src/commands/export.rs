//! `brdf export --from MODEL.json --to mitsuba|pbrt|gltf|materialx|usd|blender OUT`
//! (or `--to mitsuba --tabulate-on DATA.bsdf OUT.bsdf`, any model tabulated):
//! write a saved model as a renderer's material, a thin layer over
//! [`brdf_export`]. Exact where the target has the model's equivalent;
//! otherwise converted by fitting a model the target has (`--via` names
//! it), with the conversion error printed and written into the file;
//! `--exact` refuses conversions; one that renders differently is written
//! with a warning, and one that renders as another material is refused
//! unless `--force`. `--list` prints the table of
//! what each target writes exactly, maps or converts.

use std::path::PathBuf;

use brdf_export::file::ExportJob;
use brdf_export::{ConvertOptions, Exported, Light, Surface, Target, WriteOptions, identifier};

use crate::error::CliError;

/// `--to`: one value per [`Target`] (the two conversions below are
/// exhaustive matches, so a target added to the library fails to compile
/// here until it has its help line).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ToArg {
    /// Mitsuba 3 `<bsdf>` snippet (or a judge scene with --scene)
    Mitsuba,
    /// pbrt-v4 material statements
    Pbrt,
    /// glTF 2.0 asset with a preview sphere (--no-mesh: the material alone)
    Gltf,
    /// MaterialX document (--surface picks the shader)
    #[value(alias = "mtlx")]
    Materialx,
    /// USD layer (.usda): a UsdPreviewSurface, or the MaterialX graph of a coloured-lobe or thin-film fit
    #[value(alias = "usda")]
    Usd,
    /// Blender Python script building a Principled BSDF
    Blender,
}

impl From<ToArg> for Target {
    fn from(t: ToArg) -> Target {
        match t {
            ToArg::Mitsuba => Target::Mitsuba,
            ToArg::Pbrt => Target::Pbrt,
            ToArg::Gltf => Target::Gltf,
            ToArg::Materialx => Target::MaterialX,
            ToArg::Usd => Target::Usd,
            ToArg::Blender => Target::Blender,
        }
    }
}

impl From<Target> for ToArg {
    fn from(t: Target) -> ToArg {
        match t {
            Target::Mitsuba => ToArg::Mitsuba,
            Target::Pbrt => ToArg::Pbrt,
            Target::Gltf => ToArg::Gltf,
            Target::MaterialX => ToArg::Materialx,
            Target::Usd => ToArg::Usd,
            Target::Blender => ToArg::Blender,
        }
    }
}

/// `--light`: the Mitsuba scene's light set ([`Light`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LightArg {
    /// a dim constant surround and a square key light
    Studio,
    /// Mitsuba's sunsky
    Sky,
}

impl From<LightArg> for Light {
    fn from(l: LightArg) -> Light {
        match l {
            LightArg::Studio => Light::Studio,
            LightArg::Sky => Light::Sky,
        }
    }
}

/// `--surface`: the MaterialX surface shader ([`Surface`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SurfaceArg {
    /// Khronos's gltf_pbr (the glTF material itself)
    #[value(name = "gltf_pbr", alias = "gltf-pbr", alias = "gltf")]
    GltfPbr,
    /// Autodesk Standard Surface
    #[value(
        name = "standard_surface",
        alias = "standard-surface",
        alias = "standard"
    )]
    StandardSurface,
    /// OpenPBR Surface (MaterialX 1.39)
    #[value(name = "openpbr", alias = "open_pbr_surface", alias = "open-pbr")]
    Openpbr,
}

impl From<SurfaceArg> for Surface {
    fn from(s: SurfaceArg) -> Surface {
        match s {
            SurfaceArg::GltfPbr => Surface::GltfPbr,
            SurfaceArg::StandardSurface => Surface::StandardSurface,
            SurfaceArg::Openpbr => Surface::OpenPbr,
        }
    }
}

/// The `--force` help, with the limits the code applies.
fn force_help() -> String {
    format!(
        "Export a conversion even when it renders as another material (conversions are {})",
        brdf_export::convert::limits_text()
    )
}

/// Arguments of `brdf export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// A model saved by `brdf fit --save` (`.json`).
    #[arg(long, required_unless_present = "list")]
    pub from: Option<PathBuf>,
    /// Target format.
    #[arg(long, value_enum, required_unless_present = "list")]
    pub to: Option<ToArg>,
    /// Output file.
    #[arg(required_unless_present = "list")]
    pub out: Option<PathBuf>,
    /// Print which model each target writes exactly, maps or converts.
    #[arg(long)]
    pub list: bool,
    /// Mitsuba: write the model itself as a `measured` BSDF, tabulated on
    /// the grid of this RGL measurement (`.bsdf`; OUT is then a `.bsdf`
    /// file). Any model, no conversion: what Mitsuba renders is the model
    /// at the grid's nodes, interpolated between them.
    #[arg(long, value_name = "DATA.bsdf")]
    pub tabulate_on: Option<PathBuf>,
    /// Mitsuba: write a complete judge scene (sphere, camera, a light set)
    /// instead of a `<bsdf>` snippet.
    #[arg(long)]
    pub scene: bool,
    /// Mitsuba scene: the light set.
    #[arg(long, value_enum, default_value = "studio")]
    pub light: LightArg,
    /// MaterialX: the surface shader.
    #[arg(long, value_enum, default_value = "gltf_pbr")]
    pub surface: SurfaceArg,
    /// glTF: write the material alone (a material library), without the
    /// preview sphere that shows it in a viewer.
    #[arg(long)]
    pub no_mesh: bool,
    /// The material's name (default: the data's file name).
    #[arg(long)]
    pub name: Option<String>,
    /// Refuse to convert: fail where the target has no exact equivalent.
    #[arg(long)]
    pub exact: bool,
    /// The target's model to fit when converting (default: principled for
    /// Mitsuba, ggx-dielectric for pbrt, gltf for glTF and MaterialX).
    #[arg(long)]
    pub via: Option<String>,
    /// Direction pairs sampled from the model when converting.
    #[arg(long, default_value_t = 2048)]
    pub pairs: usize,
    /// Largest theta_i, theta_o (degrees) sampled when converting.
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Multi-start count of the conversion fit.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
    #[arg(long, help = force_help())]
    pub force: bool,
    /// Convert by BRDF-space fitting only (faster; no image objective).
    #[arg(long)]
    pub brdf_space: bool,
    /// Also save the converted model (the material written) here.
    #[arg(long)]
    pub save_converted: Option<PathBuf>,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

/// Run `brdf export`.
pub fn run(args: &ExportArgs) -> Result<(), CliError> {
    let (Some(to), Some(out), false) = (&args.to, &args.out, args.list) else {
        return say!("{}", brdf_export::table::markdown());
    };
    let target = Target::from(*to);
    if args.scene && target != Target::Mitsuba {
        return Err(brdf_export::ExportError::UnknownOption {
            option: "--scene",
            value: target.to_string(),
            expected: "--to mitsuba (only Mitsuba scenes are written)",
        }
        .into());
    }
    if let Some(grid) = &args.tabulate_on {
        return tabulated(args, target, grid, out);
    }
    let job = ExportJob {
        from: args
            .from
            .clone()
            .ok_or(brdf_export::ExportError::UnknownOption {
                option: "--from",
                value: String::new(),
                expected: "a model saved by `brdf fit --save` (--from MODEL.json)",
            })?,
        target,
        out: out.clone(),
        exact: args.exact,
        convert: ConvertOptions {
            via: args.via.clone(),
            pairs: args.pairs,
            limit_deg: args.limit,
            starts: args.starts,
            appearance: !args.brdf_space,
            force: args.force,
            ..ConvertOptions::default()
        },
        save_converted: args.save_converted.clone(),
        write: WriteOptions {
            name: args.name.as_deref().map(identifier).unwrap_or_default(),
            scene: args.scene,
            light: args.light.into(),
            surface: args.surface.into(),
            mesh: !args.no_mesh,
        },
    };
    let done = brdf_export::file::run(&job)?;
    if !args.json {
        for w in &done.exported.warnings {
            eprintln!("warning: {w}");
        }
    }
    report(args, out, &done.model, job.target, &done.exported)
}

/// `--tabulate-on`: the model tabulated on a measurement's grid.
fn tabulated(
    args: &ExportArgs,
    target: Target,
    grid: &std::path::Path,
    out: &std::path::Path,
) -> Result<(), CliError> {
    if target != Target::Mitsuba || args.scene {
        return Err(brdf_export::ExportError::UnknownOption {
            option: "--tabulate-on",
            value: format!("--to {target}{}", if args.scene { " --scene" } else { "" }),
            expected: "--to mitsuba without --scene (Mitsuba's `measured` plugin reads the tabulated file)",
        }
        .into());
    }
    let from = args
        .from
        .as_deref()
        .ok_or(brdf_export::ExportError::UnknownOption {
            option: "--from",
            value: String::new(),
            expected: "a model saved by `brdf fit --save` (--from MODEL.json)",
        })?;
    let t = brdf_export::measured::run(from, grid, out)?;
    if args.json {
        let v = serde_json::json!({
            "model": t.model, "target": "mitsuba", "out": out.display().to_string(),
            "exact": true, "tabulated_on": grid.display().to_string(),
            "incident_directions": t.incident, "nodes_per_direction": t.per_incident,
            "snippet": t.snippet,
        });
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    say!(
        "wrote {}: `{}` tabulated on the grid of {} ({} incident directions x {} nodes, RGB) for Mitsuba's `measured` plugin:\n{}",
        out.display(),
        t.model,
        grid.display(),
        t.incident,
        t.per_incident,
        t.snippet.trim_end()
    )
}

fn report(
    args: &ExportArgs,
    out: &std::path::Path,
    model: &str,
    target: Target,
    exported: &Exported,
) -> Result<(), CliError> {
    let out = out.display();
    if args.json {
        let conversion = exported.conversion.as_ref().map(|c| {
            serde_json::json!({
                "via": c.model.name(),
                "samples": c.error.samples,
                "limit_deg": c.error.limit_deg,
                "ngan_l2": c.error.ngan_l2,
                "relative_l2": c.error.relative_l2,
                "image": c.image,
                "note": c.note(),
                "mean_flip": c.image.mean_flip(),
                "max_flip": c.image.max_flip(),
                "max_delta_e": c.image.max_delta_e(),
                // Beyond the refusal limits, so written only because of
                // --force; beyond the warning limits, written with a warning.
                "forced": c.check(target).is_err(),
                "warned": brdf_export::for_renderer::conversion_warning(c, target, brdf_export::FrontEnd::Cli).is_some(),
            })
        });
        let v = serde_json::json!({
            "model": model, "target": target.to_string(), "out": out.to_string(),
            "exact": exported.conversion.is_none(), "mapped": brdf_export::table::is_mapped(model, target, args.surface.into()),
            "conversion": conversion, "warnings": exported.warnings,
        });
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    match &exported.conversion {
        None if brdf_export::table::is_mapped(model, target, args.surface.into()) => say!(
            "wrote {out}: `{model}` mapped to {target} (its parameters; the renderer's own BRDF, see `brdf export --list`)"
        ),
        None => say!("wrote {out}: `{model}` exactly as {target}"),
        Some(c) => say!("wrote {out}: {}", c.note()),
    }?;
    say!("{}", target.usage(&out.to_string()))
}

#[cfg(test)]
mod tests {
    use clap::ValueEnum;

    use super::*;

    #[test]
    fn every_target_has_one_to_value_that_the_library_parses_back() {
        assert_eq!(ToArg::value_variants().len(), Target::ALL.len());
        for t in Target::ALL {
            let arg = ToArg::from(t);
            assert_eq!(Target::from(arg), t);
            let name = arg.to_possible_value().map(|v| v.get_name().to_string());
            assert_eq!(name.as_deref().map(str::parse::<Target>), Some(Ok(t)));
        }
    }

    #[test]
    fn light_and_surface_values_are_the_library_s() {
        for l in LightArg::value_variants() {
            let name = l.to_possible_value().map(|v| v.get_name().to_string());
            assert_eq!(
                name.as_deref().map(str::parse::<Light>),
                Some(Ok((*l).into()))
            );
        }
        for s in SurfaceArg::value_variants() {
            let name = s.to_possible_value().map(|v| v.get_name().to_string());
            assert_eq!(
                name.as_deref().map(str::parse::<Surface>),
                Some(Ok((*s).into()))
            );
        }
    }

    #[test]
    fn the_force_help_states_the_code_s_limits() {
        let h = force_help();
        assert!(
            h.contains(&format!(
                "refused above HDR-FLIP {}",
                brdf_export::convert::FLIP_REFUSE
            )),
            "{h}"
        );
        assert!(
            h.contains("0.02") && h.contains("0.1") && !h.contains("0.05"),
            "{h}"
        );
    }
}
