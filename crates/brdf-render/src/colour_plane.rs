//! How far an image's colours lie from every plane of white and one colour:
//! a lower bound on how closely a renderer model with one base colour can
//! render it.
//!
//! Every lobe of the principled BRDF (Mitsuba 3's `principled`, Blender's
//! Principled BSDF in its reflection part) and of glTF's metallic-roughness
//! BRDF is coloured white or by the base colour `C`: the diffuse by `C`, the
//! sheen by a mix of white and `C`'s hue, the specular Fresnel by white, `C`
//! (metal) or `C`'s hue (tint), each going to white at grazing angles
//! (Schlick: `F0 (1 - w) + w`), the clear coat white. So at every direction
//! pair the value is `a (1, 1, 1) + b C` with `a, b >= 0`, and under lights
//! of one colour, white (the judge's `studio` set), so is every pixel of a
//! render: all of its colours lie in the plane through the origin spanned by
//! white and `C`.
//!
//! [`colour_plane`] finds the plane that the image's colours are closest to
//! (least squares in linear RGB over the masked pixels) and the part of the
//! colours it leaves out: with `w = (1, 1, 1) / sqrt 3`, each colour's
//! chroma `p = c - (c . w) w` is a point of the 2-D plane orthogonal to
//! white, the planes through white are the lines through the origin there,
//! and the best line is the principal axis of the scatter `sum p p^T`
//! (`nalgebra`'s symmetric eigendecomposition; the distances from it are
//! then summed). Relaxing `b >= 0` (a ray) to a line only
//! lowers the distance, so
//!
//! `outside = sqrt(lambda_min / sum |c|^2)`
//!
//! is a lower bound: no render of such a model under white light comes
//! closer to the image than that relative RMS difference (linear RGB), for
//! any parameters. A colour-shifting film whose highlight hue differs from
//! its body's (cc_ibiza_sunset: a magenta highlight over an orange body) has
//! colours off every such plane; a paint of one hue (colodur_napoli) does
//! not.

use nalgebra::{Matrix2, Vector2, Vector3};

use crate::Image;
use crate::tonemap::rgb_at;

/// The plane of white and one colour closest to an image's colours, and
/// how much of them lies off it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColourPlane {
    /// The plane's colour (linear RGB, largest channel 1, smallest 0): the
    /// hue a single base colour would need; with white it spans the plane.
    pub colour: [f64; 3],
    /// RMS distance of the colours from the plane over their RMS (linear
    /// RGB): a lower bound on the relative RMS difference of any render
    /// whose colours lie in a plane through white.
    pub outside: f64,
}

/// The colour plane of the pixels of `image` where `mask` is true; `None`
/// when there are none or all are black. Two passes over the pixels.
pub fn colour_plane(image: &Image, mask: &[bool]) -> Option<ColourPlane> {
    let white = Vector3::new(1.0, 1.0, 1.0).normalize();
    // An orthonormal basis of the chroma plane (orthogonal to white).
    let e1 = Vector3::new(1.0, -1.0, 0.0).normalize();
    let e2 = white.cross(&e1);
    // Each masked pixel's chroma coordinates and squared norm.
    let pixels = || {
        (0..image.width * image.height)
            .filter(|&p| mask.get(p).copied().unwrap_or(false))
            .map(|p| {
                let c = Vector3::from(rgb_at(image, p));
                (Vector2::new(c.dot(&e1), c.dot(&e2)), c.norm_squared())
            })
    };
    let mut scatter = Matrix2::zeros();
    let mut energy = 0.0;
    for (q, e) in pixels() {
        scatter += q * q.transpose();
        energy += e;
    }
    if !(energy > 0.0) {
        return None;
    }
    let eig = scatter.symmetric_eigen();
    let major = usize::from(eig.eigenvalues[1] > eig.eigenvalues[0]);
    let axis = eig.eigenvectors.column(major);
    // The distances summed directly, not read off the smallest eigenvalue:
    // that is a difference of squares, whose rounding (relative 1e-16 of
    // the largest) would show as 1e-8 in its square root.
    let (mut pos, mut neg, mut off) = (0.0, 0.0, 0.0);
    for (q, _) in pixels() {
        let along = q.dot(&axis);
        let across = q.y * axis[0] - q.x * axis[1];
        off += across * across;
        // The axis's direction holding more of the colours names the hue.
        if along > 0.0 {
            pos += along * along;
        } else {
            neg += along * along;
        }
    }
    let sign = if pos >= neg { 1.0 } else { -1.0 };
    let chroma = (e1 * axis[0] + e2 * axis[1]) * sign;
    Some(ColourPlane {
        colour: hue_colour(&chroma),
        outside: (off / energy).sqrt(),
    })
}

/// The colour of chroma direction `d` (orthogonal to white), shifted along
/// white to a smallest channel of 0 and scaled to a largest of 1.
fn hue_colour(d: &Vector3<f64>) -> [f64; 3] {
    let lo = d.min();
    let c = d.map(|x| x - lo);
    let hi = c.max();
    if hi > 0.0 { (c / hi).into() } else { [1.0; 3] }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(colours: &[[f64; 3]]) -> (Image, Vec<bool>) {
        let img = Image {
            width: colours.len(),
            height: 1,
            channels: 3,
            data: colours.iter().flatten().copied().collect(),
        };
        (img, vec![true; colours.len()])
    }

    #[test]
    fn colours_of_white_and_one_colour_lie_in_its_plane() {
        // a (1, 1, 1) + b C for C orange, with a, b >= 0 of any sizes.
        let c = [0.9, 0.4, 0.1];
        let colours: Vec<[f64; 3]> = [(0.0, 1.0), (0.2, 0.5), (1.0, 0.0), (0.05, 3.0)]
            .iter()
            .map(|(a, b)| std::array::from_fn(|k| a + b * c[k]))
            .collect();
        let (img, mask) = image(&colours);
        let plane = colour_plane(&img, &mask).unwrap();
        assert!(plane.outside < 1e-12, "{plane:?}");
        // The plane's colour is C's hue: C shifted to a zero minimum, scaled.
        let want = [1.0, 0.375, 0.0];
        for k in 0..3 {
            assert!((plane.colour[k] - want[k]).abs() < 1e-12, "{plane:?}");
        }
    }

    #[test]
    fn two_hues_a_right_angle_apart_leave_the_smaller_one_out() {
        // Chromas along e1 (size 2) and e2 (size 1), no white component:
        // the best line is e1's, the distance left is the e2 colour's, so
        // outside = |1| / sqrt(2^2 + 1^2) (hand-derived).
        let e1 = Vector3::new(1.0, -1.0, 0.0).normalize();
        let e2 = Vector3::new(1.0, 1.0, 1.0).normalize().cross(&e1);
        let (img, mask) = image(&[(e1 * 2.0).into(), e2.into()]);
        let plane = colour_plane(&img, &mask).unwrap();
        assert!(
            (plane.outside - 1.0 / 5f64.sqrt()).abs() < 1e-12,
            "{plane:?}"
        );
        // e1 = (1, -1, 0) / sqrt 2: magenta-red, shifted and scaled.
        let want = [1.0, 0.0, 0.5];
        for k in 0..3 {
            assert!((plane.colour[k] - want[k]).abs() < 1e-12, "{plane:?}");
        }
    }

    #[test]
    fn masked_out_and_black_pixels_do_not_count() {
        let (img, _) = image(&[[0.9, 0.4, 0.1], [0.0, 0.0, 1.0]]);
        let plane = colour_plane(&img, &[true, false]).unwrap();
        assert!(plane.outside < 1e-12);
        assert!(colour_plane(&img, &[false, false]).is_none());
        let (black, mask) = image(&[[0.0; 3]; 2]);
        assert!(colour_plane(&black, &mask).is_none());
    }
}
