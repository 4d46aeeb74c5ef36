//! Time the judge render of a GGX-like BRDF at 128 x 128 under the studio
//! set (terms once, then renders), on one thread, and print the numbers:
//!
//! `cargo run --release -p brdf-render --example judge_timing`

use std::time::Instant;

use brdf_core::Brdf;
use brdf_render::{LightSet, ShadingPoints};
use nalgebra::Vector3;

/// Lambert plus a GGX lobe with Smith shadowing and Schlick Fresnel.
struct Ggx {
    kd: [f64; 3],
    alpha: f64,
    f0: f64,
}

impl Brdf for Ggx {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let h = (l + v).normalize();
        let a2 = self.alpha * self.alpha;
        let d = a2 / (std::f64::consts::PI * (h.z * h.z * (a2 - 1.0) + 1.0).powi(2));
        let lambda = |c: f64| 0.5 * ((1.0 + a2 * (1.0 - c * c) / (c * c)).sqrt() - 1.0);
        let g = 1.0 / (1.0 + lambda(l.z) + lambda(v.z));
        let f = self.f0 + (1.0 - self.f0) * (1.0 - l.dot(&h)).powi(5);
        let spec = d * g * f / (4.0 * l.z * v.z);
        for c in 0..3 {
            out[c] = self.kd[c] / std::f64::consts::PI + spec;
        }
    }
}

/// CPU seconds (user + system) of this process so far, from
/// `/proc/self/stat` (Linux; `None` elsewhere). Wall time overstates the
/// cost on a loaded machine.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = after.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

const RENDERS: usize = 20;

fn main() {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build();
    let Ok(pool) = pool else {
        eprintln!("cannot build a one-thread pool");
        return;
    };
    let brdf = Ggx {
        kd: [0.3, 0.2, 0.1],
        alpha: 0.2,
        f0: 0.04,
    };
    pool.install(|| {
        let t0 = Instant::now();
        let c0 = cpu_seconds();
        let sp = ShadingPoints::judge(&LightSet::studio(), 128);
        let t1 = Instant::now();
        let c1 = cpu_seconds();
        let mut img = sp.render(&brdf);
        for _ in 1..RENDERS {
            img = sp.render(&brdf);
        }
        let c2 = cpu_seconds();
        let t2 = Instant::now();
        let cpu = match (c0, c1, c2) {
            (Some(a), Some(b), Some(c)) => format!(
                "terms {:.0} ms CPU, render {:.1} ms CPU",
                (b - a) * 1e3,
                (c - b) * 1e3 / RENDERS as f64
            ),
            _ => "CPU time unknown".into(),
        };
        println!(
            "studio 128 px: {} pixels, {} terms; terms {:.1} ms, render {:.1} ms wall, {cpu} (one thread, mean of {RENDERS}); peak {:.3}",
            sp.pixels.len(),
            sp.len(),
            (t1 - t0).as_secs_f64() * 1e3,
            (t2 - t1).as_secs_f64() * 1e3 / RENDERS as f64,
            img.peak()
        );
    });
}
