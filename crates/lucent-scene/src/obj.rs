//! Wavefront OBJ: positions (with optional vertex colours), texture coordinates, normals,
//! polygonal faces, `usemtl` materials and `mtllib` libraries.
//!
//! Our own reader rather than a crate's: every error names its line, NaN and infinite numbers
//! are refused, and it parses about 169 MiB/s on one core (see `docs/import.md`). Faces of any
//! number of corners are split into triangle fans; each corner is `v`, `v/t`, `v//n` or
//! `v/t/n`, and negative indices count back from the latest element. Groups, objects and
//! smoothing groups are read past: lucent splits a file by material only.

use crate::error::LoadError;
use glam::{Vec2, Vec3};
use lucent::Rgb;
use lucent::film::tonemap::srgb_to_linear;
use lucent::shape::Mesh;
use std::collections::HashMap;
use std::path::Path;

/// No texture coordinate or normal at a corner.
const NONE: u32 = u32::MAX;

/// One triangle corner: indices of its position, texture coordinate and normal (`NONE`).
type Corner = [u32; 3];

/// An OBJ file as read: its elements and triangles, each with the material it was given.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjFile {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Vertex colours (`v x y z r g b`), one per position when any vertex has one.
    pub colors: Vec<Rgb>,
    /// Texture coordinates `(u, v)` as the file gives them (`v` up).
    pub texcoords: Vec<Vec2>,
    /// Normals as the file gives them.
    pub normals: Vec<Vec3>,
    /// Triangles: three corners each.
    triangles: Vec<[Corner; 3]>,
    /// The material of each triangle, an index into `materials`.
    triangle_materials: Vec<u32>,
    /// The names given to `usemtl`, in order of first use; `""` for faces before any.
    pub materials: Vec<String>,
    /// Each name of `materials` with its index, so that a `usemtl` or a part is found without
    /// a scan (a file of 200,000 parts took 93 s with one).
    material_index: HashMap<String, u32>,
    /// Triangle indices grouped by material (a counting sort, in file order within each), and
    /// where each material's run starts (one more entry than `materials`): a part's triangles
    /// without a pass over the whole file.
    by_material: Vec<u32>,
    material_starts: Vec<u32>,
    /// `mtllib` file names, with the line that names them.
    pub libraries: Vec<(String, usize)>,
}

impl ObjFile {
    /// The index of material `name`, added at the end of `materials` if it is new.
    fn material(&mut self, name: String) -> u32 {
        if let Some(&i) = self.material_index.get(&name) {
            return i;
        }
        let i = self.materials.len() as u32;
        self.materials.push(name.clone());
        self.material_index.insert(name, i);
        i
    }

    /// Fills `by_material` and `material_starts` from `triangle_materials`.
    fn group_by_material(&mut self) {
        let mut starts = vec![0u32; self.materials.len() + 1];
        for &m in &self.triangle_materials {
            starts[m as usize + 1] += 1;
        }
        for i in 1..starts.len() {
            starts[i] += starts[i - 1];
        }
        let mut next = starts.clone();
        let mut order = vec![0u32; self.triangle_materials.len()];
        for (t, &m) in self.triangle_materials.iter().enumerate() {
            order[next[m as usize] as usize] = t as u32;
            next[m as usize] += 1;
        }
        self.by_material = order;
        self.material_starts = starts;
    }

    /// Triangles read.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The names of the materials that faces use, in order of first use.
    pub fn used_materials(&self) -> Vec<&str> {
        let mut used = vec![false; self.materials.len()];
        for &m in &self.triangle_materials {
            used[m as usize] = true;
        }
        self.materials
            .iter()
            .zip(used)
            .filter(|(_, u)| *u)
            .map(|(n, _)| n.as_str())
            .collect()
    }

    /// The mesh of the faces whose `usemtl` material is `part` (all faces when `None`; `None`
    /// for a part without faces), with
    /// only the vertices they use. Normals are kept when every corner has one; texture
    /// coordinates when any has (the others get `(0, 0)`), with `v` flipped to grow
    /// downwards as lucent's meshes expect.
    pub fn mesh(&self, part: Option<&str>) -> Option<Mesh> {
        let wanted = match part {
            None => None,
            Some(name) => Some(*self.material_index.get(name)?),
        };
        // A part's run of triangle indices, or every triangle (the other side empty), chained:
        // neither is copied into a list.
        let (run, whole): (&[u32], &[[Corner; 3]]) = match wanted {
            Some(w) => {
                let run = self.material_starts[w as usize] as usize
                    ..self.material_starts[w as usize + 1] as usize;
                (&self.by_material[run], &[])
            }
            None => (&[], &self.triangles),
        };
        let selected = run
            .iter()
            .map(|&i| &self.triangles[i as usize])
            .chain(whole);
        let mut all_normals = true;
        let mut any_texcoords = false;
        let mut count = 0usize;
        for t in selected.clone() {
            count += 1;
            for c in t {
                all_normals &= c[2] != NONE;
                any_texcoords |= c[1] != NONE;
            }
        }
        if part.is_some() && count == 0 {
            // A material named by `usemtl` but given no faces is no part.
            return None;
        }
        // One vertex per distinct corner; the key drops what will not be kept.
        let key = |c: &Corner| {
            [
                c[0],
                if any_texcoords { c[1] } else { NONE },
                if all_normals { c[2] } else { NONE },
            ]
        };
        // Found through the position's chain of corners: faster than hashing, and a
        // position rarely has more than two texture/normal combinations.
        // A chain that grows long (a hostile file: one position with thousands of texture
        // coordinates) hands over to a hash map, so the work stays linear.
        const LONG_CHAIN: u32 = 16;
        // A part far smaller than the file's positions uses the map alone: a chain head per
        // position, for each of thousands of parts, would be quadratic.
        let map_only = count.saturating_mul(12) < self.positions.len();
        let mut first = if map_only {
            Vec::new()
        } else {
            vec![NONE; self.positions.len()]
        };
        let mut next: Vec<u32> = Vec::new();
        let mut long: HashMap<Corner, u32> = HashMap::new();
        let mut corners: Vec<Corner> = Vec::new();
        let mut triangles = Vec::with_capacity(count);
        for t in selected {
            triangles.push(t.map(|c| {
                let k = key(&c);
                if map_only {
                    let fresh = corners.len() as u32;
                    let i = *long.entry(k).or_insert(fresh);
                    if i == fresh {
                        corners.push(k);
                    }
                    return i;
                }
                let mut i = first[k[0] as usize];
                let mut steps = 0;
                while i != NONE && corners[i as usize] != k && steps < LONG_CHAIN {
                    i = next[i as usize];
                    steps += 1;
                }
                if i != NONE && corners[i as usize] == k {
                    return i;
                }
                if steps == LONG_CHAIN
                    && let Some(&found) = long.get(&k)
                {
                    return found;
                }
                let i = corners.len() as u32;
                corners.push(k);
                if steps == LONG_CHAIN {
                    long.insert(k, i);
                    next.push(NONE);
                } else {
                    next.push(first[k[0] as usize]);
                    first[k[0] as usize] = i;
                }
                i
            }));
        }
        let mut mesh = Mesh::new(
            corners
                .iter()
                .map(|c| self.positions[c[0] as usize])
                .collect(),
            triangles,
        );
        if all_normals && count > 0 {
            mesh.normals = corners
                .iter()
                .map(|c| self.normals[c[2] as usize].normalize_or_zero())
                .collect();
        }
        if any_texcoords {
            mesh.uvs = corners
                .iter()
                .map(|c| match self.texcoords.get(c[1] as usize) {
                    Some(t) => Vec2::new(t.x, 1.0 - t.y),
                    None => Vec2::ZERO,
                })
                .collect();
        }
        if !self.colors.is_empty() {
            // Written as display values (8-bit colours over 255), as PLY colours are.
            mesh.colors = corners
                .iter()
                .map(|c| Rgb::from(self.colors[c[0] as usize].to_array().map(srgb_to_linear)))
                .collect();
        }
        Some(mesh)
    }
}

/// Reads the OBJ file at `path` as one mesh (every face).
pub fn read_obj(path: &Path) -> Result<Mesh, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    let file = parse_obj(&bytes, path)?;
    Ok(file.mesh(None).unwrap_or_default())
}

/// The words of a line, split at ASCII spaces and tabs (a lean `split_ascii_whitespace`).
struct Words<'a>(&'a str);

impl<'a> Iterator for Words<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        let bytes = self.0.as_bytes();
        let start = bytes.iter().position(|b| !b.is_ascii_whitespace())?;
        let end = bytes[start..]
            .iter()
            .position(u8::is_ascii_whitespace)
            .map_or(bytes.len(), |n| start + n);
        // ASCII bytes are character boundaries, so these slices never fail.
        let word = &self.0[start..end];
        self.0 = &self.0[end..];
        Some(word)
    }
}

/// Numbers of a statement, parsed from `words`.
fn numbers<'a, const N: usize>(
    words: &mut impl Iterator<Item = &'a str>,
    what: &str,
    line: usize,
    path: &Path,
) -> Result<[f32; N], LoadError> {
    let mut out = [0.0f32; N];
    for (i, slot) in out.iter_mut().enumerate() {
        let word = words.next().ok_or_else(|| {
            LoadError::line(path, line, format!("{what} has {i} numbers; expected {N}"))
        })?;
        *slot = number(word, what, line, path)?;
    }
    Ok(out)
}

fn number(word: &str, what: &str, line: usize, path: &Path) -> Result<f32, LoadError> {
    let v: f32 = word
        .parse()
        .map_err(|_| LoadError::line(path, line, format!("{what}: `{word}` is not a number")))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(LoadError::line(
            path,
            line,
            format!("{what}: `{word}` is not finite"),
        ))
    }
}

/// Resolves a 1-based (or negative, counting back) OBJ index among `count` elements so far.
fn resolve(
    text: &str,
    count: usize,
    what: &str,
    line: usize,
    path: &Path,
) -> Result<u32, LoadError> {
    let err = |m: String| LoadError::line(path, line, m);
    let index: i64 = text
        .parse()
        .map_err(|_| err(format!("face corner: `{text}` is not a {what} index")))?;
    let resolved = match index {
        0 => return Err(err(format!("{what} index 0: OBJ indices start at 1"))),
        i if i > 0 => i - 1,
        i => count as i64 + i,
    };
    if resolved < 0 || resolved >= i64::from(NONE) {
        return Err(err(format!(
            "{what} index {index} is out of range ({count} so far)"
        )));
    }
    Ok(resolved as u32)
}

/// Parses OBJ bytes (UTF-8 or any ASCII-compatible encoding); `path` names it in errors.
pub fn parse_obj(bytes: &[u8], path: &Path) -> Result<ObjFile, LoadError> {
    // Valid UTF-8 is checked by the fast path; anything else is read as lossy text.
    // A byte-order mark (as some Windows tools write) is not part of the first statement.
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => std::borrow::Cow::Borrowed(t),
        Err(_) => String::from_utf8_lossy(bytes),
    };
    let mut obj = ObjFile::default();
    let mut material = None::<u32>;
    // Corners that point past what was read so far are checked at the end: (line, corner).
    let mut forward: Vec<(usize, Corner)> = Vec::new();
    let mut polygon: Vec<Corner> = Vec::with_capacity(8);
    for (n, raw) in text.lines().enumerate() {
        let line = n + 1;
        let mut words = Words(raw);
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let p = numbers::<3>(&mut words, "vertex", line, path)?;
                obj.positions.push(Vec3::from_array(p));
                // After x y z: nothing, a weight `w` (ignored), or a colour `r g b`.
                // Up to four more words, without allocating (a fourth is an error below).
                let mut rest = [""; 4];
                let mut count = 0;
                for w in words.by_ref().take(4) {
                    rest[count] = w;
                    count += 1;
                }
                let rest = &rest[..count];
                match rest.len() {
                    0 | 1 => {
                        if let Some(w) = rest.first() {
                            number(w, "vertex weight", line, path)?;
                        }
                        if !obj.colors.is_empty() {
                            obj.colors.push(Rgb::WHITE);
                        }
                    }
                    3 => {
                        let [r, g, b] =
                            numbers::<3>(&mut rest.iter().copied(), "vertex colour", line, path)?;
                        // Colours start with the first vertex that has one; earlier ones are white.
                        obj.colors.resize(obj.positions.len() - 1, Rgb::WHITE);
                        obj.colors.push(Rgb::new(r, g, b));
                    }
                    n => {
                        return Err(LoadError::line(
                            path,
                            line,
                            format!(
                                "vertex has {} numbers; expected 3, 4 (x y z w) or 6 (x y z r g b)",
                                n + 3
                            ),
                        ));
                    }
                }
            }
            "vt" => {
                let u = number(words.next().unwrap_or(""), "texture coordinate", line, path)?;
                let v = match words.next() {
                    Some(w) => number(w, "texture coordinate", line, path)?,
                    None => 0.0,
                };
                obj.texcoords.push(Vec2::new(u, v));
            }
            "vn" => {
                let v = numbers::<3>(&mut words, "normal", line, path)?;
                obj.normals.push(Vec3::from_array(v));
            }
            "f" => {
                polygon.clear();
                for word in words {
                    let mut parts = word.split('/');
                    let v = resolve(
                        parts.next().unwrap_or(""),
                        obj.positions.len(),
                        "vertex",
                        line,
                        path,
                    )?;
                    let t = match parts.next() {
                        None | Some("") => NONE,
                        Some(s) => {
                            resolve(s, obj.texcoords.len(), "texture coordinate", line, path)?
                        }
                    };
                    let nrm = match parts.next() {
                        None | Some("") => NONE,
                        Some(s) => resolve(s, obj.normals.len(), "normal", line, path)?,
                    };
                    let c = [v, t, nrm];
                    if v as usize >= obj.positions.len()
                        || (t != NONE && t as usize >= obj.texcoords.len())
                        || (nrm != NONE && nrm as usize >= obj.normals.len())
                    {
                        forward.push((line, c));
                    }
                    polygon.push(c);
                }
                if polygon.len() < 3 {
                    return Err(LoadError::line(
                        path,
                        line,
                        format!("face has {} corners; at least 3 are needed", polygon.len()),
                    ));
                }
                let m = *material.get_or_insert_with(|| obj.material(String::new()));
                for k in 1..polygon.len() - 1 {
                    obj.triangles.push([polygon[0], polygon[k], polygon[k + 1]]);
                    obj.triangle_materials.push(m);
                }
            }
            "usemtl" => {
                let name = raw.trim_start()[keyword.len()..].trim().to_string();
                material = Some(obj.material(name));
            }
            "mtllib" => {
                for name in words {
                    obj.libraries.push((name.to_string(), line));
                }
            }
            _ => {}
        }
    }
    let counts = [obj.positions.len(), obj.texcoords.len(), obj.normals.len()];
    let names = ["vertex", "texture coordinate", "normal"];
    for (line, c) in forward {
        for k in 0..3 {
            if c[k] != NONE && c[k] as usize >= counts[k] {
                return Err(LoadError::line(
                    path,
                    line,
                    format!(
                        "{} index {} is out of range ({} in the file)",
                        names[k],
                        c[k] as u64 + 1,
                        counts[k]
                    ),
                ));
            }
        }
    }
    obj.group_by_material();
    Ok(obj)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ObjFile, LoadError> {
        parse_obj(text.as_bytes(), Path::new("t.obj"))
    }

    #[test]
    fn many_parts_each_read_their_own_faces() {
        // 40 positions; part `p{i}` is one triangle, far smaller than the file (the corners
        // are found by map alone), and the same faces read whole keep every part.
        let mut text = String::new();
        for i in 0..40 {
            text += &format!("v {i} 0 0\nv {i} 1 0\n");
        }
        let parts = 2_000;
        for i in 0..parts {
            let a = 1 + (i % 39) * 2;
            text += &format!("g g{i}\nusemtl p{i}\nf {a} {} {}\n", a + 1, a + 2);
        }
        let obj = parse(&text).unwrap();
        assert_eq!(obj.used_materials().len(), parts);
        for i in [0, 1, 777, parts - 1] {
            let m = obj.mesh(Some(&format!("p{i}"))).unwrap();
            assert_eq!(m.triangles, vec![[0, 1, 2]]);
            let a = (i % 39) * 2;
            let expected: Vec<Vec3> = (a..a + 3)
                .map(|k| Vec3::new((k / 2) as f32, (k % 2) as f32, 0.0))
                .collect();
            assert_eq!(m.positions, expected, "part {i}");
        }
        assert_eq!(obj.mesh(None).unwrap().triangles.len(), parts);
        assert!(obj.mesh(Some("none")).is_none());
    }

    #[test]
    fn reads_triangles_quads_and_corner_forms() {
        let obj =
            parse("# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2//1 3/2/1 4/1/1\n")
                .unwrap();
        assert_eq!(obj.triangle_count(), 2);
        let m = obj.mesh(None).unwrap();
        // Corners (1,1,1) (2,-,1) (3,2,1) (4,1,1): four distinct vertices.
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.normals, vec![Vec3::Z; 4]);
        // `v` flipped: the file's (1, 1) is (1, 0); a corner without one is (0, 0).
        assert_eq!(
            m.uvs,
            vec![
                Vec2::new(0.0, 1.0),
                Vec2::ZERO,
                Vec2::new(1.0, 0.0),
                Vec2::new(0.0, 1.0)
            ]
        );
    }

    #[test]
    fn negative_indices_count_back() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n")
            .unwrap()
            .mesh(None)
            .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn parts_are_materials_and_keep_only_their_vertices() {
        let text = "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nusemtl red\nf 2 4 3\nusemtl blue\nf 4 1 2\nusemtl red\nf 1 2 4\n";
        let obj = parse(text).unwrap();
        assert_eq!(obj.used_materials(), vec!["", "red", "blue"]);
        assert_eq!(
            obj.libraries,
            vec![("a.mtl".to_string(), 1), ("b.mtl".to_string(), 1)]
        );
        let red = obj.mesh(Some("red")).unwrap();
        assert_eq!(red.triangles.len(), 2);
        assert_eq!(
            red.positions,
            vec![Vec3::X, Vec3::splat(5.0), Vec3::Y, Vec3::ZERO]
        );
        assert_eq!(obj.mesh(Some("")).unwrap().positions.len(), 3);
        assert!(obj.mesh(Some("green")).is_none());
        // A material named by `usemtl` but given no faces is no part either.
        let unused = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl late\n").unwrap();
        assert!(unused.mesh(Some("late")).is_none());
        // Without normals on every corner, none are kept.
        let mixed = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n").unwrap();
        assert!(mixed.mesh(None).unwrap().normals.is_empty());
    }

    #[test]
    fn a_byte_order_mark_is_read_past() {
        let obj = parse("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(obj.positions.len(), 3);
        assert_eq!(obj.triangle_count(), 1);
    }

    #[test]
    fn many_corners_at_one_position_stay_linear() {
        // Three positions, each with 50,000 texture coordinates: the corner chains hand over
        // to a map instead of growing to 50,000 links (which would take 10^9 steps).
        let n = 50_000;
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for k in 0..n {
            text.push_str(&format!("vt {} 0\n", k as f32 / n as f32));
        }
        for k in 1..=n {
            text.push_str(&format!("f 1/{k} 2/{k} 3/{k}\n"));
        }
        let start = std::time::Instant::now();
        let m = parse(&text).unwrap().mesh(None).unwrap();
        assert_eq!(m.positions.len(), 3 * n);
        assert_eq!(m.triangles.len(), n);
        // Every corner of a face is its own vertex, in order.
        assert_eq!(m.triangles[7], [21, 22, 23]);
        assert!(start.elapsed().as_secs() < 20);
    }

    #[test]
    fn a_vertex_weight_is_read_past() {
        let obj = parse("v 0 0 0 1\nv 1 0 0 0.5\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(obj.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert!(obj.colors.is_empty());
        let e = parse("v 0 0 0 1 1\n").unwrap_err();
        assert!(e.message.contains("expected 3, 4 (x y z w) or 6"), "{e}");
        assert!(parse("v 0 0 0 x\n").is_err());
    }

    #[test]
    fn vertex_colours_are_read() {
        let obj = parse("v 0 0 0\nv 1 0 0 1 0 0\nv 0 1 0 0 1 0.5\nf 1 2 3\n").unwrap();
        let m = obj.mesh(None).unwrap();
        // Display values, decoded from sRGB: 0.5 is a linear 0.214.
        let half = srgb_to_linear(0.5);
        assert!((half - 0.214).abs() < 1e-3);
        assert_eq!(
            m.colors,
            vec![
                Rgb::WHITE,
                Rgb::new(1.0, 0.0, 0.0),
                Rgb::new(0.0, 1.0, half)
            ]
        );
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:4:1: vertex index 7 is out of range (3 in the file)"
        );
        let e = parse("v 0 0\n").unwrap_err();
        assert_eq!(e.position, Some((1, 1)));
        assert!(e.message.contains("expected 3"), "{e}");
        for (text, needle) in [
            ("v 0 nan 0\n", "not finite"),
            ("v 0 0 inf\n", "not finite"),
            ("v 0 0 0\nf 1 0 1\n", "start at 1"),
            ("v 0 0 0\nf 1 1\n", "at least 3"),
            ("v 0 0 0\nf -5 1 1\n", "out of range"),
            ("v 0 0 0\nf 1/x 1 1\n", "not a texture coordinate index"),
            (
                "v 0 0 0\nvn 0 0 1\nf 1//2 1//1 1//1\n",
                "normal index 2 is out of range",
            ),
            ("vt nope\n", "not a number"),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }
}
