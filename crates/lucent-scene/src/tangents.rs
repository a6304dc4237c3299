//! MikkTSpace tangent frames for meshes that come without them, so that normal maps baked
//! against MikkTSpace (glTF's rule, and what Blender and Substance bake with) are read in the
//! frame they were made in.
//!
//! MikkTSpace is run on uvs with `v` flipped to grow upwards (the meshes hold glTF's `v` that
//! grows downwards), so its bitangent, `w·(n × t)`, points up the image as a normal map's `+y`
//! does. It gives each corner of each triangle a frame; corners that share a vertex but not a
//! frame (at a mirrored seam) get vertices of their own.

use bevy_mikktspace::Geometry;
use glam::{Vec3, Vec4};
use lucent::shape::Mesh;
use std::collections::HashMap;

/// The mesh seen by MikkTSpace, collecting the frame of every corner.
struct Corners<'a> {
    mesh: &'a Mesh,
    frames: Vec<Vec4>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.triangles[face][vert] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let uv = self.mesh.uvs[self.vertex(face, vert)];
        [uv.x, 1.0 - uv.y]
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        self.frames[3 * face + vert] = Vec4::from_array(tangent);
    }
}

/// Gives `mesh` MikkTSpace's tangents (splitting vertices whose corners disagree). `false`,
/// the mesh unchanged, when it has no normals or uvs, or MikkTSpace finds no frame.
pub fn generate(mesh: &mut Mesh) -> bool {
    if mesh.normals.is_empty() || mesh.uvs.is_empty() || mesh.triangles.is_empty() {
        return false;
    }
    let mut corners = Corners {
        mesh,
        frames: vec![Vec4::ZERO; 3 * mesh.triangles.len()],
    };
    if !bevy_mikktspace::generate_tangents(&mut corners) {
        return false;
    }
    let frames = corners.frames;
    if frames.iter().any(|f| !f.is_finite()) {
        return false;
    }
    // One vertex per (vertex, frame) pair: a vertex whose corners agree stays one.
    let mut tangents: Vec<Option<Vec4>> = vec![None; mesh.positions.len()];
    let mut copies: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    for (k, frame) in frames.into_iter().enumerate() {
        let (face, vert) = (k / 3, k % 3);
        let v = mesh.triangles[face][vert];
        match tangents[v as usize] {
            None => tangents[v as usize] = Some(frame),
            Some(t) if t == frame => {}
            Some(_) => {
                let key = (v, frame.to_array().map(f32::to_bits));
                let copy = *copies.entry(key).or_insert_with(|| {
                    let i = mesh.positions.len() as u32;
                    duplicate(mesh, v as usize);
                    tangents.push(Some(frame));
                    i
                });
                mesh.triangles[face][vert] = copy;
            }
        }
    }
    mesh.tangents = tangents
        .into_iter()
        // A vertex no triangle uses gets any frame.
        .map(|t| t.unwrap_or(Vec4::new(1.0, 0.0, 0.0, 1.0)))
        .map(|t| {
            let xyz = t.truncate().try_normalize().unwrap_or(Vec3::X);
            xyz.extend(if t.w < 0.0 { -1.0 } else { 1.0 })
        })
        .collect();
    true
}

/// Appends a copy of vertex `v` with all its attributes.
fn duplicate(mesh: &mut Mesh, v: usize) {
    mesh.positions.push(mesh.positions[v]);
    mesh.normals.push(mesh.normals[v]);
    mesh.uvs.push(mesh.uvs[v]);
    if !mesh.colors.is_empty() {
        mesh.colors.push(mesh.colors[v]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A unit quad facing +z, uvs as glTF's (v down the image, so up the quad is −v).
    fn quad(mirror_right_half: bool) -> Mesh {
        let mut m = Mesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        m.normals = vec![Vec3::Z; 4];
        m.uvs = vec![
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
        ];
        if mirror_right_half {
            // u runs right to left: the image is mirrored.
            for uv in &mut m.uvs {
                uv.x = 1.0 - uv.x;
            }
        }
        m
    }

    #[test]
    fn an_upright_quad_gets_u_as_tangent_and_a_right_handed_frame() {
        let mut m = quad(false);
        assert!(generate(&mut m));
        assert_eq!(m.tangents.len(), 4);
        for t in &m.tangents {
            assert!((t.truncate() - Vec3::X).length() < 1e-4, "{t}");
            // n × t = +y: up the quad, up the image.
            assert_eq!(t.w, 1.0);
        }
    }

    #[test]
    fn mirrored_uvs_flip_the_handedness() {
        let mut m = quad(true);
        assert!(generate(&mut m));
        for t in &m.tangents {
            assert!((t.truncate() + Vec3::X).length() < 1e-4, "{t}");
            // n × t = −y, but up the image is still +y.
            assert_eq!(t.w, -1.0);
        }
    }

    #[test]
    fn a_mesh_without_uvs_is_left_alone() {
        let mut m = quad(false);
        m.uvs.clear();
        assert!(!generate(&mut m));
        assert!(m.tangents.is_empty());
    }
}
