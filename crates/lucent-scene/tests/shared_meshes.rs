//! Every mesh of `../shared/data/meshes` loads with the counts its own file states: vertex and
//! face lines of the OBJs, the header and strips of igea's PLY, counted here independently.

use lucent_scene::mesh_file::read_mesh;
use lucent_scene::{data_dir, obj, ply};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

fn meshes() -> Option<PathBuf> {
    let dir = data_dir().join("meshes");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: {} is not here", dir.display());
        None
    }
}

/// Vertex lines and the triangles of the face lines (a face of n corners makes n − 2).
fn obj_counts(text: &str) -> (usize, usize) {
    let (mut vertices, mut triangles) = (0, 0);
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices += 1,
            Some("f") => triangles += words.count() - 2,
            _ => {}
        }
    }
    (vertices, triangles)
}

#[test]
fn every_obj_has_the_counts_of_its_lines() {
    let Some(dir) = meshes() else { return };
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "obj") {
            continue;
        }
        let bytes = std::fs::read(&path).unwrap();
        let (vertices, triangles) = obj_counts(&String::from_utf8_lossy(&bytes));
        let file = obj::parse_obj(&bytes, &path).unwrap();
        assert_eq!(file.positions.len(), vertices, "{}", path.display());
        assert_eq!(file.triangle_count(), triangles, "{}", path.display());
        let mesh = read_mesh(&path).unwrap();
        assert_eq!(mesh.triangles.len(), triangles, "{}", path.display());
        // One mesh vertex per distinct corner: never fewer than the positions used.
        let used: HashSet<[u32; 3]> = mesh
            .triangles
            .iter()
            .flatten()
            .map(|&i| mesh.positions[i as usize].to_array().map(f32::to_bits))
            .collect();
        assert!(mesh.positions.len() >= used.len(), "{}", path.display());
        mesh.validate().unwrap();
        seen += 1;
    }
    assert_eq!(seen, 6, "the six OBJ files of the data folder");
}

/// igea's header, then its one `tristrips` list read by hand: (vertices, strips' indices).
fn igea_by_hand(bytes: &[u8]) -> (usize, Vec<i32>) {
    let end = b"end_header\n";
    let body = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let header = std::str::from_utf8(&bytes[..body]).unwrap();
    assert!(header.contains("format binary_little_endian 1.0"));
    assert!(header.contains("element tristrips 1\nproperty list int int vertex_indices"));
    let vertices: usize = header
        .lines()
        .find_map(|l| l.strip_prefix("element vertex "))
        .unwrap()
        .parse()
        .unwrap();
    let props = header.matches("property float").count();
    let list = &bytes[body + vertices * 4 * props..];
    let int = |k: usize| i32::from_le_bytes(list[4 * k..4 * k + 4].try_into().unwrap());
    let n = int(0) as usize;
    assert_eq!(list.len(), 4 * (n + 1), "the strips end the file");
    (vertices, (1..=n).map(int).collect())
}

#[test]
fn igea_strips_expand_to_their_triangles() {
    let Some(dir) = meshes() else { return };
    let path = dir.join("igea.ply");
    let bytes = std::fs::read(&path).unwrap();
    let (vertices, strips) = igea_by_hand(&bytes);
    // Triangle k of a strip uses s[k], s[k+1], s[k+2]; those repeating a vertex are dropped.
    let expected: usize = strips
        .split(|&i| i == -1)
        .flat_map(|s| s.windows(3))
        .filter(|w| w[0] != w[1] && w[1] != w[2] && w[0] != w[2])
        .count();
    let mesh = ply::parse_ply(&bytes, &path).unwrap();
    assert_eq!(mesh.positions.len(), vertices);
    assert_eq!(mesh.triangles.len(), expected);
    assert!(expected > 250_000, "{expected}");
    // Alternating winding keeps the surface consistently oriented: neighbours cross their
    // shared edge in opposite directions, so a directed edge is almost never used twice (it
    // would be for half the triangles if the winding did not alternate).
    let mut edges = HashSet::new();
    let mut repeated = 0;
    for t in &mesh.triangles {
        for k in 0..3 {
            if !edges.insert((t[k], t[(k + 1) % 3])) {
                repeated += 1;
            }
        }
    }
    assert!(
        repeated * 1000 < 3 * mesh.triangles.len(),
        "{repeated} repeated edges"
    );
    read_mesh(Path::new(&path)).unwrap().validate().unwrap();
}
