//! A reader of Stanford PLY meshes: ASCII and binary (little- and big-endian), every property
//! type, faces of any arity (split into fans), and triangle strips (`tristrips`: −1 restarts a
//! strip, winding alternates, degenerate triangles are dropped).
//!
//! Vertex positions (`x`, `y`, `z`), and where present normals (`nx`, `ny`, `nz`) and colours
//! (`red`, `green`, `blue`, 0–255 integers or 0–1 floats) are kept; other elements and properties
//! are read past. A header is checked against the file's size before anything is allocated: a
//! header that claims more elements than the file can hold is refused.

use crate::error::LoadError;
use glam::Vec3;
use std::path::Path;

/// A mesh read from a PLY file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlyMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex normals, when the file has them.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex colours in [0, 1], when the file has them.
    pub colors: Option<Vec<[f32; 3]>>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Ascii,
    LittleEndian,
    BigEndian,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Debug)]
enum Property {
    Scalar {
        name: String,
        ty: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
}

impl Element {
    /// The fewest bytes one element can take in the body.
    fn min_size(&self, format: Format) -> u64 {
        self.props
            .iter()
            .map(|p| match (format, p) {
                // At least one character and one separator per value.
                (Format::Ascii, _) => 2,
                (_, Property::Scalar { ty, .. }) => ty.size() as u64,
                (_, Property::List { count, .. }) => count.size() as u64,
            })
            .sum()
    }
}

/// Reads the PLY file at `path`.
pub fn read_ply(path: &Path) -> Result<PlyMesh, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    parse_ply(&bytes, path)
}

/// Parses PLY bytes; `path` names them in errors.
pub fn parse_ply(bytes: &[u8], path: &Path) -> Result<PlyMesh, LoadError> {
    let (format, elements, body_start) = parse_header(bytes, path)?;
    let body = &bytes[body_start..];
    for e in &elements {
        // Checked before anything is allocated: a hostile header cannot ask for absurd memory.
        let need = e.count.saturating_mul(e.min_size(format));
        if need > body.len() as u64 {
            return Err(LoadError::file(
                path,
                format!(
                    "the header declares {} `{}` elements, more than the file's {} bytes of data can hold",
                    e.count,
                    e.name,
                    body.len()
                ),
            ));
        }
    }
    let mut reader = Reader {
        bytes: body,
        pos: 0,
        format,
        path,
        line: header_lines(bytes, body_start),
    };
    let mut mesh = PlyMesh::default();
    let mut vertex_count = None;
    for e in &elements {
        match e.name.as_str() {
            "vertex" => {
                read_vertices(&mut reader, e, &mut mesh)?;
                vertex_count = Some(mesh.positions.len());
            }
            "face" | "tristrips" => {
                let n = vertex_count.ok_or_else(|| {
                    LoadError::file(path, format!("`{}` comes before `vertex`", e.name))
                })?;
                read_polygons(&mut reader, e, n, &mut mesh)?;
            }
            _ => reader.skip_element(e)?,
        }
    }
    if vertex_count.is_none() {
        return Err(LoadError::file(path, "the file has no `vertex` element"));
    }
    Ok(mesh)
}

/// The number of lines before `offset` (the body's first line number is one more).
fn header_lines(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset].iter().filter(|&&b| b == b'\n').count()
}

fn parse_header(bytes: &[u8], path: &Path) -> Result<(Format, Vec<Element>, usize), LoadError> {
    const END: &[u8] = b"end_header";
    let end = bytes
        .windows(END.len())
        .position(|w| w == END)
        .ok_or_else(|| LoadError::file(path, "not a PLY file: no `end_header` line"))?;
    let mut body_start = end + END.len();
    // The header ends with a newline (`\n` or `\r\n`).
    if bytes.get(body_start) == Some(&b'\r') {
        body_start += 1;
    }
    if bytes.get(body_start) != Some(&b'\n') {
        return Err(LoadError::file(
            path,
            "`end_header` is not followed by a line break",
        ));
    }
    body_start += 1;
    let text = std::str::from_utf8(&bytes[..end])
        .map_err(|_| LoadError::file(path, "the PLY header is not text"))?;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let err = |msg: String| LoadError::line(path, line_no, msg);
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [] => {}
            ["ply"] if line_no == 1 => {}
            _ if line_no == 1 => {
                return Err(err("not a PLY file: the first line is not `ply`".into()));
            }
            ["format", f, _version] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::LittleEndian,
                    "binary_big_endian" => Format::BigEndian,
                    other => return Err(err(format!("unknown PLY format `{other}`"))),
                })
            }
            ["comment", ..] | ["obj_info", ..] => {}
            ["element", name, count] => {
                let count = count
                    .parse()
                    .map_err(|_| err(format!("element count `{count}` is not a number")))?;
                // A second `vertex` would replace the first's positions while the faces were
                // checked against the first's count (found by the ply fuzz target).
                if elements.iter().any(|e| e.name == *name) {
                    return Err(err(format!("a second `element {name}`")));
                }
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    props: vec![],
                });
            }
            ["property", "list", count, item, name] => {
                let e = elements
                    .last_mut()
                    .ok_or_else(|| err("a property before any element".into()))?;
                let ty = |s: &str| {
                    Scalar::parse(s).ok_or_else(|| err(format!("unknown property type `{s}`")))
                };
                let (count, item) = (ty(count)?, ty(item)?);
                if count.is_float() {
                    return Err(err("a list's count must be an integer type".into()));
                }
                e.props.push(Property::List {
                    name: name.to_string(),
                    count,
                    item,
                });
            }
            ["property", ty, name] => {
                let e = elements
                    .last_mut()
                    .ok_or_else(|| err("a property before any element".into()))?;
                let ty = Scalar::parse(ty)
                    .ok_or_else(|| err(format!("unknown property type `{ty}`")))?;
                e.props.push(Property::Scalar {
                    name: name.to_string(),
                    ty,
                });
            }
            _ => return Err(err(format!("cannot read this header line: `{line}`"))),
        }
    }
    let format =
        format.ok_or_else(|| LoadError::file(path, "the PLY header has no `format` line"))?;
    Ok((format, elements, body_start))
}

/// Reads values from the body, binary or ASCII.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    format: Format,
    path: &'a Path,
    /// ASCII: the line being read (1-based, counted in the whole file).
    line: usize,
}

impl Reader<'_> {
    fn truncated(&self, what: &str) -> LoadError {
        LoadError::file(
            self.path,
            format!("the file ends early, in the middle of {what}"),
        )
    }

    fn read(&mut self, ty: Scalar, what: &str) -> Result<f64, LoadError> {
        if self.format == Format::Ascii {
            return self.read_ascii(ty, what);
        }
        let n = ty.size();
        let b = self
            .bytes
            .get(self.pos..self.pos + n)
            .ok_or_else(|| self.truncated(what))?;
        self.pos += n;
        let le = self.format == Format::LittleEndian;
        macro_rules! num {
            ($t:ty) => {{
                let arr: [u8; size_of::<$t>()] = b.try_into().expect("length checked above");
                (if le {
                    <$t>::from_le_bytes(arr)
                } else {
                    <$t>::from_be_bytes(arr)
                }) as f64
            }};
        }
        Ok(match ty {
            Scalar::I8 => num!(i8),
            Scalar::U8 => num!(u8),
            Scalar::I16 => num!(i16),
            Scalar::U16 => num!(u16),
            Scalar::I32 => num!(i32),
            Scalar::U32 => num!(u32),
            Scalar::F32 => num!(f32),
            Scalar::F64 => num!(f64),
        })
    }

    fn read_ascii(&mut self, ty: Scalar, what: &str) -> Result<f64, LoadError> {
        while let Some(&c) = self.bytes.get(self.pos) {
            if !c.is_ascii_whitespace() {
                break;
            }
            if c == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        let start = self.skip_word();
        if start == self.pos {
            return Err(self.truncated(what));
        }
        let word = std::str::from_utf8(&self.bytes[start..self.pos]).unwrap_or("?");
        let value: f64 = word.parse().map_err(|_| {
            LoadError::line(
                self.path,
                self.line + 1,
                format!("`{word}` is not a number ({what})"),
            )
        })?;
        if !ty.is_float() && value.fract() != 0.0 {
            return Err(LoadError::line(
                self.path,
                self.line + 1,
                format!("`{word}` is not an integer ({what})"),
            ));
        }
        Ok(value)
    }

    /// ASCII: moves past the word at the position (none at whitespace); returns where it began.
    fn skip_word(&mut self) -> usize {
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|c| !c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        start
    }

    /// ASCII: the end of one element's line. PLY writes each element on a line of its own, so
    /// a value left over is an error (read on, it would shift every later value).
    fn end_row(&mut self, what: &str) -> Result<(), LoadError> {
        if self.format != Format::Ascii {
            return Ok(());
        }
        while let Some(&c) = self.bytes.get(self.pos) {
            match c {
                b'\n' | b'\r' => return Ok(()),
                c if c.is_ascii_whitespace() => self.pos += 1,
                _ => {
                    let start = self.skip_word();
                    let word = String::from_utf8_lossy(&self.bytes[start..self.pos]);
                    return Err(LoadError::line(
                        self.path,
                        self.line + 1,
                        format!("`{word}` is one value more than {what} has properties"),
                    ));
                }
            }
        }
        Ok(())
    }

    /// A list's length, checked against what is left of the file.
    fn list_len(&mut self, count: Scalar, item: Scalar, what: &str) -> Result<usize, LoadError> {
        let n = self.read(count, what)?;
        if !(0.0..=u32::MAX as f64).contains(&n) {
            return Err(LoadError::file(
                self.path,
                format!("a list length of {n} in {what}"),
            ));
        }
        let n = n as usize;
        let min = if self.format == Format::Ascii {
            2
        } else {
            item.size()
        };
        if n.saturating_mul(min) > self.bytes.len() - self.pos {
            return Err(self.truncated(what));
        }
        Ok(n)
    }

    fn skip_element(&mut self, e: &Element) -> Result<(), LoadError> {
        // An element without properties takes no bytes, so the size check lets any count
        // through: without this, `element junk 18446744073709551615` would loop 2^64 times
        // (unoptimised builds do not remove the empty loop).
        if e.props.is_empty() {
            return Ok(());
        }
        let what = format!("element `{}`", e.name);
        for _ in 0..e.count {
            for p in &e.props {
                match p {
                    Property::Scalar { ty, .. } => {
                        self.read(*ty, &what)?;
                    }
                    Property::List { count, item, .. } => {
                        for _ in 0..self.list_len(*count, *item, &what)? {
                            self.read(*item, &what)?;
                        }
                    }
                }
            }
            self.end_row(&what)?;
        }
        Ok(())
    }
}

fn read_vertices(r: &mut Reader, e: &Element, mesh: &mut PlyMesh) -> Result<(), LoadError> {
    let slot = |name: &str| {
        e.props
            .iter()
            .position(|p| matches!(p, Property::Scalar { name: n, .. } if n == name))
    };
    let [x, y, z] = ["x", "y", "z"].map(slot);
    let (Some(x), Some(y), Some(z)) = (x, y, z) else {
        return Err(LoadError::file(
            r.path,
            "the `vertex` element lacks an `x`, `y` or `z` property",
        ));
    };
    let normal = ["nx", "ny", "nz"].map(slot);
    let color = ["red", "green", "blue"].map(slot);
    let has_normals = normal.iter().all(Option::is_some);
    let has_colors = color.iter().all(Option::is_some);
    let n = e.count as usize;
    mesh.positions = Vec::with_capacity(n);
    let mut normals = Vec::with_capacity(if has_normals { n } else { 0 });
    let mut colors = Vec::with_capacity(if has_colors { n } else { 0 });
    let mut values = vec![0.0f64; e.props.len()];
    for i in 0..n {
        for (k, p) in e.props.iter().enumerate() {
            values[k] = match p {
                Property::Scalar { ty, .. } => r.read(*ty, "vertex data")?,
                Property::List { count, item, .. } => {
                    for _ in 0..r.list_len(*count, *item, "vertex data")? {
                        r.read(*item, "vertex data")?;
                    }
                    0.0
                }
            };
        }
        r.end_row("a vertex")?;
        let p = Vec3::new(values[x] as f32, values[y] as f32, values[z] as f32);
        if !p.is_finite() {
            return Err(LoadError::file(
                r.path,
                format!("vertex {i} has a coordinate that is not finite: {p}"),
            ));
        }
        mesh.positions.push(p);
        if has_normals {
            normals.push(Vec3::from_array(
                normal.map(|k| values[k.unwrap_or(0)] as f32),
            ));
        }
        if has_colors {
            colors.push(color.map(|k| {
                let k = k.unwrap_or(0);
                let v = values[k] as f32;
                let integer = matches!(&e.props[k], Property::Scalar { ty, .. } if !ty.is_float());
                if integer { v / 255.0 } else { v }
            }));
        }
    }
    mesh.normals = has_normals.then_some(normals);
    mesh.colors = has_colors.then_some(colors);
    Ok(())
}

/// Faces (fans) or triangle strips.
fn read_polygons(
    r: &mut Reader,
    e: &Element,
    vertices: usize,
    mesh: &mut PlyMesh,
) -> Result<(), LoadError> {
    let strips = e.name == "tristrips";
    let what = format!("element `{}`", e.name);
    let list = e
        .props
        .iter()
        .position(|p| matches!(p, Property::List { name, .. } if name == "vertex_indices" || name == "vertex_index"))
        .ok_or_else(|| LoadError::file(r.path, format!("`{}` has no `vertex_indices` list", e.name)))?;
    let mut indices: Vec<i64> = Vec::new();
    for i in 0..e.count {
        for (k, p) in e.props.iter().enumerate() {
            match p {
                Property::Scalar { ty, .. } => {
                    r.read(*ty, &what)?;
                }
                Property::List { count, item, .. } => {
                    let n = r.list_len(*count, *item, &what)?;
                    if k != list {
                        for _ in 0..n {
                            r.read(*item, &what)?;
                        }
                        continue;
                    }
                    indices.clear();
                    indices.reserve(n);
                    for _ in 0..n {
                        let v = r.read(*item, &what)? as i64;
                        let restart = strips && v == -1;
                        if !restart && !(0..vertices as i64).contains(&v) {
                            return Err(LoadError::file(
                                r.path,
                                format!(
                                    "{} {i} uses vertex {v}, but there are {vertices} vertices",
                                    if strips { "strip" } else { "face" }
                                ),
                            ));
                        }
                        indices.push(v);
                    }
                }
            }
        }
        r.end_row(if strips { "a strip" } else { "a face" })?;
        if strips {
            push_strips(&indices, &mut mesh.triangles);
        } else {
            // Fans; a "face" of fewer than three vertices has no area and is skipped.
            for k in 1..indices.len().saturating_sub(1) {
                mesh.triangles
                    .push([indices[0] as u32, indices[k] as u32, indices[k + 1] as u32]);
            }
        }
    }
    Ok(())
}

/// Triangles of strips separated by −1: triangle `k` of a strip is `(s[k], s[k+1], s[k+2])`
/// with the first two swapped for odd `k` (the winding alternates); triangles that repeat a
/// vertex (used to join strips) are dropped.
fn push_strips(indices: &[i64], out: &mut Vec<[u32; 3]>) {
    for strip in indices.split(|&v| v == -1) {
        for k in 0..strip.len().saturating_sub(2) {
            let (a, b, c) = (strip[k] as u32, strip[k + 1] as u32, strip[k + 2] as u32);
            if a == b || b == c || a == c {
                continue;
            }
            out.push(if k % 2 == 0 { [a, b, c] } else { [b, a, c] });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<PlyMesh, LoadError> {
        parse_ply(bytes, Path::new("t.ply"))
    }

    const ASCII: &str = "ply\nformat ascii 1.0\ncomment a quad\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n4 0 1 2 3\n";

    #[test]
    fn an_ascii_line_with_a_value_too_many_is_refused_at_its_line() {
        let text = ASCII.replace("1 0 0 0 255 0\n", "1 0 0 0 255 0 7\n");
        let e = parse(text.as_bytes()).unwrap_err();
        assert_eq!(e.position.map(|p| p.0), Some(15), "{e}");
        assert!(
            e.message
                .contains("`7` is one value more than a vertex has"),
            "{e}"
        );
        let text = ASCII.replace("4 0 1 2 3\n", "4 0 1 2 3 0\n");
        let e = parse(text.as_bytes()).unwrap_err();
        assert!(e.message.contains("more than a face has"), "{e}");
        // Trailing spaces and Windows line ends are no values.
        let (header, body) = ASCII.split_at(ASCII.find("end_header\n").unwrap() + 11);
        let text = format!("{header}{}", body.replace("\n", " \r\n"));
        assert_eq!(parse(text.as_bytes()).unwrap().triangles.len(), 2);
    }

    #[test]
    fn reads_ascii_with_colours_and_a_quad() {
        let m = parse(ASCII.as_bytes()).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.colors.unwrap()[1], [0.0, 1.0, 0.0]);
        assert!(m.normals.is_none());
    }

    fn binary(big: bool) -> Vec<u8> {
        let fmt = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut b = format!("ply\nformat {fmt} 1.0\nelement vertex 3\nproperty double x\nproperty float y\nproperty short z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\nproperty list uchar uint vertex_indices\nproperty int flags\nend_header\n").into_bytes();
        for (x, y, z) in [(0.0f64, 0.0f32, 0i16), (1.0, 0.0, 0), (0.0, 2.0, -3)] {
            let put = |b: &mut Vec<u8>, bytes: &[u8]| b.extend_from_slice(bytes);
            if big {
                put(&mut b, &x.to_be_bytes());
                put(&mut b, &y.to_be_bytes());
                put(&mut b, &z.to_be_bytes());
                for n in [0.0f32, 0.0, 1.0] {
                    put(&mut b, &n.to_be_bytes());
                }
            } else {
                put(&mut b, &x.to_le_bytes());
                put(&mut b, &y.to_le_bytes());
                put(&mut b, &z.to_le_bytes());
                for n in [0.0f32, 0.0, 1.0] {
                    put(&mut b, &n.to_le_bytes());
                }
            }
        }
        b.push(3);
        for i in [0u32, 1, 2, 7] {
            b.extend_from_slice(&if big {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
        b
    }

    #[test]
    fn reads_binary_both_endians_any_types() {
        for big in [false, true] {
            let m = parse(&binary(big)).unwrap();
            assert_eq!(m.positions[2], Vec3::new(0.0, 2.0, -3.0));
            assert_eq!(m.triangles, vec![[0, 1, 2]]);
            assert_eq!(m.normals.unwrap()[0], Vec3::Z);
        }
    }

    #[test]
    fn an_element_without_properties_is_read_past_whatever_its_count() {
        // Such an element takes no bytes, so no size check bounds its count: it is not looped over.
        let text = ASCII.replace(
            "element face 1\n",
            "element junk 18446744073709551615\nelement face 1\n",
        );
        assert_eq!(parse(text.as_bytes()).unwrap().triangles.len(), 2);
    }

    #[test]
    fn strips_restart_alternate_and_drop_degenerates() {
        let mut out = vec![];
        push_strips(&[0, 1, 2, 3, 3, 4, -1, 5, 6, 7], &mut out);
        assert_eq!(out, vec![[0, 1, 2], [2, 1, 3], [5, 6, 7]]);
    }

    #[test]
    fn broken_files_are_refused_with_a_cause() {
        let mut truncated = binary(false);
        truncated.truncate(truncated.len() - 5);
        assert!(
            parse(&truncated)
                .unwrap_err()
                .message
                .contains("ends early")
        );
        let huge = ASCII.replace("element vertex 4", "element vertex 1000000000000");
        let e = parse(huge.as_bytes()).unwrap_err();
        assert!(e.message.contains("more than the file's"), "{e}");
        let bad_index = ASCII.replace("4 0 1 2 3", "4 0 1 2 9");
        assert!(
            parse(bad_index.as_bytes())
                .unwrap_err()
                .message
                .contains("uses vertex 9, but there are 4")
        );
        let nan = ASCII.replace("1 1 0 0 0 255", "nan 1 0 0 0 255");
        assert!(
            parse(nan.as_bytes())
                .unwrap_err()
                .message
                .contains("not finite")
        );
        assert!(parse(b"plx\n").unwrap_err().message.contains("end_header"));
        let twice = ASCII.replace(
            "element face 1\n",
            "element vertex 2\nproperty float x\nelement face 1\n",
        );
        let e = parse(twice.as_bytes()).unwrap_err();
        assert!(e.message.contains("a second `element vertex`"), "{e}");
        assert_eq!(e.position.map(|p| p.0), Some(11), "{e}");
        let bad_word = ASCII.replace("0 1 0 255", "0 one 0 255");
        let e = parse(bad_word.as_bytes()).unwrap_err();
        assert_eq!(e.position, Some((17, 1)), "{e}");
    }
}
