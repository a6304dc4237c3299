//! Mesh primitives as triangle meshes: topology, attributes, and the merge of placed
//! primitives into one world-space mesh.

use super::accessor::{MAX_ELEMENTS, read_floats, read_indices};
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use gltf::mesh::{Mode, Semantic};
use lucent::Rgb;
use lucent::shape::Mesh;

/// A primitive read: its triangles in the mesh's own space, or why it has none.
#[derive(Clone, Debug)]
pub(super) enum Decoded {
    /// Triangles, with notes on what was dropped (each a sentence, without the file's name).
    Triangles(Mesh, Vec<String>),
    /// Not triangles (points or lines), or no triangle at all: why.
    Skipped(String),
}

/// Reads primitive `prim` of mesh `mesh`, with the texture coordinates of set `uv_set`
/// (`TEXCOORD_n`: its material's, see `material::uv_set`), its morph targets added at
/// `weights` (the mesh's default weights). Errors name the mesh and primitive.
pub(super) fn decode(
    buffers: &[Vec<u8>],
    mesh: usize,
    prim: &gltf::Primitive,
    uv_set: u32,
    weights: &[f32],
) -> Result<Decoded, String> {
    let label = format!("mesh {mesh} primitive {}", prim.index());
    let err = |e: String| format!("{label}: {e}");
    let mode = prim.mode();
    if matches!(
        mode,
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
    ) {
        return Ok(Decoded::Skipped(format!(
            "{label} is drawn as {mode:?}, not triangles; skipped"
        )));
    }
    let position = prim
        .get(&Semantic::Positions)
        .ok_or_else(|| err("has no POSITION attribute".into()))?;
    let (mut flat, _) = read_floats(buffers, &position, &[3]).map_err(err)?;
    morph(buffers, prim, weights, |t| t.positions(), &mut flat, 3).map_err(err)?;
    let positions: Vec<Vec3> = flat.chunks_exact(3).map(Vec3::from_slice).collect();
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(err(format!("position {i} is not finite: {p}")));
    }
    let n = positions.len();
    let indices = match prim.indices() {
        Some(a) => {
            let indices = read_indices(buffers, &a).map_err(err)?;
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
                return Err(err(format!("index {bad} out of range ({n} vertices)")));
            }
            indices
        }
        // Non-indexed: vertex k is corner k.
        None => (0..n as u32).collect(),
    };
    let mut notes = Vec::new();
    let triangles = triangulate(mode, &indices);
    if mode == Mode::Triangles && indices.len() % 3 != 0 {
        notes.push(format!(
            "{label} has {} vertex indices, not a multiple of 3; the last {} are ignored",
            indices.len(),
            indices.len() % 3
        ));
    }
    if triangles.is_empty() {
        return Ok(Decoded::Skipped(format!(
            "{label} has no triangles; skipped"
        )));
    }
    let mut m = Mesh::new(positions, triangles);
    let mut optional = |semantic: Semantic, widths: &[usize], what: &str| {
        let a = prim.get(&semantic)?;
        match read_floats(buffers, &a, widths) {
            Ok((v, w)) if v.len() == n * w => Some((v, w)),
            Ok((v, w)) => {
                notes.push(format!(
                    "{label}: {what} dropped: {} of them for {n} vertices",
                    v.len() / w
                ));
                None
            }
            Err(e) => {
                notes.push(format!("{label}: {what} dropped: {e}"));
                None
            }
        }
    };
    let mut normals = optional(Semantic::Normals, &[3], "normals");
    let uvs = optional(Semantic::TexCoords(uv_set), &[2], "texture coordinates");
    let colors = optional(Semantic::Colors(0), &[3, 4], "colours");
    let mut tangents = optional(Semantic::Tangents, &[4], "tangents");
    if let Some((v, w)) = &mut normals {
        morph(buffers, prim, weights, |t| t.normals(), v, *w).map_err(err)?;
    }
    if let Some((v, w)) = &mut tangents {
        morph(buffers, prim, weights, |t| t.tangents(), v, *w).map_err(err)?;
    }
    if let Some((v, _)) = normals {
        // Shading normals must be unit vectors; the file's should be, but are normalised anyway.
        let unit: Option<Vec<Vec3>> = v
            .chunks_exact(3)
            .map(|c| Vec3::from_slice(c).try_normalize())
            .collect();
        match unit {
            Some(unit) => m.normals = unit,
            None => notes.push(format!(
                "{label}: normals dropped: one is zero or not finite"
            )),
        }
    }
    if let Some((v, _)) = uvs {
        if v.iter().all(|x| x.is_finite()) {
            m.uvs = v.chunks_exact(2).map(Vec2::from_slice).collect();
        } else {
            notes.push(format!(
                "{label}: texture coordinates dropped: one is not finite"
            ));
        }
    }
    if let Some((v, w)) = colors {
        // COLOR_0's alpha, if any, is not used.
        let rgb: Vec<Rgb> = v
            .chunks_exact(w)
            .map(|c| Rgb::new(c[0], c[1], c[2]))
            .collect();
        if rgb
            .iter()
            .all(|c| c.is_finite() && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0)
        {
            m.colors = rgb;
        } else {
            notes.push(format!(
                "{label}: colours dropped: one is negative or not finite"
            ));
        }
    }
    if let Some((v, _)) = tangents {
        let frames: Option<Vec<Vec4>> = v
            .chunks_exact(4)
            .map(|c| {
                let t = Vec3::from_slice(&c[..3]).try_normalize()?;
                Some(t.extend(if c[3] < 0.0 { -1.0 } else { 1.0 }))
            })
            .collect();
        match frames {
            Some(f) if !m.normals.is_empty() => m.tangents = f,
            Some(_) => notes.push(format!("{label}: tangents dropped: there are no normals")),
            None => notes.push(format!(
                "{label}: tangents dropped: one is zero or not finite"
            )),
        }
    }
    // A normal map needs the frame it was baked in: MikkTSpace's, where the file gives none.
    let material = prim.material();
    let normal_mapped = material.normal_texture().is_some()
        || material
            .extension_value("KHR_materials_clearcoat")
            .is_some_and(|c| c.get("clearcoatNormalTexture").is_some())
        || material
            .extension_value("KHR_materials_anisotropy")
            .is_some();
    if normal_mapped && m.tangents.is_empty() && !crate::tangents::generate(&mut m) {
        notes.push(format!(
            "{label}: its material's normal map needs normals and texture coordinates for a tangent frame; the uv tangents of each triangle are used"
        ));
    }
    m.validate().map_err(err)?;
    Ok(Decoded::Triangles(m, notes))
}

/// Triangles of `indices` drawn as `mode` (glTF 2.0 §3.7.2.1): lists in threes; strips
/// `(i, i+1, i+2)` with `(i, i+2, i+1)` for odd `i`, so every triangle keeps the first one's
/// winding; fans `(i+1, i+2, 0)`. Strip and fan triangles that repeat a vertex (used to stitch
/// strips together) have no area and are dropped.
fn triangulate(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    let corners = |k: usize| indices[k];
    let solid = |t: &[u32; 3]| t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        Mode::TriangleStrip => (0..indices.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [corners(i), corners(i + 1), corners(i + 2)]
                } else {
                    [corners(i), corners(i + 2), corners(i + 1)]
                }
            })
            .filter(solid)
            .collect(),
        Mode::TriangleFan => (0..indices.len().saturating_sub(2))
            .map(|i| [corners(i + 1), corners(i + 2), corners(0)])
            .filter(solid)
            .collect(),
        _ => Vec::new(),
    }
}

/// Whether `m` can place an object: finite, affine, and not flattening (the same test as the
/// scene format's `transform`).
pub(super) fn placeable(m: &Mat4) -> bool {
    let det = m.determinant();
    m.is_finite() && det != 0.0 && det.is_finite() && m.row(3) == glam::Vec4::W
}

/// The meshes in `parts`, each moved by its world matrix, merged into one mesh.
///
/// Positions are transformed by the matrix and normals by its inverse transpose. Where the
/// matrix mirrors (negative determinant) each triangle's winding is reversed, so the side that
/// was the front in the mesh's own space stays the front (glTF 2.0 §3.7.4). An attribute is kept
/// when every part has it; colours are the exception: parts without them get white, which
/// leaves the material's colour as it is.
pub(super) fn merge(parts: &[(&Mesh, Mat4)]) -> Result<Mesh, String> {
    let vertices: usize = parts.iter().map(|(m, _)| m.positions.len()).sum();
    let triangles: usize = parts.iter().map(|(m, _)| m.triangles.len()).sum();
    if vertices > MAX_ELEMENTS || triangles > MAX_ELEMENTS {
        return Err(format!(
            "the placed meshes have {vertices} vertices and {triangles} triangles; at most {MAX_ELEMENTS} of each are supported"
        ));
    }
    let all = |has: fn(&Mesh) -> bool| parts.iter().all(|(m, _)| has(m));
    let keep_normals = all(|m| !m.normals.is_empty());
    let keep_uvs = all(|m| !m.uvs.is_empty());
    let keep_tangents = all(|m| !m.tangents.is_empty());
    let keep_colors = parts.iter().any(|(m, _)| !m.colors.is_empty());
    let mut out = Mesh {
        positions: Vec::with_capacity(vertices),
        triangles: Vec::with_capacity(triangles),
        ..Mesh::default()
    };
    for (m, world) in parts {
        let base = out.positions.len() as u32;
        let first = out.positions.len();
        out.positions
            .extend(m.positions.iter().map(|&p| world.transform_point3(p)));
        if let Some(p) = out.positions[first..].iter().find(|p| !p.is_finite()) {
            return Err(format!(
                "a vertex placed by its node's transform is not finite: {p}"
            ));
        }
        let mirrored = world.determinant() < 0.0;
        out.triangles.extend(m.triangles.iter().map(|t| {
            let t = t.map(|v| v + base);
            if mirrored { [t[0], t[2], t[1]] } else { t }
        }));
        if keep_normals {
            let normal_matrix = Mat3::from_mat4(*world).inverse().transpose();
            out.normals.extend(
                m.normals
                    .iter()
                    .map(|&n| (normal_matrix * n).normalize_or(n)),
            );
        }
        if keep_uvs {
            out.uvs.extend_from_slice(&m.uvs);
        }
        if keep_tangents {
            // Tangents are directions; a mirror turns the bitangent against `n × t`.
            let linear = Mat3::from_mat4(*world);
            let sign = if mirrored { -1.0 } else { 1.0 };
            out.tangents.extend(m.tangents.iter().map(|t| {
                (linear * t.truncate())
                    .normalize_or(t.truncate())
                    .extend(t.w * sign)
            }));
        }
        if keep_colors {
            if m.colors.is_empty() {
                out.colors
                    .extend(std::iter::repeat_n(Rgb::WHITE, m.positions.len()));
            } else {
                out.colors.extend_from_slice(&m.colors);
            }
        }
    }
    out.validate()?;
    Ok(out)
}

/// Adds to `values` (flattened, `width` numbers a vertex, of which the first three move) the
/// displacements of `prim`'s morph targets that `target` picks, each times its weight:
/// glTF's pose at `weights`. A target whose count differs from the vertices' is refused.
fn morph<'a>(
    buffers: &[Vec<u8>],
    prim: &gltf::Primitive<'a>,
    weights: &[f32],
    target: impl Fn(&gltf::mesh::MorphTarget<'a>) -> Option<gltf::Accessor<'a>>,
    values: &mut [f32],
    width: usize,
) -> Result<(), String> {
    for (k, (t, &w)) in prim.morph_targets().zip(weights).enumerate() {
        let Some(a) = target(&t).filter(|_| w != 0.0 && w.is_finite()) else {
            continue;
        };
        let (d, _) = read_floats(buffers, &a, &[3])?;
        if d.len() / 3 != values.len() / width {
            return Err(format!(
                "morph target {k} moves {} vertices of {}",
                d.len() / 3,
                values.len() / width
            ));
        }
        for (v, d) in values.chunks_exact_mut(width).zip(d.chunks_exact(3)) {
            for c in 0..3 {
                v[c] += w * d[c];
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_the_winding() {
        assert_eq!(
            triangulate(Mode::TriangleStrip, &[0, 1, 2, 3, 4]),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            triangulate(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![[1, 2, 0], [2, 3, 0]]
        );
        // A stitch: the degenerate triangles are dropped, and the parity carries across it
        // (the triangle (5, 6, 7) starts at odd position 5).
        assert_eq!(
            triangulate(Mode::TriangleStrip, &[0, 1, 2, 2, 5, 5, 6, 7]),
            vec![[0, 1, 2], [5, 7, 6]]
        );
        assert_eq!(
            triangulate(Mode::Triangles, &[0, 1, 2, 3, 4]),
            vec![[0, 1, 2]]
        );
        assert!(triangulate(Mode::TriangleFan, &[0, 1]).is_empty());
    }

    #[test]
    fn merging_mirrors_the_winding_and_fills_colours() {
        let tri = Mesh {
            normals: vec![Vec3::Z; 3],
            ..Mesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]])
        };
        let coloured = Mesh {
            colors: vec![Rgb::new(1.0, 0.0, 0.0); 3],
            ..tri.clone()
        };
        let mirror = Mat4::from_scale(Vec3::new(1.0, 1.0, -2.0));
        let moved = Mat4::from_translation(Vec3::X);
        let m = merge(&[(&tri, moved), (&coloured, mirror)]).unwrap();
        assert_eq!(m.positions[1], Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(m.triangles, vec![[0, 1, 2], [3, 5, 4]]);
        assert_eq!(m.normals[3], -Vec3::Z);
        assert_eq!(m.colors[0], Rgb::WHITE);
        assert_eq!(m.colors[3], Rgb::new(1.0, 0.0, 0.0));
        assert!(m.uvs.is_empty());
        assert!(placeable(&mirror));
        assert!(!placeable(&Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0))));
        assert!(!placeable(&Mat4::from_cols_array(&[f32::NAN; 16])));
    }
}
