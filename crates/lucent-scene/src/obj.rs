//! A minimal Wavefront OBJ reader: vertex positions and polygonal faces.
//!
//! Reads `v x y z` and `f a b c ...` (each corner `i`, `i/t`, `i//n` or `i/t/n`; negative
//! indices count back from the latest vertex); polygons are split into triangle fans. Every
//! other statement (normals, texture coordinates, groups, materials) is skipped. The full
//! importer, with materials and normals, is a later piece of work.

use crate::error::LoadError;
use glam::Vec3;
use std::path::Path;

/// Positions and triangles read from an OBJ file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as 0-based vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

/// Reads the OBJ file at `path`.
pub fn read_obj(path: &Path) -> Result<ObjMesh, LoadError> {
    let bytes = std::fs::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    parse_obj(&String::from_utf8_lossy(&bytes), path)
}

/// Parses OBJ text; `path` names it in errors.
pub fn parse_obj(text: &str, path: &Path) -> Result<ObjMesh, LoadError> {
    let mut mesh = ObjMesh::default();
    // Face corners whose index is only checked once every vertex is known: (line, index).
    let mut forward_refs: Vec<(usize, usize)> = Vec::new();
    let mut corners: Vec<u32> = Vec::with_capacity(8);
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let err = |msg: String| LoadError::line(path, line_no, msg);
        let mut words = line.split_ascii_whitespace();
        match words.next() {
            Some("v") => {
                let mut xyz = [0.0f32; 3];
                for (axis, slot) in xyz.iter_mut().enumerate() {
                    let word = words
                        .next()
                        .ok_or_else(|| err(format!("vertex has {axis} coordinates; expected 3")))?;
                    *slot = word
                        .parse()
                        .map_err(|_| err(format!("vertex coordinate `{word}` is not a number")))?;
                    if !slot.is_finite() {
                        return Err(err(format!("vertex coordinate `{word}` is not finite")));
                    }
                }
                mesh.positions.push(Vec3::from_array(xyz));
            }
            Some("f") => {
                corners.clear();
                for word in words {
                    let index_text = word.split('/').next().unwrap_or("");
                    let index: i64 = index_text.parse().map_err(|_| {
                        err(format!(
                            "face corner `{word}` does not start with a vertex index"
                        ))
                    })?;
                    let count = mesh.positions.len() as i64;
                    let resolved = match index {
                        0 => return Err(err("vertex index 0: OBJ indices start at 1".into())),
                        i if i > 0 => i - 1,
                        i => count + i,
                    };
                    if resolved < 0 || resolved >= i64::from(u32::MAX) {
                        return Err(err(format!(
                            "vertex index {index} is out of range ({count} vertices so far)"
                        )));
                    }
                    if resolved >= count {
                        forward_refs.push((line_no, resolved as usize));
                    }
                    corners.push(resolved as u32);
                }
                if corners.len() < 3 {
                    return Err(err(format!(
                        "face has {} corners; at least 3 are needed",
                        corners.len()
                    )));
                }
                for k in 1..corners.len() - 1 {
                    mesh.triangles
                        .push([corners[0], corners[k], corners[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if let Some(&(line, index)) = forward_refs
        .iter()
        .find(|&&(_, i)| i >= mesh.positions.len())
    {
        let count = mesh.positions.len();
        return Err(LoadError::line(
            path,
            line,
            format!(
                "vertex index {} is out of range ({count} vertices)",
                index + 1
            ),
        ));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ObjMesh, LoadError> {
        parse_obj(text, Path::new("t.obj"))
    }

    #[test]
    fn reads_triangles_quads_and_corner_forms() {
        let m =
            parse("# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1/1/1 2//1 3/2 4\n")
                .unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn negative_indices_count_back() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:4:1: vertex index 7 is out of range (3 vertices)"
        );
        let e = parse("v 0 0\n").unwrap_err();
        assert_eq!(e.position, Some((1, 1)));
        assert!(e.message.contains("expected 3"), "{e}");
        assert!(
            parse("v 0 nan 0\n")
                .unwrap_err()
                .message
                .contains("not finite")
        );
        assert!(
            parse("v 0 0 0\nf 1 0 1\n")
                .unwrap_err()
                .message
                .contains("start at 1")
        );
        assert!(
            parse("v 0 0 0\nf 1 1\n")
                .unwrap_err()
                .message
                .contains("at least 3")
        );
        assert!(
            parse("v 0 0 0\nf -5 1 1\n")
                .unwrap_err()
                .message
                .contains("out of range")
        );
    }
}
