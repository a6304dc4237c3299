//! Mesh files by extension: `.obj` (Wavefront) and `.ply` (Stanford).

use crate::error::LoadError;
use crate::hash::Fingerprint;
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
    read_mesh_fingerprinted(path, &mut Fingerprint::default())
}

/// [`read_mesh`], adding the file's bytes to `fingerprint`.
pub fn read_mesh_fingerprinted(
    path: &Path,
    fingerprint: &mut Fingerprint,
) -> Result<Mesh, LoadError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("obj" | "ply")) {
        return Err(LoadError::file(
            path,
            "unknown mesh format (use .obj or .ply)",
        ));
    }
    let bytes = std::fs::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    fingerprint.add(&bytes);
    if ext.as_deref() == Some("obj") {
        let m = crate::obj::parse_obj(&String::from_utf8_lossy(&bytes), path)?;
        Ok(Mesh::new(m.positions, m.triangles))
    } else {
        let m = crate::ply::parse_ply(&bytes, path)?;
        Ok(Mesh::new(m.positions, m.triangles))
    }
}
