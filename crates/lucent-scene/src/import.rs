//! What an importer (OBJ, PLY, glTF, Mitsuba XML) gives: a scene description like the TOML
//! reader's, whose relative file names start from the imported file's folder — and the pieces
//! a scene without a camera or lights gets.

use crate::desc::{
    CameraDesc, Color, Finite, LightDesc, LightKind, MaterialDesc, ObjectDesc, ObjectKind, Point,
    SceneDesc, Vector,
};
use crate::error::LoadError;
use crate::framing::Framing;
use crate::hash::Fingerprint;
use crate::paths::LoadOptions;
use glam::Vec3;
use lucent::Rgb;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A scene read from a foreign format.
#[derive(Clone, Debug)]
pub struct Imported {
    /// The scene. When `camera_given` is false its camera is a placeholder, replaced by one
    /// framing the scene's bounds.
    pub desc: SceneDesc,
    /// Whether the file had a camera.
    pub camera_given: bool,
    /// What was read but cannot be rendered as written (one line each, naming the file).
    pub warnings: Vec<String>,
}

/// A placeholder camera, for files without one.
pub fn placeholder_camera() -> Spanned<CameraDesc> {
    Spanned::new(
        0..0,
        CameraDesc {
            eye: Point(glam::DVec3::Z),
            look_at: Point(glam::DVec3::ZERO),
            up: Vector(Vec3::Y),
            fov: Finite(45.0),
            aperture: None,
            focus_distance: None,
            orthographic: None,
            motion: None,
            shutter: None,
        },
    )
}

/// The light a scene without any gets: white, travelling away from the upper left behind a
/// framing camera (of the default [`Framing`]: [`crate::SceneFile::set_framing`] turns it with
/// the camera), with a little ambient light.
pub fn add_default_light(desc: &mut SceneDesc) {
    let mut light = LightDesc::new(LightKind::Directional);
    let direction = Framing::default().light_direction();
    light.direction = Some(Spanned::new(0..0, Vector(direction)));
    desc.lights.push(Spanned::new(0..0, light));
    desc.world.ambient = Color(Rgb::gray(0.1));
    desc.world.background = Color(Rgb::gray(0.05));
}

/// The material of mesh files without their own: a light grey with a soft highlight.
pub fn default_material(name: &str) -> MaterialDesc {
    let mut m = MaterialDesc::named(name);
    m.ka = Some(Color(Rgb::gray(0.8)));
    m.kd = Some(crate::desc::TextureDesc::gray(0.8));
    m.ks = Some(Color(Rgb::gray(0.2)));
    m.shininess = Some(Spanned::new(0..0, Finite(30.0)));
    m
}

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
    })
}
