//! Mesh files by extension: `.obj` (Wavefront) and `.ply` (Stanford).

use crate::error::LoadError;
use lucent::shape::Mesh;
use std::path::Path;

/// The extensions [`read_mesh`] knows.
pub const MESH_EXTENSIONS: [&str; 2] = ["obj", "ply"];

/// True when `path` has a mesh file's extension.
pub fn is_mesh_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.iter().any(|m| m.eq_ignore_ascii_case(e)))
}

/// The positions and triangles of the mesh file at `path`.
pub fn read_mesh(path: &Path) -> Result<Mesh, LoadError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => crate::obj::read_obj(path).map(|m| Mesh {
            positions: m.positions,
            triangles: m.triangles,
        }),
        Some("ply") => crate::ply::read_ply(path).map(|m| Mesh {
            positions: m.positions,
            triangles: m.triangles,
        }),
        _ => Err(LoadError::file(
            path,
            "unknown mesh format (use .obj or .ply)",
        )),
    }
}
