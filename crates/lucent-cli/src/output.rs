//! Image files: PNG (sRGB, 8 bit), PFM and OpenEXR (linear float).
//!
//! Every file is written under a temporary name in the same folder and renamed into place,
//! so a crash (even SIGKILL) never leaves a truncated image under the final name. PNG and EXR
//! carry the samples per pixel reached in their metadata (`lucent.samples`: `N`, or `MIN..MAX`
//! when a stopped render left pixels at different counts).

use anyhow::{Context, anyhow, bail};
use lucent::film::Display;
use lucent::film::Film;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// How EXR files are written: lossless, and with their blocks in increasing order so that the
/// same image always gives the same bytes (parallel compression would otherwise order them as
/// the threads finish).
pub const EXR_ENCODING: exr::image::Encoding = exr::image::Encoding {
    line_order: exr::meta::attribute::LineOrder::Increasing,
    ..exr::image::Encoding::FAST_LOSSLESS
};

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

/// Runs `write` on a temporary file beside `path`, flushes it to disk, and renames it to `path`;
/// on failure the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let tmp = {
        // Two threads writing one path (the Python package releases the GIL) each get their
        // own temporary file.
        let mut in_use = lock_temporaries();
        let (mut n, mut tmp) = (0, temporary_path(path, 0));
        while in_use.contains(&tmp) {
            n += 1;
            tmp = temporary_path(path, n);
        }
        in_use.push(tmp.clone());
        tmp
    };
    let result = (|| {
        let file =
            File::create(&tmp).with_context(|| format!("cannot create {}", tmp.display()))?;
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        let file = out.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot move {} into place", tmp.display()))?;
        // The rename itself reaches the disk only with the folder (for power cuts).
        #[cfg(unix)]
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            File::open(dir).and_then(|d| d.sync_all()).ok();
        }
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    lock_temporaries().retain(|t| *t != tmp);
    result
}

/// Temporary files being written, for [`remove_temporaries`]. Global because the Ctrl-C
/// handler, which runs on its own thread with nothing passed in, must find them.
static TEMPORARIES: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn lock_temporaries() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes the temporary files of writes still under way: for a process about to exit in the
/// middle of them (a second Ctrl-C), so that it leaves no `.tmp-PID` files behind.
pub fn remove_temporaries() {
    for tmp in lock_temporaries().drain(..) {
        let _ = std::fs::remove_file(tmp);
    }
}

/// Checks that `path`'s folder exists and takes new files (by creating and removing a probe).
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        bail!(
            "cannot write {}: the folder {} does not exist",
            path.display(),
            dir.display()
        );
    }
    let probe = dir.join(format!(".lucent-probe-{}", std::process::id()));
    File::create(&probe).with_context(|| {
        format!(
            "cannot write {}: the folder {} does not take new files",
            path.display(),
            dir.display()
        )
    })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

fn temporary_path(path: &Path, n: u32) -> PathBuf {
    let mut name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(format!(".tmp-{}", std::process::id()));
    if n > 0 {
        name.push(format!("-{n}"));
    }
    path.with_file_name(name)
}

/// The samples per pixel the film holds, as metadata says it.
fn samples_text(film: &Film) -> String {
    match film.sample_range() {
        (a, b) if a == b => a.to_string(),
        (a, b) => format!("{a}..{b}"),
    }
}

/// Writes the corners each pixel of an adaptive render used as a grey PNG: black for the 4 of
/// an unsplit pixel, white for a pixel split at every level down to `depth`.
pub fn write_density_map(
    density: &[u32],
    width: u32,
    height: u32,
    depth: u32,
    path: &Path,
) -> anyhow::Result<()> {
    let full = lucent::schedule::adaptive::corners_fully_split(depth);
    let span = (full - 4).max(1) as f64;
    let grey: Vec<u8> = density
        .iter()
        .map(|&n| {
            ((u64::from(n).saturating_sub(4)) as f64 / span * 255.0)
                .round()
                .min(255.0) as u8
        })
        .collect();
    write_atomically(path, |out| {
        let mut encoder = png::Encoder::new(&mut *out, width, height);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&grey)?;
        writer.finish()?;
        Ok(())
    })
}

/// Writes `film` to `path` as `format`, atomically, its values shown as lucent's linear
/// light.
pub fn write_image(film: &Film, path: &Path, format: ImageFormat) -> anyhow::Result<()> {
    write_image_as(film, path, format, Display::Srgb)
}

/// [`write_image`] of a film whose values are shown as `display` says (a POV-Ray scene's
/// gamma).
pub fn write_image_as(
    film: &Film,
    path: &Path,
    format: ImageFormat,
    display: Display,
) -> anyhow::Result<()> {
    write_atomically(path, |out| encode_image_as(film, format, display, out))
}

/// The file `write_image` writes, into `out` (the Python package's inline PNGs are these bytes).
pub fn encode_image(
    film: &Film,
    format: ImageFormat,
    out: &mut (impl Write + std::io::Seek),
) -> anyhow::Result<()> {
    encode_image_as(film, format, Display::Srgb, out)
}

/// [`encode_image`] with the film's values shown as `display` says: the PNG's bytes encoded
/// so, the EXR's values turned into linear light.
pub fn encode_image_as(
    film: &Film,
    format: ImageFormat,
    display: Display,
    out: &mut (impl Write + std::io::Seek),
) -> anyhow::Result<()> {
    let (w, h) = (film.width(), film.height());
    let samples = samples_text(film);
    match format {
        ImageFormat::Png => {
            let mut encoder = png::Encoder::new(&mut *out, w, h);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            // fdeflate: a 2400×1800 render's PNG in a fraction of the default's time.
            encoder.set_compression(png::Compression::Fast);
            encoder.add_text_chunk("lucent.samples".into(), samples.clone())?;
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&film.to_8bit(display))?;
            writer.finish()?;
            Ok(())
        }
        ImageFormat::Exr => {
            use exr::prelude::*;
            let pixels: Vec<[f32; 3]> = film
                .to_linear_rgb()
                .into_iter()
                .map(|p| p.map(|v| display.linear(v)))
                .collect();
            let channel = |name: &str, c: usize| {
                AnyChannel::new(
                    name,
                    FlatSamples::F32(pixels.iter().map(|p| p[c]).collect()),
                )
            };
            let channels = AnyChannels::sort(SmallVec::from_vec(vec![
                channel("R", 0),
                channel("G", 1),
                channel("B", 2),
            ]));
            let mut attributes = LayerAttributes::named("lucent");
            attributes.other.insert(
                Text::new_or_panic("lucent.samples"),
                AttributeValue::Text(Text::new_or_panic(samples.clone())),
            );
            let image = Image::from_layer(Layer::new(
                (w as usize, h as usize),
                attributes,
                EXR_ENCODING,
                channels,
            ));
            image
                .write()
                .to_buffered(&mut *out)
                .map_err(|e| anyhow!("{e}"))
        }
        ImageFormat::Pfm => Ok(write_pfm(out, w, h, &film.to_linear_rgb())?),
    }
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
