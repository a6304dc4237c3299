//! Image files for textures and environments: PNG, JPEG, EXR, HDR, read into linear RGB.

use crate::desc::texture::Encoding;
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

/// Reads the image at `path`: 8-bit and 16-bit images are decoded by `encoding` (sRGB or
/// linear), float images (EXR, HDR) are linear; an alpha channel is kept (always linear). Its
/// bytes are added to `inputs`.
pub fn read_image(
    path: &Path,
    encoding: Encoding,
    inputs: &mut Fingerprint,
) -> Result<ImageTexture, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the image: {e}")))?;
    inputs.add(&bytes);
    decode_image(&bytes, encoding).map_err(|e| LoadError::file(path, e))
}

/// The image encoded in `bytes` (PNG, JPEG, EXR, HDR …), decoded as [`read_image`] says.
pub fn decode_image(bytes: &[u8], encoding: Encoding) -> Result<ImageTexture, String> {
    let unreadable = |e: image::ImageError| format!("cannot read the image: {e}");
    let mut decoder = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read the image: {e}"))?
        .into_decoder()
        .map_err(unreadable)?;
    // The header's size, checked before anything is decoded.
    let (w, h) = image::ImageDecoder::dimensions(&decoder);
    if u64::from(w) * u64::from(h) > MAX_TEXELS {
        return Err(format!(
            "the image is {w}×{h}: more than the {MAX_TEXELS} texels lucent reads"
        ));
    }
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(MAX_DECODE_BYTES);
    let decoded = image::ImageDecoder::set_limits(&mut decoder, limits)
        .and_then(|()| image::DynamicImage::from_decoder(decoder))
        .map_err(|e| format!("cannot decode the image: {e}"))?;
    let color = decoded.color();
    let float = matches!(color, image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    let wide = matches!(
        color,
        image::ColorType::L16
            | image::ColorType::La16
            | image::ColorType::Rgb16
            | image::ColorType::Rgba16
    );
    let has_alpha = color.has_alpha();
    let srgb = encoding == Encoding::Srgb;
    let mut alpha = Vec::new();
    let texels: Vec<Rgb> = if float {
        let img = decoded.into_rgba32f();
        if has_alpha {
            alpha = img.pixels().map(|p| p.0[3].clamp(0.0, 1.0)).collect();
        }
        img.pixels()
            .map(|p| Rgb::new(p.0[0], p.0[1], p.0[2]))
            .collect()
    } else if wide {
        let decode = |v: u16| {
            let x = f32::from(v) / 65535.0;
            if srgb { srgb_to_linear(x) } else { x }
        };
        let img = decoded.into_rgba16();
        if has_alpha {
            alpha = img.pixels().map(|p| f32::from(p.0[3]) / 65535.0).collect();
        }
        img.pixels()
            .map(|p| Rgb::new(decode(p.0[0]), decode(p.0[1]), decode(p.0[2])))
            .collect()
    } else {
        let decode = |v: u8| {
            if srgb {
                srgb8_to_linear(v)
            } else {
                f32::from(v) / 255.0
            }
        };
        let img = decoded.into_rgba8();
        if has_alpha {
            alpha = img.pixels().map(|p| f32::from(p.0[3]) / 255.0).collect();
        }
        img.pixels()
            .map(|p| Rgb::new(decode(p.0[0]), decode(p.0[1]), decode(p.0[2])))
            .collect()
    };
    if texels
        .iter()
        .any(|t| !(t.r.is_finite() && t.g.is_finite() && t.b.is_finite()))
    {
        return Err("the image holds values that are not finite".into());
    }
    let max = lucent::texture::MAX_VALUE;
    if texels.iter().any(|t| t.max_channel() > max) {
        return Err(format!(
            "the image holds values above {max:e}, the largest a texture may take"
        ));
    }
    let image = ImageTexture::new(w, h, texels).ok_or("the image is empty")?;
    if alpha.is_empty() {
        return Ok(image);
    }
    image
        .with_alpha(alpha)
        .ok_or_else(|| "the image's alpha channel does not match its size".into())
}
