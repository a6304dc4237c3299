//! A reader of Mitsuba's `serialized` meshes, the compressed triangle meshes of Mitsuba 0.x to 3
//! (the `serialized` shape; `matpreview.serialized` of Mitsuba's documentation scenes).
//!
//! ```toml
//! [[object]]
//! kind = "mesh"
//! file = "meshes/matpreview.serialized"
//! part = "2"          # the shape index, from 0 (the default)
//! ```
//!
//! ## The format
//!
//! Little-endian throughout. A file is a run of shapes, then a dictionary:
//!
//! | bytes | what |
//! | --- | --- |
//! | `u16`, `u16` | each shape begins with the format id `0x041C` and the version, 3 or 4 |
//! | zlib stream | the shape (below), deflated |
//! | … | the next shapes, each with its own id, version and stream |
//! | `u64` × n (version 4), `u32` × n (version 3) | the file offset of each shape (the first is 0) |
//! | `u32` | n, the number of shapes |
//!
//! A shape, inflated: a `u32` of flags (`0x1` vertex normals, `0x2` texture coordinates, `0x8`
//! vertex colours, `0x10` face normals, `0x1000` single and `0x2000` double precision); in
//! version 4 the shape's name, UTF-8 ending in a zero byte; the vertex count and the triangle
//! count (`u64` each); then positions (x, y, z per vertex), normals, texture coordinates (u, v)
//! and colours (r, g, b) when flagged, as `f32` or `f64`; then the triangles, three `u32`
//! vertex indices each (`u64` above 2³² vertices, beyond what lucent stores).
//!
//! As Mitsuba 3 reads them: texture coordinates are kept as written (`v` runs down the image,
//! lucent's convention and Mitsuba's, unlike OBJ's), normals are normalised, and the face-normals
//! flag is read past (Mitsuba 3 ignores it; the shape's `face_normals` asks for them). Colours
//! are linear RGB (Mitsuba kept them as its linear spectra); Mitsuba 3 skips them, lucent keeps
//! them for a material with `vertex_colors`.
//!
//! ## Sizes are claims
//!
//! Every size in the file is checked before it is used. The shape count must fit the file, the
//! dictionary's offsets must start at 0, increase, and lie before the dictionary, and each shape
//! must start with the file's id and version. A shape's vertex and triangle counts must fit
//! the scene's geometry budget (`Limits::geometry` vertices and triangles) and their arrays must be bytes that
//! its compressed stream may inflate to ([`MAX_RATIO`]) before a byte of the arrays is read.
//! The stream is then inflated [`CHUNK`] bytes at a time, the arrays grow only as their bytes
//! arrive, and inflating stops at the bytes the counts need: whatever follows is never inflated.
//! A stream that inflates more than [`MAX_RATIO`] times the compressed bytes it has used (past
//! the first [`RATIO_FREE`] bytes) is refused as a zip bomb. Indices must name a vertex, and
//! every number must be finite in single precision.

use crate::error::LoadError;
use crate::limits::{Limit, Limits};
use flate2::{Decompress, FlushDecompress, Status};
use glam::{Vec2, Vec3};
use lucent::Rgb;
use lucent::shape::Mesh;
use std::path::Path;

/// The format id every shape of a file starts with.
pub const FORMAT_ID: u16 = 0x041C;

/// The versions read: 3 (offsets of 32 bits, unnamed shapes) and 4 (offsets of 64 bits, a name
/// per shape), the only ones Mitsuba 3 reads.
pub const VERSIONS: [u16; 2] = [3, 4];

/// Most times a shape's inflated bytes may outnumber the compressed bytes they came from.
/// Deflate's own ceiling is 1032 (runs of one byte); meshes compress 1.5 to 4 times (the low
/// bits of floats and indices are nearly random), and a mesh of constant normals and colours
/// still below 25. Only a stream of runs — a zip bomb, or a mesh whose vertices all coincide —
/// inflates further.
pub const MAX_RATIO: u64 = 256;

/// Inflated bytes below which [`MAX_RATIO`] does not apply: a small mesh may compress well
/// (a few vertices at round coordinates) and costs little whatever it claims.
pub const RATIO_FREE: u64 = 16 << 20;

/// The bytes inflated at a time: the most inflated beyond what a shape's counts need.
pub const CHUNK: usize = 64 << 10;

/// Longest shape name read (version 4), terminating zero included.
pub const MAX_NAME: usize = 4096;

/// The fewest bytes a shape takes in the file: its id and version, and a zlib header.
const MIN_SHAPE: u64 = 6;

/// Elements reserved ahead of their bytes: arrays grow past this only as their data arrives.
const RESERVE: u64 = 1 << 16;

const HAS_NORMALS: u32 = 0x0001;
const HAS_UVS: u32 = 0x0002;
const HAS_TANGENTS: u32 = 0x0004;
const HAS_COLORS: u32 = 0x0008;
const FACE_NORMALS: u32 = 0x0010;
const SINGLE: u32 = 0x1000;
const DOUBLE: u32 = 0x2000;
const KNOWN: u32 =
    HAS_NORMALS | HAS_UVS | HAS_TANGENTS | HAS_COLORS | FACE_NORMALS | SINGLE | DOUBLE;

/// One shape of a serialized file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shape {
    /// Its name (version 4; empty in version 3).
    pub name: String,
    /// Its triangles, with normals, texture coordinates and colours where the file has them.
    pub mesh: Mesh,
}

/// Reads shape `index` of the serialized file at `path`.
pub fn read_serialized(path: &Path, index: u32) -> Result<Shape, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    parse_serialized(&bytes, index, path)
}

/// The shape index a mesh object's `part` names: `None` is shape 0, else a decimal number.
pub fn shape_index(part: Option<&str>, path: &Path) -> Result<u32, LoadError> {
    let Some(part) = part else { return Ok(0) };
    if part.is_empty() || !part.bytes().all(|b| b.is_ascii_digit()) {
        return Err(LoadError::file(
            path,
            format!(
                "part `{part}` is not a shape index: the parts of a serialized file are its shapes, numbered from 0"
            ),
        ));
    }
    part.parse()
        .map_err(|_| LoadError::file(path, format!("shape index {part} is out of range")))
}

/// The number of shapes in serialized bytes, after checking the header and the dictionary.
pub fn shape_count(bytes: &[u8], path: &Path) -> Result<u32, LoadError> {
    Ok(Dictionary::read(bytes, path)?.count)
}

/// Parses shape `index` of serialized bytes; `path` names them in errors.
pub fn parse_serialized(bytes: &[u8], index: u32, path: &Path) -> Result<Shape, LoadError> {
    parse_serialized_within(bytes, index, path, &Limits::DEFAULT)
}

/// [`parse_serialized`] with a shape's vertices and triangles held, from its counts, to
/// `limits.geometry` (what the scene's budget has left).
pub fn parse_serialized_within(
    bytes: &[u8],
    index: u32,
    path: &Path,
    limits: &Limits,
) -> Result<Shape, LoadError> {
    decode(bytes, index, path, limits, &mut 0)
}

/// [`parse_serialized_within`], adding the bytes inflated to `inflated` (for the tests'
/// bounds).
fn decode(
    bytes: &[u8],
    index: u32,
    path: &Path,
    limits: &Limits,
    inflated: &mut u64,
) -> Result<Shape, LoadError> {
    let dictionary = Dictionary::read(bytes, path)?;
    let stream = dictionary.stream(bytes, index, path)?;
    let mut z = Inflater::new(stream, path, index);
    let shape = read_shape(&mut z, dictionary.version, limits);
    *inflated += z.z.total_out();
    shape
}

/// The file's header and end-of-file dictionary, checked.
struct Dictionary {
    version: u16,
    count: u32,
    /// Where the dictionary starts: the end of the last shape.
    start: u64,
}

impl Dictionary {
    fn read(bytes: &[u8], path: &Path) -> Result<Self, LoadError> {
        let err = |message: String| LoadError::file(path, message);
        let len = bytes.len() as u64;
        if len < 8 {
            return Err(err(format!(
                "not a Mitsuba serialized file: {len} bytes, too few for a header and a shape count"
            )));
        }
        let id = u16_at(bytes, 0);
        if id != FORMAT_ID {
            return Err(err(format!(
                "not a Mitsuba serialized file: it starts with {id:#06x}, not the format id {FORMAT_ID:#06x}"
            )));
        }
        let version = u16_at(bytes, 2);
        if !VERSIONS.contains(&version) {
            return Err(err(format!(
                "serialized format version {version} is not read (lucent reads versions 3 and 4)"
            )));
        }
        let count = u32_at(bytes, bytes.len() - 4);
        if count == 0 {
            return Err(err(
                "the dictionary at the end of the file says it holds no shapes".into(),
            ));
        }
        // Each shape takes its header and an offset at the least: a count the file cannot hold
        // is refused before anything is read from the dictionary.
        let width = offset_width(version);
        if u64::from(count) * (MIN_SHAPE + width) + 4 > len {
            return Err(err(format!(
                "the dictionary claims {count} shapes, more than the file's {len} bytes can hold"
            )));
        }
        let start = len - 4 - u64::from(count) * width;
        let dictionary = Self {
            version,
            count,
            start,
        };
        let mut previous = None;
        for i in 0..count {
            let offset = dictionary.offset(bytes, i);
            let check = match previous {
                None if offset != 0 => Err(format!("shape 0 starts at byte {offset}, not 0")),
                Some((p, at)) if offset < at + MIN_SHAPE => Err(format!(
                    "shape {i} starts at byte {offset}, not past shape {p} (at byte {at})"
                )),
                _ if offset.saturating_add(MIN_SHAPE) > start => Err(format!(
                    "shape {i} starts at byte {offset}, past the end of the shapes (byte {start}, where the dictionary begins)"
                )),
                _ => Ok(()),
            };
            check.map_err(|why| err(format!("the dictionary lies: {why}")))?;
            previous = Some((i, offset));
        }
        Ok(dictionary)
    }

    /// The offset of shape `i` (< `count`) as the dictionary gives it.
    fn offset(&self, bytes: &[u8], i: u32) -> u64 {
        let at = (self.start + u64::from(i) * offset_width(self.version)) as usize;
        match self.version {
            3 => u64::from(u32_at(bytes, at)),
            _ => u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")),
        }
    }

    /// The compressed stream of shape `index`, after its header is checked.
    fn stream<'b>(&self, bytes: &'b [u8], index: u32, path: &Path) -> Result<&'b [u8], LoadError> {
        if index >= self.count {
            let last = self.count - 1;
            return Err(LoadError::file(
                path,
                format!(
                    "shape index {index} is out of range: the file holds {} shape{} (0 to {last})",
                    self.count,
                    if self.count == 1 { "" } else { "s" }
                ),
            ));
        }
        // Offsets were checked to increase and to end before the dictionary.
        let begin = self.offset(bytes, index) as usize;
        let end = if index + 1 < self.count {
            self.offset(bytes, index + 1)
        } else {
            self.start
        } as usize;
        let (id, version) = (u16_at(bytes, begin), u16_at(bytes, begin + 2));
        if (id, version) != (FORMAT_ID, self.version) {
            return Err(LoadError::file(
                path,
                format!(
                    "shape {index}: its header ({id:#06x}, version {version}) is not the file's ({FORMAT_ID:#06x}, version {})",
                    self.version
                ),
            ));
        }
        Ok(&bytes[begin + 4..end])
    }
}

fn offset_width(version: u16) -> u64 {
    if version == 3 { 4 } else { 8 }
}

fn u16_at(bytes: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([bytes[at], bytes[at + 1]])
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"))
}

/// The shape in the inflater's stream.
fn read_shape(z: &mut Inflater, version: u16, limits: &Limits) -> Result<Shape, LoadError> {
    let flags = u32::from_le_bytes(z.take("the flags")?);
    if flags & !KNOWN != 0 {
        return Err(z.error(format!(
            "unknown flags {:#06x} (lucent reads {KNOWN:#06x})",
            flags & !KNOWN
        )));
    }
    if flags & HAS_TANGENTS != 0 {
        return Err(z.error(
            "flag 0x0004 (tangents) is set, but the format defines no tangent data".into(),
        ));
    }
    if flags & SINGLE != 0 && flags & DOUBLE != 0 {
        return Err(z.error("the flags ask for both single and double precision".into()));
    }
    // Mitsuba reads single precision unless the double flag is set.
    let double = flags & DOUBLE != 0;
    let name = if version == 4 {
        z.name()?
    } else {
        String::new()
    };
    let vertices = u64::from_le_bytes(z.take("the vertex count")?);
    let triangles = u64::from_le_bytes(z.take("the triangle count")?);
    if vertices.saturating_add(triangles) > limits.geometry {
        return Err(z.error(limits.exceeded(
            Limit::Geometry,
            format!("it claims {vertices} vertices and {triangles} triangles"),
        )));
    }
    let has = |flag: u32| flags & flag != 0;
    let floats = 3
        + 3 * u64::from(has(HAS_NORMALS))
        + 2 * u64::from(has(HAS_UVS))
        + 3 * u64::from(has(HAS_COLORS));
    let size = if double { 8 } else { 4 };
    // Within the budget, so no product overflows.
    let need = vertices * floats * size + triangles * 12;
    z.check_claim(need)?;

    let positions = z.attribute::<3>(vertices, double, ("the positions", "position"))?;
    let mut normals = Vec::new();
    if has(HAS_NORMALS) {
        normals = z.attribute::<3>(vertices, double, ("the normals", "normal"))?;
    }
    let mut uvs = Vec::new();
    if has(HAS_UVS) {
        uvs = z.attribute::<2>(
            vertices,
            double,
            ("the texture coordinates", "texture coordinate"),
        )?;
    }
    let mut colors = Vec::new();
    if has(HAS_COLORS) {
        colors = z.attribute::<3>(vertices, double, ("the vertex colours", "colour"))?;
    }
    let mut tris = Vec::with_capacity(triangles.min(RESERVE) as usize);
    for t in 0..triangles {
        let b: [u8; 12] = z.take("the triangles")?;
        let tri = [0, 4, 8].map(|k| u32::from_le_bytes(b[k..k + 4].try_into().expect("4 bytes")));
        if let Some(v) = tri.iter().find(|&&v| u64::from(v) >= vertices) {
            return Err(z.error(format!(
                "triangle {t} uses vertex {v}, but there are {vertices} vertices"
            )));
        }
        tris.push(tri);
    }
    let mut mesh = Mesh::new(positions.into_iter().map(Vec3::from_array).collect(), tris);
    mesh.normals = normals
        .into_iter()
        .map(|n| unit(Vec3::from_array(n)))
        .collect();
    mesh.uvs = uvs.into_iter().map(Vec2::from_array).collect();
    mesh.colors = colors.into_iter().map(Rgb::from).collect();
    Ok(Shape { name, mesh })
}

/// `n` scaled to unit length, or zero for a zero vector. Scaled by its largest component first:
/// the squares of a tiny normal (1e-22) fall among the denormals, whose few bits of precision
/// would leave `normalize` several percent off unit length.
fn unit(n: Vec3) -> Vec3 {
    let largest = n.abs().max_element();
    if largest > 0.0 {
        (n / largest).normalize()
    } else {
        Vec3::ZERO
    }
}

/// A shape's zlib stream, inflated [`CHUNK`] bytes at a time as its reader asks for bytes.
struct Inflater<'a> {
    input: &'a [u8],
    z: Decompress,
    buf: Vec<u8>,
    /// The unread inflated bytes are `buf[pos..len]`.
    pos: usize,
    len: usize,
    ended: bool,
    path: &'a Path,
    index: u32,
}

impl<'a> Inflater<'a> {
    fn new(input: &'a [u8], path: &'a Path, index: u32) -> Self {
        Self {
            input,
            z: Decompress::new(true),
            buf: vec![0; CHUNK],
            pos: 0,
            len: 0,
            ended: false,
            path,
            index,
        }
    }

    /// An error about this shape.
    fn error(&self, message: String) -> LoadError {
        LoadError::file(self.path, format!("shape {}: {message}", self.index))
    }

    /// The most bytes `compressed` bytes may inflate to here.
    fn inflatable(compressed: u64) -> u64 {
        RATIO_FREE.max(compressed.saturating_mul(MAX_RATIO))
    }

    /// Refuses `need` more bytes of arrays that the rest of the stream cannot plausibly hold.
    fn check_claim(&self, need: u64) -> Result<(), LoadError> {
        let total = self.z.total_out() - (self.len - self.pos) as u64 + need;
        let limit = Self::inflatable(self.input.len() as u64);
        if total > limit {
            return Err(self.error(format!(
                "its counts need {total} inflated bytes, more than its {} compressed bytes may inflate to ({limit}: lucent allows {MAX_RATIO} times as many, or {} MiB, against zip bombs)",
                self.input.len(),
                RATIO_FREE >> 20
            )));
        }
        Ok(())
    }

    /// Inflates the next chunk into the buffer, which must have been read to its end.
    fn fill(&mut self, what: &str) -> Result<(), LoadError> {
        loop {
            if self.ended {
                return Err(self.error(format!(
                    "the compressed stream ends after {} bytes, in the middle of {what}",
                    self.z.total_out()
                )));
            }
            let used = self.z.total_in() as usize;
            let before = self.z.total_out();
            let status = self
                .z
                .decompress(&self.input[used..], &mut self.buf, FlushDecompress::None)
                .map_err(|e| {
                    self.error(format!("the compressed data is corrupt ({e}), in {what}"))
                })?;
            let made = (self.z.total_out() - before) as usize;
            let used_now = self.z.total_in() as usize - used;
            self.ended = status == Status::StreamEnd;
            let out = self.z.total_out();
            if out > Self::inflatable(self.z.total_in()) {
                return Err(self.error(format!(
                    "{} compressed bytes inflate to {out}, more than {MAX_RATIO} times as many: refused as a zip bomb",
                    self.z.total_in()
                )));
            }
            if made > 0 {
                (self.pos, self.len) = (0, made);
                return Ok(());
            }
            if self.ended {
                continue;
            }
            if self.z.total_in() as usize == self.input.len() {
                return Err(self.error(format!(
                    "the shape's bytes end in the middle of its compressed stream, in {what}"
                )));
            }
            if used_now == 0 {
                // Neither input used nor output made, with room for both: inflating is stuck.
                return Err(self.error(format!(
                    "the compressed stream makes no progress, in {what}"
                )));
            }
        }
    }

    /// The next `N` inflated bytes.
    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], LoadError> {
        let mut out = [0; N];
        let mut at = 0;
        while at < N {
            if self.pos == self.len {
                self.fill(what)?;
            }
            let n = (N - at).min(self.len - self.pos);
            out[at..at + n].copy_from_slice(&self.buf[self.pos..self.pos + n]);
            self.pos += n;
            at += n;
        }
        Ok(out)
    }

    /// The next `N` numbers, single or double precision, as `f32`.
    /// `vertices` elements of `N` numbers, each finite in single precision: `array` names them
    /// all in messages, `element` one of them.
    fn attribute<const N: usize>(
        &mut self,
        vertices: u64,
        double: bool,
        (array, element): (&str, &str),
    ) -> Result<Vec<[f32; N]>, LoadError> {
        let mut out = Vec::with_capacity(vertices.min(RESERVE) as usize);
        for i in 0..vertices {
            let v = self.floats::<N>(double, array)?;
            if !v.iter().all(|x| x.is_finite()) {
                return Err(self.error(format!(
                    "vertex {i}'s {element} {v:?} is not finite in single precision"
                )));
            }
            out.push(v);
        }
        Ok(out)
    }

    fn floats<const N: usize>(&mut self, double: bool, what: &str) -> Result<[f32; N], LoadError> {
        let mut out = [0.0; N];
        for x in &mut out {
            *x = if double {
                f64::from_le_bytes(self.take(what)?) as f32
            } else {
                f32::from_le_bytes(self.take(what)?)
            };
        }
        Ok(out)
    }

    /// The shape's name: bytes up to a zero.
    fn name(&mut self) -> Result<String, LoadError> {
        let mut name = Vec::new();
        loop {
            let [b] = self.take("the name")?;
            if b == 0 {
                return Ok(String::from_utf8_lossy(&name).into_owned());
            }
            if name.len() + 1 == MAX_NAME {
                return Err(self.error(format!(
                    "its name runs past {MAX_NAME} bytes without the zero that ends it"
                )));
            }
            name.push(b);
        }
    }
}

#[cfg(test)]
mod tests;
