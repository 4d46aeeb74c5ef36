//! Shared by the fuzz targets: a few fixed direction pairs at which a
//! successfully parsed BRDF is evaluated (normal, oblique, grazing, below
//! the horizon), so evaluation of a fuzzed table is exercised too.

use nalgebra::Vector3;

/// `(L, V)` pairs covering the cases evaluation has to handle.
pub fn probe_pairs() -> Vec<(Vector3<f64>, Vector3<f64>)> {
    let dir = |t: f64, p: f64| Vector3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    vec![
        (dir(0.0, 0.0), dir(0.0, 0.0)),
        (dir(0.5, 0.3), dir(0.7, 3.0)),
        (dir(1.2, -2.0), dir(0.2, 1.0)),
        (dir(1.5707, 0.0), dir(1.5707, 3.14159)),
        (dir(0.3, 0.0), dir(2.0, 0.0)),
    ]
}
