//! Triangle meshes as flat arrays: positions and index triples, and optional per-vertex
//! normals (smooth shading), texture coordinates, colours and tangent frames.

use crate::Rgb;
use glam::{Vec2, Vec3, Vec4};
use lucent_accel::Aabb;

/// An indexed triangle mesh (its material is given when it is added to a scene).
///
/// Triangles wind counter-clockwise seen from their front side; a closed mesh wound that way
/// has outward normals, which refraction uses to tell entering from leaving.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, in world space.
    pub positions: Vec<Vec3>,
    /// Vertex indices of each triangle, all `< positions.len()`.
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex shading normals (unit length), or empty: the shading normal is then the
    /// triangle's own.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates `(u, v)`, `v` growing downwards in the image (glTF's
    /// convention; OBJ's `v` is flipped on reading), or empty.
    pub uvs: Vec<Vec2>,
    /// Per-vertex colours (linear RGB), multiplying the diffuse colour, or empty.
    pub colors: Vec<Rgb>,
    /// Per-vertex tangent frames for normal maps, or empty: the tangent (`xyz`, along `+u`,
    /// perpendicular to the normal) and the bitangent's handedness (`w`, `±1`: the bitangent,
    /// along `−v`, is `w·(n × t)`), as glTF's `TANGENT` holds them.
    pub tangents: Vec<Vec4>,
}

impl Mesh {
    /// A mesh of positions and triangles only.
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
            ..Self::default()
        }
    }

    /// Checks that the optional arrays are empty or hold one entry per vertex, and that every
    /// index is in range; the message says what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        let n = self.positions.len();
        for (what, len) in [
            ("normals", self.normals.len()),
            ("tangents", self.tangents.len()),
            ("texture coordinates", self.uvs.len()),
            ("colours", self.colors.len()),
        ] {
            if len != 0 && len != n {
                return Err(format!("{len} {what} for {n} vertices"));
            }
        }
        if let Some((i, t)) = self
            .triangles
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&v| v as usize >= n))
        {
            return Err(format!(
                "triangle {i} refers to vertex {}, but there are {n}",
                t.iter().max().unwrap_or(&0)
            ));
        }
        Ok(())
    }

    /// Turns every triangle around (and the normals with it).
    pub fn flip(&mut self) {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
        for n in &mut self.normals {
            *n = -*n;
        }
        // The normal turned, `n × t` turns too, while the bitangent stays.
        for t in &mut self.tangents {
            t.w = -t.w;
        }
    }

    /// The tangent frame at barycentric weights `bary` of the triangle of vertices `corners`:
    /// the corners' tangents interpolated, the first corner's handedness. `None` without
    /// tangents.
    #[inline]
    pub fn tangent_at(&self, corners: [usize; 3], bary: [f32; 3]) -> Option<Vec4> {
        if self.tangents.is_empty() {
            return None;
        }
        let t = corners
            .iter()
            .zip(bary)
            .fold(Vec3::ZERO, |a, (&i, b)| a + b * self.tangents[i].truncate());
        Some(t.extend(self.tangents[corners[0]].w))
    }

    /// The three vertices of triangle `i`.
    #[inline]
    pub fn vertices(&self, i: u32) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[i as usize];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// The bounding box of triangle `i`.
    pub fn triangle_bounds(&self, i: u32) -> Aabb {
        Aabb::from_points(self.vertices(i))
    }

    /// The bounding box of the whole mesh.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.positions.iter().copied())
    }
}
