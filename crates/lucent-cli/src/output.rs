//! Image files: PNG (sRGB, 8 bit), PFM and OpenEXR (linear float).
//!
//! Every file is written under a temporary name in the same folder and renamed into place,
//! so a crash never leaves a truncated image under the final name.

use anyhow::{Context, bail};
use image::{DynamicImage, ImageBuffer, Rgb, Rgb32FImage, RgbImage};
use lucent::film::Film;
use lucent::film::tonemap::srgb8;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The image formats lucent writes, chosen by the file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// `.png`: sRGB-encoded, 8 bits per channel, clamped to [0, 1].
    Png,
    /// `.pfm`: linear 32-bit float RGB (Portable Float Map).
    Pfm,
    /// `.exr`: linear 32-bit float RGB (OpenEXR).
    Exr,
}

impl ImageFormat {
    /// The format for `path`'s extension.
    pub fn from_path(path: &Path) -> anyhow::Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Self::Png),
            Some("pfm") => Ok(Self::Pfm),
            Some("exr") => Ok(Self::Exr),
            _ => bail!(
                "{}: unknown image format (use .png, .pfm or .exr)",
                path.display()
            ),
        }
    }
}

/// Writes `film` to `path` as `format`, atomically.
pub fn write_image(film: &Film, path: &Path, format: ImageFormat) -> anyhow::Result<()> {
    let tmp = temporary_path(path);
    let result = write_to(film, &tmp, format).and_then(|()| {
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot move {} into place", tmp.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn temporary_path(path: &Path) -> PathBuf {
    let mut name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(format!(".tmp-{}", std::process::id()));
    path.with_file_name(name)
}

fn write_to(film: &Film, path: &Path, format: ImageFormat) -> anyhow::Result<()> {
    let (w, h) = (film.width(), film.height());
    let pixels = film.to_linear_rgb();
    let file = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut out = BufWriter::new(file);
    match format {
        ImageFormat::Png => {
            let bytes = pixels.iter().flat_map(|p| p.map(srgb8)).collect();
            let img: RgbImage =
                ImageBuffer::from_raw(w, h, bytes).context("image size mismatch")?;
            DynamicImage::ImageRgb8(img).write_to(&mut out, image::ImageFormat::Png)?;
        }
        ImageFormat::Exr => {
            let floats = pixels.iter().flatten().copied().collect();
            let img: Rgb32FImage = ImageBuffer::<Rgb<f32>, _>::from_raw(w, h, floats)
                .context("image size mismatch")?;
            DynamicImage::ImageRgb32F(img).write_to(&mut out, image::ImageFormat::OpenExr)?;
        }
        ImageFormat::Pfm => write_pfm(&mut out, w, h, &pixels)?,
    }
    let file = out.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()?;
    Ok(())
}

/// Portable Float Map: a text header, then little-endian floats, rows from the bottom up.
fn write_pfm(out: &mut impl Write, w: u32, h: u32, pixels: &[[f32; 3]]) -> std::io::Result<()> {
    write!(out, "PF\n{w} {h}\n-1.0\n")?;
    for row in pixels.chunks(w as usize).rev() {
        for p in row {
            for c in p {
                out.write_all(&c.to_le_bytes())?;
            }
        }
    }
    Ok(())
}
