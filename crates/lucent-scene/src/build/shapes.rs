//! The unit shapes of `[[object]]` kinds `rectangle`, `cube` and `disk`, as meshes with texture
//! coordinates (Mitsuba's shapes, placed by a transform). Rectangles and cubes carry no vertex
//! normals: each face's own normal is exactly an axis, and a hit then neither interpolates nor
//! transforms a second one. A disk keeps its normals (`+z`): its fan's faces, cut by rounded
//! sines and cosines, are an ulp off the axis. A rectangle's
//! `(u, v) = ((x + 1)/2, (1 − y)/2)`: image rows run downwards, so an image stands upright on
//! it; an object's `flip_v` gives Mitsuba's `v = (y + 1)/2`. A disk's are planar (Mitsuba's
//! polar), each cube face a rectangle's.

use glam::{Vec2, Vec3};
use lucent::shape::Mesh;

/// Segments around a disk's rim.
pub const DISK_SEGMENTS: u32 = 64;

/// The square `[-1, 1]²` in the plane z = 0, facing +z.
pub fn rectangle() -> Mesh {
    let positions = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ];
    let uvs = positions
        .iter()
        .map(|p| Vec2::new(0.5 * (p.x + 1.0), 0.5 * (1.0 - p.y)))
        .collect();
    Mesh {
        positions,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        normals: vec![],
        uvs,
        colors: vec![],
        tangents: vec![],
    }
}

/// The cube `[-1, 1]³`, each face facing out, with its own four vertices.
pub fn cube() -> Mesh {
    let mut mesh = Mesh::default();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            // Two in-face directions whose cross product is the outward normal.
            let mut u = Vec3::ZERO;
            u[(axis + 1) % 3] = 1.0;
            let v = n.cross(u);
            let base = mesh.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(n + a * u + b * v);
                mesh.uvs.push(Vec2::new(0.5 * (a + 1.0), 0.5 * (1.0 - b)));
            }
            mesh.triangles.push([base, base + 1, base + 2]);
            mesh.triangles.push([base, base + 2, base + 3]);
        }
    }
    mesh
}

/// The disk of radius 1 in the plane z = 0, facing +z, as a fan of `DISK_SEGMENTS` triangles.
pub fn disk() -> Mesh {
    let mut mesh = Mesh::default();
    mesh.positions.push(Vec3::ZERO);
    for i in 0..DISK_SEGMENTS {
        let a = i as f32 / DISK_SEGMENTS as f32 * std::f32::consts::TAU;
        mesh.positions.push(Vec3::new(a.cos(), a.sin(), 0.0));
        mesh.triangles.push([0, 1 + i, 1 + (i + 1) % DISK_SEGMENTS]);
    }
    mesh.normals = vec![Vec3::Z; mesh.positions.len()];
    mesh.uvs = mesh
        .positions
        .iter()
        .map(|p| Vec2::new(0.5 * (p.x + 1.0), 0.5 * (1.0 - p.y)))
        .collect();
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use lucent::shape::triangle;

    fn area_and_outwardness(mesh: &Mesh) -> (f32, bool) {
        let mut area = 0.0;
        let mut outward = true;
        for t in 0..mesh.triangles.len() as u32 {
            let v = mesh.vertices(t);
            area += 0.5 * triangle::double_area(v) as f32;
            let n = (v[1] - v[0]).cross(v[2] - v[0]);
            let centre = (v[0] + v[1] + v[2]) / 3.0;
            outward &= n.dot(centre) > 0.0 || n.dot(Vec3::Z) > 0.0;
        }
        (area, outward)
    }

    #[test]
    fn unit_shapes_have_their_areas_and_face_out() {
        let (a, out) = area_and_outwardness(&rectangle());
        assert!((a - 4.0).abs() < 1e-6 && out);
        let (a, out) = area_and_outwardness(&cube());
        assert!((a - 24.0).abs() < 1e-5 && out);
        let (a, _) = area_and_outwardness(&disk());
        let polygon =
            0.5 * DISK_SEGMENTS as f32 * (std::f32::consts::TAU / DISK_SEGMENTS as f32).sin();
        assert!((a - polygon).abs() < 1e-4);
        for m in [rectangle(), cube(), disk()] {
            m.validate().unwrap();
        }
        // Without vertex normals, shading uses the faces' own: exact axes.
        for m in [rectangle(), cube()] {
            assert!(m.normals.is_empty());
            for t in 0..m.triangles.len() as u32 {
                let n = triangle::normal(m.vertices(t)).unwrap();
                assert_eq!(n.abs().max_element(), 1.0, "{n}");
            }
        }
    }
}
