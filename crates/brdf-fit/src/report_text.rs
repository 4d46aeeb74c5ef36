//! A fit report as text, as `brdf fit` prints it: what was fitted on
//! what, the solver's course, every parameter with its standard error and
//! bound, the errors and the time, and the parameters the fit leaves
//! undetermined.

use std::fmt::Write as _;

use crate::{FitReport, FitSummary};
use brdf_render::ImageError;

/// The readable report of one fit (several lines).
pub fn text(rep: &FitReport) -> String {
    let r = &rep.summary;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {} on {} ({} of {} samples used; dropped {} invalid, {} beyond {} deg)",
        r.model,
        r.data,
        r.samples,
        rep.samples_present,
        rep.dropped_invalid,
        rep.dropped_angle,
        rep.limit_deg
    );
    let _ = writeln!(s, "solver: {}", r.solver);
    let _ = writeln!(
        s,
        "iterations {}, {}; starts {} ({} converged, {} at the best cost)",
        r.iterations, r.termination, r.starts.0, r.starts.1, r.starts.2
    );
    let off_lobe = undetermined(r);
    for p in &r.parameters {
        let se = p
            .std_error
            .map(|s| format!("+- {s:.3e}"))
            .unwrap_or_default();
        let b = p
            .at_bound
            .as_ref()
            .map(|b| format!(" [at {b} bound]"))
            .unwrap_or_default();
        let pr = if p.projected { " (projected)" } else { "" };
        let off = if off_lobe.contains(&p.name) {
            " [undetermined: lobe off, ks = 0]"
        } else {
            ""
        };
        let _ = writeln!(s, "  {:<8} {:>14.6e} {se}{b}{pr}{off}", p.name, p.value);
    }
    let _ = writeln!(
        s,
        "{} error: {:.6e}  Ngan L2: {:.6e}  time: {:.3} ms",
        r.objective,
        r.error,
        r.ngan_l2,
        r.seconds * 1e3
    );
    image_lines(&mut s, rep);
    for note in &rep.notes {
        let _ = writeln!(s, "note: {note}");
    }
    s
}

/// The candidates of a fit chosen by image error, and the fit's image
/// errors (or why there are none).
fn image_lines(s: &mut String, rep: &FitReport) {
    for c in &rep.candidates {
        let flips: Vec<String> = c
            .image
            .lights
            .iter()
            .map(|l| format!("{} {:.3}", l.light, l.flip))
            .collect();
        let _ = writeln!(
            s,
            "candidate{} {:<9} lobes [{}]: FLIP {} ({} px), CIEDE2000 {:.1}, Ngan L2 {:.4e}, {:.2} s",
            if c.chosen { " *" } else { "  " },
            c.objective,
            c.lobes.join(", "),
            flips.join(", "),
            c.image.size,
            c.image.max_delta_e(),
            c.ngan_l2,
            c.seconds
        );
    }
    if let Some(e) = &rep.image_error {
        s.push_str(&image_error_lines(e));
    }
    if let Some(n) = &rep.image_note {
        let _ = writeln!(s, "{n}");
    }
}

/// One line per light set of image errors (`brdf fit`, `brdf select`).
pub fn image_error_lines(e: &ImageError) -> String {
    let mut s = String::new();
    for l in &e.lights {
        let _ = writeln!(
            s,
            "image error ({}, {} px): FLIP {:.3}  PSNR {:.1} dB  mean colour CIEDE2000 {:.2}",
            l.light, e.size, l.flip, l.psnr, l.delta_e
        );
    }
    s
}

/// Names of the non-linear parameters a fit leaves undetermined: the
/// shape parameters of a specular lobe whose strengths (`ks`, `ks1`,
/// `ks_r`, ...) are all zero and on which the fitted model then does not
/// depend ([`FitSummary::inert`]; the coupled Ashikhmin-Shirley diffuse
/// term still depends on `f0`).
pub fn undetermined(summary: &FitSummary) -> Vec<String> {
    fn strength(n: &str) -> Option<&str> {
        let n = n.split('_').next().unwrap_or(n);
        n.strip_prefix("ks")
            .filter(|r| r.chars().all(|c| c.is_ascii_digit()))
    }
    let mut lobes: Vec<(String, bool)> = Vec::new();
    for p in summary.parameters.iter() {
        if let Some(k) = strength(&p.name) {
            let off = p.value.abs() <= 0.0;
            match lobes.iter_mut().find(|(l, _)| l == k) {
                Some(e) => e.1 &= off,
                None => lobes.push((k.to_string(), off)),
            }
        }
    }
    summary
        .parameters
        .iter()
        .filter(|p| !p.projected && strength(&p.name).is_none())
        .filter(|p| summary.inert.contains(&p.name))
        .filter(|p| {
            let lobe = lobe_number(&p.name);
            lobes
                .iter()
                .any(|(l, off)| *off && (l.is_empty() || *l == lobe))
        })
        .map(|p| p.name.clone())
        .collect()
}

/// Trailing lobe number of a shape parameter (`m1`, `f0_1`, `cxy2`): the
/// digits after the last letter or underscore, "" when the name has none
/// besides a built-in digit (`f0`).
fn lobe_number(name: &str) -> String {
    if let Some((_, k)) = name.rsplit_once('_')
        && k.chars().all(|c| c.is_ascii_digit())
    {
        return k.to_string();
    }
    if name == "f0" {
        return String::new();
    }
    let digits: String = name
        .chars()
        .rev()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.chars().rev().collect()
}
