//! Partial films and checkpoints: a film's raw sums, weights and sample counts in an OpenEXR
//! file, with what it belongs to in the header.
//!
//! Channels: `sum.R`, `sum.G`, `sum.B` and `weight` (32-bit float), `samples` (32-bit
//! unsigned). Header attributes (text, prefixed `lucent.`): `fingerprint` (scene inputs and
//! settings), `shard` (`I/N`), `spp`, `scene` (the scene file, empty for the built-in one),
//! `overrides` (the command line's settings), `output` (where the final image goes), and
//! `checksum` (of the pixel data, so a damaged file is refused rather than resumed). The same
//! format serves shards (`--shard`, merged by `lucent merge`) and checkpoints (`--resume`).

use anyhow::{Context, anyhow, bail};
use exr::prelude::*;
use lucent::film::{Film, FilmData};
use lucent::render::Shard;
use lucent_scene::{Limit, Limits};
use std::path::Path;

/// What a film file belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilmMeta {
    /// Fingerprint of the scene's inputs and the settings that shape the image.
    pub fingerprint: String,
    /// The share of the work it holds.
    pub shard: Shard,
    /// Samples per pixel of the finished render.
    pub spp: u32,
    /// Side of the tiles, in pixels: the unit shards are made of.
    pub tile: u32,
    /// The scene file, or empty for the built-in default scene.
    pub scene: String,
    /// The command line's settings, as `key=value` pairs separated by `;`.
    pub overrides: String,
    /// Where the final image goes.
    pub output: String,
}

impl FilmMeta {
    /// Each header attribute's name (after `lucent.`) and value.
    fn fields(&self) -> [(&'static str, String); 7] {
        [
            ("fingerprint", self.fingerprint.clone()),
            (
                "shard",
                format!("{}/{}", self.shard.index, self.shard.count),
            ),
            ("spp", self.spp.to_string()),
            ("tile", self.tile.to_string()),
            ("scene", self.scene.clone()),
            ("overrides", self.overrides.clone()),
            ("output", self.output.clone()),
        ]
    }
}

/// Bytes outside printable ASCII (and `%`) as `%XX`: EXR text attributes hold Latin-1 only.
fn escape(s: &str) -> String {
    s.bytes()
        .map(|b| {
            if (0x20..0x7f).contains(&b) && b != b'%' {
                (b as char).to_string()
            } else {
                format!("%{b:02X}")
            }
        })
        .collect()
}

fn unescape(s: &str) -> Option<String> {
    let mut out = Vec::new();
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            out.push(u8::from_str_radix(s.get(i + 1..i + 3)?, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Hex fingerprint of every bit of the film's data.
fn checksum(data: &FilmData) -> String {
    let mut f = lucent_scene::hash::Fingerprint::default();
    f.add(&data.width.to_le_bytes());
    f.add(&data.height.to_le_bytes());
    for v in data.sums.iter().flatten().chain(&data.weights) {
        f.add_raw(&v.to_le_bytes());
    }
    for v in &data.samples {
        f.add_raw(&v.to_le_bytes());
    }
    format!("{:016x}", f.value())
}

/// Writes `film` and `meta` to `path` (atomically: a temporary file, then a rename).
pub fn write_film(path: &Path, film: &Film, meta: &FilmMeta) -> anyhow::Result<()> {
    let mut data = film.to_data();
    // Sums that overflowed (inputs near f32::MAX) are stored clamped to the largest float (NaN
    // as 0), so that the film reads back, merges and resumes instead of being taken for a
    // damaged file.
    for v in data.sums.iter_mut().flatten() {
        *v = if v.is_nan() {
            0.0
        } else {
            v.clamp(-f32::MAX, f32::MAX)
        };
    }
    let size = (data.width as usize, data.height as usize);
    let channel = |name: &str, f: &dyn Fn(usize) -> f32| {
        AnyChannel::new(
            name,
            FlatSamples::F32((0..data.weights.len()).map(f).collect()),
        )
    };
    let channels = AnyChannels::sort(SmallVec::from_vec(vec![
        channel("sum.R", &|i| data.sums[i][0]),
        channel("sum.G", &|i| data.sums[i][1]),
        channel("sum.B", &|i| data.sums[i][2]),
        channel("weight", &|i| data.weights[i]),
        AnyChannel::new("samples", FlatSamples::U32(data.samples.clone())),
    ]));
    let mut attributes = LayerAttributes::named("lucent film");
    for (key, value) in meta.fields() {
        let text =
            Text::new_or_none(escape(&value)).ok_or_else(|| anyhow!("cannot store `{value}`"))?;
        attributes.other.insert(
            Text::new_or_panic(format!("lucent.{key}")),
            AttributeValue::Text(text),
        );
    }
    let sum = Text::new_or_panic(checksum(&data));
    attributes.other.insert(
        Text::new_or_panic("lucent.checksum"),
        AttributeValue::Text(sum),
    );
    let image = Image::from_layer(Layer::new(
        size,
        attributes,
        crate::output::EXR_ENCODING,
        channels,
    ));
    crate::output::write_atomically(path, |file| {
        image.write().to_buffered(file).map_err(|e| anyhow!("{e}"))
    })
}

/// The channels of a film file, and their sample types.
const CHANNELS: [(&str, exr::meta::attribute::SampleType); 5] = {
    use exr::meta::attribute::SampleType::{F32, U32};
    [
        ("samples", U32),
        ("sum.B", F32),
        ("sum.G", F32),
        ("sum.R", F32),
        ("weight", F32),
    ]
};

/// Bytes of pixel data a film file holds per pixel: its five 32-bit channels.
const BYTES_PER_PIXEL: u64 = 20;

/// The header, checked before any pixel is read: one layer of a size lucent renders and the
/// `film` budget allows, with the film's channels — so that a hostile file cannot make the
/// reader allocate gigabytes.
fn check_header(path: &Path, limits: &Limits) -> anyhow::Result<exr::meta::MetaData> {
    let not_ours = |why: String| not_ours(path, &why);
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| anyhow!("{}: cannot read the film file: {e}", path.display()))?;
    let [header] = meta.headers.as_slice() else {
        return Err(not_ours(format!("{} layers", meta.headers.len())));
    };
    let (w, h) = (header.layer_size.0 as u64, header.layer_size.1 as u64);
    if w * h > lucent_scene::build::MAX_PIXELS
        || w > u64::from(lucent_scene::build::MAX_IMAGE_SIDE)
        || h > u64::from(lucent_scene::build::MAX_IMAGE_SIDE)
    {
        return Err(not_ours(format!(
            "{w}×{h} pixels, more than lucent renders"
        )));
    }
    // lucent writes one resolution level; the reader's handling of others is not for hostile
    // input (levels it does not ask for reach its sample buffers).
    if let exr::meta::BlockDescription::Tiles(t) = &header.blocks
        && t.level_mode != exr::meta::attribute::LevelMode::Singular
    {
        return Err(not_ours("several resolution levels".to_string()));
    }
    // A block (a tile or a band of scan lines) the header makes larger than the whole image
    // (or than one 64 × 64 tile, which lucent writes) is a lie: the reader would allocate
    // what each block claims before finding the bytes missing.
    let block = header.max_block_byte_size() as u64;
    if block > (w * h).max(64 * 64) * BYTES_PER_PIXEL {
        return Err(not_ours(format!(
            "blocks of {block} bytes in a {w}×{h} image"
        )));
    }
    let bytes = w * h * BYTES_PER_PIXEL;
    if bytes > limits.film_bytes {
        bail!(
            "{}: {}",
            path.display(),
            limits.exceeded(
                Limit::Film,
                format!(
                    "a {w}×{h} film holds {} MiB of pixel data",
                    bytes.div_ceil(1 << 20)
                )
            )
        );
    }
    let channels: Vec<(String, exr::meta::attribute::SampleType)> = header
        .channels
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_type))
        .collect();
    let want: Vec<(String, exr::meta::attribute::SampleType)> =
        CHANNELS.iter().map(|(n, t)| (n.to_string(), *t)).collect();
    if channels != want || header.deep {
        return Err(not_ours("other channels than a film's".to_string()));
    }
    Ok(meta)
}

/// The error for a file at `path` that is not a film, and why.
fn not_ours(path: &Path, why: &str) -> anyhow::Error {
    anyhow!(
        "{}: not a lucent partial film or checkpoint ({why})",
        path.display()
    )
}

/// The header attributes of a film file, read without its pixels: what a caller can check
/// before paying for them (a finished shard given to `--resume`).
pub fn read_meta(path: &Path, limits: &Limits) -> anyhow::Result<FilmMeta> {
    let meta = check_header(path, limits)?;
    meta_of(&meta.headers[0].own_attributes, path)
}

/// The `lucent.` attributes of a film's layer, checked.
fn meta_of(attributes: &LayerAttributes, path: &Path) -> anyhow::Result<FilmMeta> {
    let not_ours = |why: &str| not_ours(path, why);
    let attr = |key: &str| attribute(attributes, key, path);
    let shard = attr("shard")?;
    let (index, count) = shard
        .split_once('/')
        .ok_or_else(|| not_ours("a garbled shard"))?;
    let shard = Shard {
        index: index.parse().map_err(|_| not_ours("a garbled shard"))?,
        count: count.parse().map_err(|_| not_ours("a garbled shard"))?,
    };
    if shard.count == 0
        || shard.index >= shard.count
        || u64::from(shard.count) > lucent_scene::build::MAX_PIXELS
    {
        return Err(not_ours("a shard index out of range"));
    }
    Ok(FilmMeta {
        fingerprint: attr("fingerprint")?,
        shard,
        spp: attr("spp")?
            .parse()
            .map_err(|_| not_ours("a garbled spp"))?,
        tile: attr("tile")?
            .parse()
            .ok()
            .filter(|&t| t > 0)
            .ok_or_else(|| not_ours("a garbled tile size"))?,
        scene: attr("scene")?,
        overrides: attr("overrides")?,
        output: attr("output")?,
    })
}

/// The text attribute `lucent.{key}` of a film's layer.
fn attribute(attributes: &LayerAttributes, key: &str, path: &Path) -> anyhow::Result<String> {
    let not_ours = |why: &str| not_ours(path, why);
    match attributes
        .other
        .get(&Text::new_or_panic(format!("lucent.{key}")))
    {
        Some(AttributeValue::Text(t)) => {
            unescape(&t.to_string()).ok_or_else(|| not_ours(&format!("a garbled `{key}`")))
        }
        _ => Err(not_ours(&format!("no `lucent.{key}` attribute"))),
    }
}

/// Reads a film file written by [`write_film`], checking that it is one.
pub fn read_film(path: &Path, limits: &Limits) -> anyhow::Result<(Film, FilmMeta)> {
    let not_ours = |why: &str| not_ours(path, why);
    check_header(path, limits)?;
    // The `exr` crate's own consistency checks can panic on a crafted file (a block of another
    // resolution level than its header's, found by the `film` fuzz target): such a file is
    // refused like any other that cannot be read.
    let decoded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
    }))
    .map_err(|_| {
        anyhow!(
            "{}: cannot read the film file: its blocks are inconsistent",
            path.display()
        )
    })?;
    let image =
        decoded.map_err(|e| anyhow!("{}: cannot read the film file: {e}", path.display()))?;
    let layer = &image.layer_data;
    let meta = meta_of(&layer.attributes, path)?;
    let find = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == Text::new_or_panic(name))
    };
    let floats = |name: &str| -> anyhow::Result<Vec<f32>> {
        match find(name).map(|c| &c.sample_data) {
            Some(FlatSamples::F32(v)) => Ok(v.clone()),
            _ => Err(not_ours(&format!("no float channel `{name}`"))),
        }
    };
    let (r, g, b, weights) = (
        floats("sum.R")?,
        floats("sum.G")?,
        floats("sum.B")?,
        floats("weight")?,
    );
    let samples = match find("samples").map(|c| &c.sample_data) {
        Some(FlatSamples::U32(v)) => v.clone(),
        _ => return Err(not_ours("no `samples` channel")),
    };
    let size = layer.size;
    let data = FilmData {
        width: u32::try_from(size.0).context("width")?,
        height: u32::try_from(size.1).context("height")?,
        sums: r
            .iter()
            .zip(&g)
            .zip(&b)
            .map(|((r, g), b)| [*r, *g, *b])
            .collect(),
        weights,
        samples,
    };
    if attribute(&layer.attributes, "checksum", path)? != checksum(&data) {
        bail!(
            "{}: corrupted: the pixel data does not match its checksum",
            path.display()
        );
    }
    if data.samples.iter().any(|&s| s > meta.spp) {
        bail!(
            "{}: corrupted: a pixel has more samples than the render's {}",
            path.display(),
            meta.spp
        );
    }
    if data.weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
        || data.sums.iter().flatten().any(|v| !v.is_finite())
    {
        bail!(
            "{}: corrupted: sums or weights that are not finite",
            path.display()
        );
    }
    let film = Film::from_data(data).ok_or_else(|| not_ours("channels of different sizes"))?;
    Ok((film, meta))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping_round_trips() {
        for s in ["plain", "a%b", "ünïcode/€", ""] {
            assert_eq!(unescape(&escape(s)).as_deref(), Some(s));
        }
        assert!(escape("€").is_ascii());
    }

    #[test]
    fn films_round_trip_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.exr");
        let mut film = Film::new(3, 2);
        film.add_sample(1, 1, Some(lucent::Rgb::new(0.1, 1e-20, 3.5e10)), 1.0);
        film.add_sample(1, 1, None, 1.0);
        let meta = FilmMeta {
            fingerprint: "abc".into(),
            shard: Shard { index: 1, count: 3 },
            spp: 4,
            tile: 16,
            scene: "scènes/x.toml".into(),
            overrides: "spp=4;width=3".into(),
            output: "out.png".into(),
        };
        write_film(&path, &film, &meta).unwrap();
        let (back, back_meta) = read_film(&path, &Limits::default()).unwrap();
        assert_eq!(back, film);
        assert_eq!(back_meta, meta);
        // A sum that overflowed is stored clamped to the largest float: it reads back, finite.
        film.add_sample(0, 0, Some(lucent::Rgb::gray(3e38)), 1.0);
        film.add_sample(0, 0, Some(lucent::Rgb::gray(3e38)), 1.0);
        assert_eq!(film.overflowed_pixels(), 1);
        write_film(&path, &film, &meta).unwrap();
        let (back, _) = read_film(&path, &Limits::default()).unwrap();
        assert_eq!(back.overflowed_pixels(), 0);
        assert!(back.pixel(0, 0).r >= 1e38 && back.pixel(0, 0).is_finite());
    }

    #[test]
    fn films_the_exr_reader_cannot_take_safely_are_refused() {
        // Found by the `film` fuzz target: a 20 × 12 film whose header gives tiles the reader
        // would have allocated 1.9 GB for, each.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fuzz/seeds/film/oom-tile-claims-1.9-gb.exr");
        let limits = Limits::default();
        let Err(e) = read_film(&path, &limits) else {
            panic!("a film of 1.9 GB blocks was read");
        };
        let e = e.to_string();
        assert!(
            e.contains("not a lucent partial film or checkpoint (blocks of"),
            "{e}"
        );
        assert!(read_meta(&path, &limits).is_err());
        // Found next: a block that says it is of another resolution level than the header's
        // one, which the reader's consistency checks panic on (with debug assertions) or
        // whose samples fail the checksum (without).
        let path = path.with_file_name("crash-resolution-levels.exr");
        let Err(e) = read_film(&path, &limits) else {
            panic!("a film with a block of another resolution level was read");
        };
        assert!(e.to_string().contains("crash-resolution-levels.exr"), "{e}");
    }
}
