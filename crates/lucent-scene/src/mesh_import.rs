//! A bare mesh file imported as a scene: an OBJ with its MTL libraries (one object per material
//! its faces use), or a PLY with the default material. Its triangles are read when the scene is
//! built, through `mesh_file`, which this reads the OBJ into so that it is parsed once.

use crate::desc::{ObjectDesc, ObjectKind, SceneDesc};
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::import::{Imported, default_material};
use crate::paths::LoadOptions;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// An empty description with a placeholder camera.
fn empty_desc() -> SceneDesc {
    toml::from_str::<SceneDesc>("camera = { eye = [0, 0, 1], look_at = [0, 0, 0] }")
        .expect("a camera alone is a scene")
}

/// The file name of `path`, as written in a description whose base folder is its own.
fn own_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// A PLY file: one mesh with the default material.
pub fn import_ply(path: &Path) -> Imported {
    let mut desc = empty_desc();
    desc.materials
        .push(Spanned::new(0..0, default_material("default")));
    let mut o = ObjectDesc::new(ObjectKind::Mesh, "default");
    o.file = Some(Spanned::new(0..0, own_name(path)));
    desc.objects.push(Spanned::new(0..0, o));
    Imported {
        desc,
        camera_given: false,
        warnings: vec![],
        lit_as_given: false,
    }
}

/// An OBJ file with its MTL libraries: one object per material its faces use.
pub fn import_obj(
    path: &Path,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
    files: &mut crate::mesh_file::MeshFiles,
) -> Result<Imported, LoadError> {
    let bytes = crate::input::read(path)
        .map_err(|e| LoadError::file(path, format!("cannot read the mesh file: {e}")))?;
    inputs.add(&bytes);
    let obj = std::sync::Arc::new(crate::obj::parse_obj(&bytes, path)?);
    // One object per material used: held to the budget before any is made.
    let used = obj.used_materials();
    options
        .limits
        .check(crate::limits::Limit::Objects, used.len() as u64, |n| {
            format!("the file's faces use {n} materials, an object each")
        })
        .map_err(|e| LoadError::file(path, e))?;
    // The build takes its parts from this parse rather than reading the file again.
    files.keep_obj(path, obj.clone());
    let folder = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    let mut warnings = Vec::new();
    // Every material of every library, with the library's folder (relative to the OBJ's).
    let mut library = Vec::new();
    for (name, line) in &obj.libraries {
        let lib_path = crate::paths::resolve(&folder, name, options)
            .map_err(|e| LoadError::line(path, *line, e))?;
        match crate::input::read(&lib_path) {
            Ok(b) => {
                inputs.add(&b);
                let dir = Path::new(name)
                    .parent()
                    .map_or_else(PathBuf::new, Path::to_path_buf);
                for m in crate::mtl::parse_mtl(&b, &lib_path)? {
                    library.push((m, dir.clone(), lib_path.clone()));
                }
            }
            Err(e) => warnings.push(format!(
                "{}:{line}: material library `{name}` cannot be read ({e}); its materials are grey",
                path.display()
            )),
        }
    }
    if obj.triangle_count() == 0 {
        warnings.push(format!("{}: the file has no faces", path.display()));
    }
    let mut desc = empty_desc();
    for (i, name) in used.iter().enumerate() {
        let our_name = if name.is_empty() {
            "default".to_string()
        } else {
            format!("obj:{name}")
        };
        let found = library.iter().find(|(m, _, _)| m.name == *name);
        let material = match found {
            Some((m, dir, lib_path)) => {
                let texture = match m.texture() {
                    Some(t) => {
                        let rel = dir.join(t).to_string_lossy().replace('\\', "/");
                        crate::paths::resolve(&folder, &rel, options)
                            .map_err(|e| LoadError::line(lib_path, m.line, e))?;
                        Some(rel)
                    }
                    None => None,
                };
                m.to_desc(&our_name, texture, &mut warnings)
            }
            None => {
                if !name.is_empty() {
                    warnings.push(format!(
                        "{}: material `{name}` is in no material library; it is grey",
                        path.display()
                    ));
                }
                default_material(&our_name)
            }
        };
        desc.materials.push(Spanned::new(0..0, material));
        let mut o = ObjectDesc::new(ObjectKind::Mesh, &our_name);
        o.file = Some(Spanned::new(0..0, own_name(path)));
        if used.len() > 1 {
            o.part = Some(Spanned::new(0..0, used[i].to_string()));
        }
        desc.objects.push(Spanned::new(0..0, o));
    }
    Ok(Imported {
        desc,
        camera_given: false,
        warnings,
        lit_as_given: false,
    })
}
