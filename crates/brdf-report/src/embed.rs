//! Images inside the HTML: PNG bytes as base64 `data:` URIs.

use base64::Engine;
use brdf_render::Image;

use crate::ReportError;

/// `data:image/png;base64,...` of `image` at `exposure` (gamma 2.2).
pub fn png_uri(image: &Image, exposure: f64) -> Result<String, ReportError> {
    let bytes = image.png_bytes(exposure)?;
    Ok(format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tiny_image_is_a_png_data_uri() {
        let img = Image {
            width: 2,
            height: 1,
            channels: 3,
            data: vec![0.5; 6],
        };
        let uri = png_uri(&img, 1.0).expect("encodes");
        // base64 of the PNG signature
        assert!(
            uri.starts_with("data:image/png;base64,iVBORw0KGgo"),
            "{uri}"
        );
    }
}
