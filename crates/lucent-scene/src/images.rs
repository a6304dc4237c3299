//! Image files for textures and environments: PNG, JPEG, EXR, HDR, read into linear RGB.

use crate::error::LoadError;
use crate::hash::Fingerprint;
use lucent::Rgb;
use lucent::film::tonemap::{srgb_to_linear, srgb8_to_linear};
use lucent::texture::ImageTexture;
use std::path::Path;

/// Largest image side read, in texels.
pub const MAX_IMAGE_SIDE: u32 = 32_768;
/// Most bytes the decoder may allocate for one image.
const MAX_DECODE_BYTES: u64 = 1 << 30;
/// Most texels of one image (an 8192 × 4096 environment map): checked from the header before
/// decoding, since the texels end as 12-byte float triples.
pub const MAX_TEXELS: u64 = 1 << 25;

/// Reads the image at `path`: 8-bit and 16-bit images are taken as sRGB-encoded, float images
/// (EXR, HDR) as linear. Its bytes are added to `inputs`.
pub fn read_image(path: &Path, inputs: &mut Fingerprint) -> Result<ImageTexture, LoadError> {
    let bytes = std::fs::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the image: {e}")))?;
    inputs.add(&bytes);
    let unreadable =
        |e: image::ImageError| LoadError::file(path, format!("cannot read the image: {e}"));
    let mut decoder = image::ImageReader::new(std::io::Cursor::new(&bytes))
        .with_guessed_format()
        .map_err(|e| LoadError::file(path, format!("cannot read the image: {e}")))?
        .into_decoder()
        .map_err(unreadable)?;
    // The header's size, checked before anything is decoded.
    let (w, h) = image::ImageDecoder::dimensions(&decoder);
    if u64::from(w) * u64::from(h) > MAX_TEXELS {
        return Err(LoadError::file(
            path,
            format!("the image is {w}×{h}: more than the {MAX_TEXELS} texels lucent reads"),
        ));
    }
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(MAX_DECODE_BYTES);
    let decoded = image::ImageDecoder::set_limits(&mut decoder, limits)
        .and_then(|()| image::DynamicImage::from_decoder(decoder))
        .map_err(|e| LoadError::file(path, format!("cannot decode the image: {e}")))?;
    let float = matches!(
        decoded.color(),
        image::ColorType::Rgb32F | image::ColorType::Rgba32F
    );
    let texels: Vec<Rgb> = if float {
        decoded
            .into_rgb32f()
            .pixels()
            .map(|p| Rgb::from(p.0))
            .collect()
    } else if matches!(
        decoded.color(),
        image::ColorType::L16
            | image::ColorType::La16
            | image::ColorType::Rgb16
            | image::ColorType::Rgba16
    ) {
        let decode = |v: u16| srgb_to_linear(f32::from(v) / 65535.0);
        decoded
            .into_rgb16()
            .pixels()
            .map(|p| Rgb::from(p.0.map(decode)))
            .collect()
    } else {
        decoded
            .into_rgb8()
            .pixels()
            .map(|p| Rgb::from(p.0.map(srgb8_to_linear)))
            .collect()
    };
    if texels
        .iter()
        .any(|t| !(t.r.is_finite() && t.g.is_finite() && t.b.is_finite()))
    {
        return Err(LoadError::file(
            path,
            "the image holds values that are not finite",
        ));
    }
    ImageTexture::new(w, h, texels).ok_or_else(|| LoadError::file(path, "the image is empty"))
}
