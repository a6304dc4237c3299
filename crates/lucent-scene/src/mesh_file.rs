//! Mesh files by extension: `.obj` (Wavefront), `.ply` (Stanford), `.gltf` and `.glb` (glTF 2.0),
//! `.serialized` (Mitsuba).

use crate::error::LoadError;
use crate::gltf_file::GltfFile;
use crate::hash::Fingerprint;
use crate::limits::{Limit, Limits};
use crate::obj::ObjFile;
use crate::paths::LoadOptions;
use glam::Vec3;
use lucent::Rgb;
use lucent::film::tonemap::srgb_to_linear;
use lucent::shape::Mesh;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The extensions [`read_mesh`] knows.
pub const MESH_EXTENSIONS: [&str; 5] = ["obj", "ply", "gltf", "glb", "serialized"];

/// The lower-case extension of `path`.
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// True when `path` has a mesh file's extension.
pub fn is_mesh_file(path: &Path) -> bool {
    extension(path).is_some_and(|e| MESH_EXTENSIONS.contains(&e.as_str()))
}

/// The mesh in the file at `path` (every face; a glTF file's scene placed by its nodes).
pub fn read_mesh(path: &Path) -> Result<Mesh, LoadError> {
    read_mesh_part(
        path,
        None,
        &LoadOptions::default(),
        &mut Fingerprint::default(),
    )
}

/// The mesh of `part` of the file at `path` (see `[[object]] part` in the scene format; `None`:
/// all of it), adding the bytes read to `fingerprint`.
pub fn read_mesh_part(
    path: &Path,
    part: Option<&str>,
    options: &LoadOptions,
    fingerprint: &mut Fingerprint,
) -> Result<Mesh, LoadError> {
    MeshFiles::default().read_part(path, part, options, fingerprint)
}

/// Mesh files read so far: an OBJ file split into parts by material, or a glTF file of many
/// primitives, is read once, not once per part.
#[derive(Clone, Default)]
pub struct MeshFiles {
    obj: HashMap<PathBuf, Arc<ObjFile>>,
    gltf: HashMap<PathBuf, Arc<GltfFile>>,
    /// Vertices and triangles of the meshes read so far.
    stored: u64,
}

impl std::fmt::Debug for MeshFiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MeshFiles")
            .field("obj", &self.obj.keys().collect::<Vec<_>>())
            .field("gltf", &self.gltf.keys().collect::<Vec<_>>())
            .finish()
    }
}

impl MeshFiles {
    /// Keeps `obj`, parsed from the file at `path`, for the build to use instead of reading
    /// the file again.
    pub fn keep_obj(&mut self, path: &Path, obj: Arc<ObjFile>) {
        self.obj.insert(path.to_path_buf(), obj);
    }

    /// As [`read_mesh_part`], reusing OBJ and glTF files already read (their bytes are added
    /// to the fingerprint the first time only), within the scene's geometry budget
    /// (`options.limits.geometry`).
    pub fn read_part(
        &mut self,
        path: &Path,
        part: Option<&str>,
        options: &LoadOptions,
        fingerprint: &mut Fingerprint,
    ) -> Result<Mesh, LoadError> {
        let mesh = self.decode_part(path, part, options, fingerprint)?;
        // A budget over every mesh stored: small files can name many large parts (glTF
        // accessors over one buffer, each a part of its own).
        self.stored += (mesh.positions.len() + mesh.triangles.len()) as u64;
        let limits = &options.limits;
        if self.stored > limits.geometry {
            return Err(LoadError::file(
                path,
                limits.exceeded(
                    Limit::Geometry,
                    format!(
                        "the scene's meshes come to {} vertices and triangles stored",
                        self.stored
                    ),
                ),
            ));
        }
        Ok(mesh)
    }

    /// The glTF file at `path`, read once (its bytes added to `fingerprint` the first time).
    pub fn gltf(
        &mut self,
        path: &Path,
        options: &LoadOptions,
        fingerprint: &mut Fingerprint,
    ) -> Result<Arc<GltfFile>, LoadError> {
        if let Some(file) = self.gltf.get(path) {
            return Ok(file.clone());
        }
        let file = Arc::new(GltfFile::open(path, options, fingerprint)?);
        self.gltf.insert(path.to_path_buf(), file.clone());
        Ok(file)
    }

    fn decode_part(
        &mut self,
        path: &Path,
        part: Option<&str>,
        options: &LoadOptions,
        fingerprint: &mut Fingerprint,
    ) -> Result<Mesh, LoadError> {
        let ext = extension(path);
        if matches!(ext.as_deref(), Some("gltf" | "glb")) {
            return self.gltf(path, options, fingerprint)?.part(part);
        }
        let mesh = match ext.as_deref() {
            Some("obj") => {
                let obj = match self.obj.get(path) {
                    Some(obj) => obj.clone(),
                    None => {
                        let obj = Arc::new(crate::obj::parse_obj(&read(path, fingerprint)?, path)?);
                        self.obj.insert(path.to_path_buf(), obj.clone());
                        obj
                    }
                };
                obj_part(&obj, part, path)?
            }
            Some("ply") => ply_mesh(&read(path, fingerprint)?, part, path)?,
            // The parts of a serialized file are its shapes, by index.
            Some("serialized") => {
                let index = crate::serialized::shape_index(part, path)?;
                // The shape's counts are checked against what the budget has left.
                let left = Limits {
                    geometry: options.limits.geometry.saturating_sub(self.stored),
                    ..options.limits
                };
                let bytes = read(path, fingerprint)?;
                crate::serialized::parse_serialized_within(&bytes, index, path, &left)?.mesh
            }
            _ => {
                return Err(LoadError::file(
                    path,
                    "unknown mesh format (use .obj, .ply, .gltf, .glb or .serialized)",
                ));
            }
        };
        mesh.validate().map_err(|e| LoadError::file(path, e))?;
        Ok(mesh)
    }
}

fn read(path: &Path, fingerprint: &mut Fingerprint) -> Result<Vec<u8>, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    fingerprint.add(&bytes);
    Ok(bytes)
}

/// The faces of an OBJ file that use the material `part` (all when `None`).
fn obj_part(obj: &ObjFile, part: Option<&str>, path: &Path) -> Result<Mesh, LoadError> {
    match part {
        None => Ok(obj.mesh(None).unwrap_or_default()),
        Some(name) => obj.mesh(Some(name)).ok_or_else(|| {
            let used = obj
                .used_materials()
                .iter()
                .map(|m| format!("`{m}`"))
                .collect::<Vec<_>>();
            LoadError::file(
                path,
                format!(
                    "no faces use the material `{name}` (parts: {})",
                    used.join(", ")
                ),
            )
        }),
    }
}

/// The mesh of PLY bytes, which have no parts.
fn ply_mesh(bytes: &[u8], part: Option<&str>, path: &Path) -> Result<Mesh, LoadError> {
    if let Some(name) = part {
        return Err(LoadError::file(
            path,
            format!("a PLY file has no parts, but part `{name}` was asked for"),
        ));
    }
    let m = crate::ply::parse_ply(bytes, path)?;
    let mut mesh = Mesh::new(m.positions, m.triangles);
    mesh.normals = m
        .normals
        .unwrap_or_default()
        .into_iter()
        .map(Vec3::normalize_or_zero)
        .collect();
    // PLY colours are 8-bit (or 0–1) sRGB values, as scanners and tools write them.
    mesh.colors = m
        .colors
        .unwrap_or_default()
        .into_iter()
        .map(|c| Rgb::from(c.map(srgb_to_linear)))
        .collect();
    Ok(mesh)
}
