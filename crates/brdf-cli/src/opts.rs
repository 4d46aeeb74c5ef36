//! Options and argument parsers shared by several commands. Imports no
//! command, so every command may use it.

use brdf_core::Direction;

use crate::error::CliError;

/// Structural options shared by every command that builds a model.
#[derive(Debug, Clone, clap::Args)]
pub struct ModelOpts {
    /// Colour channels of the model (1 grey, 3 RGB).
    #[arg(long, default_value_t = 1, value_parser = at_least_one)]
    pub channels: usize,
    /// Specular lobes (Lafortune, Cook-Torrance).
    #[arg(long, default_value_t = 1, value_parser = at_least_one)]
    pub lobes: usize,
    /// Koenderink expansion order.
    #[arg(long, default_value_t = 8)]
    pub order: usize,
    /// Polynomial degree (Kurt's model).
    #[arg(long, default_value_t = 7)]
    pub degree: usize,
}

impl ModelOpts {
    /// As a model configuration.
    pub fn config(&self) -> brdf_models::ModelConfig {
        brdf_models::ModelConfig {
            channels: self.channels,
            lobes: self.lobes,
            order: self.order,
            degree: self.degree,
        }
    }
}

/// A count of at least 1 (`--lobes`, `--channels`); clap names the flag.
pub fn at_least_one(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(0) => Err("must be at least 1 (e.g. 1)".into()),
        Ok(n) => Ok(n),
        Err(_) => Err(format!("`{s}` is not a whole number >= 1")),
    }
}

/// Parse `name=value,name=value`.
pub fn parse_assignments(s: &str) -> Result<Vec<(String, f64)>, CliError> {
    s.split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| {
            let (k, v) = t.split_once('=').ok_or_else(|| {
                CliError::Usage(format!("parameter `{t}` is not of the form name=value"))
            })?;
            let x: f64 = v.trim().parse().map_err(|_| {
                CliError::Usage(format!(
                    "parameter `{}`: `{}` is not a number",
                    k.trim(),
                    v.trim()
                ))
            })?;
            Ok((k.trim().to_string(), x))
        })
        .collect()
}

/// Parse `THETA,PHI` (radians, or degrees when `degrees`) into a direction;
/// `what` names the argument in errors.
pub fn parse_direction(s: &str, degrees: bool, what: &str) -> Result<Direction, CliError> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        return Err(CliError::Usage(format!("{what} `{s}` must be THETA,PHI")));
    }
    let mut a = [0.0f64; 2];
    for (i, p) in parts.iter().enumerate() {
        a[i] = p
            .parse()
            .map_err(|_| CliError::Usage(format!("{what}: `{p}` is not a number")))?;
    }
    if degrees {
        a = [a[0].to_radians(), a[1].to_radians()];
    }
    Ok(Direction::from_spherical(a[0], a[1])?)
}

/// `--metric`: what a fit minimises (the library's [`brdf_fit::Metric`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MetricArg {
    /// Appearance for renderer models on data that can be rendered, else ngan.
    Auto,
    /// Candidates chosen by image error, refined in the image objective.
    Appearance,
    /// Ngan's L2 (cosine-weighted).
    Ngan,
    /// Sopp's weighted objective.
    Sopp,
    /// Sopp's objective without solid-angle weights.
    SoppUnweighted,
    /// Lafortune's cos_i cos_o weighting.
    Lafortune,
    /// Matusik's log error.
    Log,
    /// Cube root of the cosine-weighted values.
    CubeRoot,
    /// Error relative to the data.
    Relative,
    /// Image objective alone (tone-mapped sphere pixels).
    Image,
}

impl MetricArg {
    /// The library's metric of the same name.
    pub fn metric(self) -> Result<brdf_fit::Metric, CliError> {
        Ok(brdf_fit::Metric::parse(&value_name(self))?)
    }
}

/// `--channels` of a fit (the library's [`brdf_fit::ChannelMode`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ChannelsArg {
    /// Every channel: shared non-linear, per-channel linear parameters.
    Rgb,
    /// The mean of the channels.
    Grey,
    /// Everything per channel (one grey model per channel).
    PerChannel,
}

impl ChannelsArg {
    /// The library's channel mode of the same name.
    pub fn mode(self) -> Result<brdf_fit::ChannelMode, CliError> {
        Ok(brdf_fit::ChannelMode::parse(&value_name(self))?)
    }
}

/// The name clap shows for a value of a [`clap::ValueEnum`], which is the
/// name the library parses.
fn value_name<T: clap::ValueEnum>(v: T) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// `--solver`: `auto`, `sqp`, `lm`, `sopp`, `ols`, `irls` or
/// `irls:WEIGHT`, parsed by the library.
pub fn solver(s: &str) -> Result<brdf_fit::Solver, String> {
    brdf_fit::Solver::parse(s).map_err(|e| e.to_string())
}

/// A renderer's material format (`--to` of `brdf export`, `--for` of
/// `brdf fit`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum TargetArg {
    /// Mitsuba 3 scene-description XML.
    Mitsuba,
    /// pbrt-v4 material statements.
    Pbrt,
    /// glTF 2.0 asset.
    Gltf,
    /// MaterialX document.
    Materialx,
    /// USD layer: a UsdPreviewSurface, or the MaterialX graph of a coloured-lobe or thin-film fit.
    Usd,
    /// Blender Python script building the material.
    Blender,
}

impl TargetArg {
    /// The exporter's target.
    pub fn target(self) -> brdf_export::Target {
        match self {
            TargetArg::Mitsuba => brdf_export::Target::Mitsuba,
            TargetArg::Pbrt => brdf_export::Target::Pbrt,
            TargetArg::Gltf => brdf_export::Target::Gltf,
            TargetArg::Materialx => brdf_export::Target::MaterialX,
            TargetArg::Usd => brdf_export::Target::Usd,
            TargetArg::Blender => brdf_export::Target::Blender,
        }
    }
}
