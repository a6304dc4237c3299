//! Triangle meshes as flat arrays: positions and index triples.

use glam::Vec3;
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
}

impl Mesh {
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
