//! Scene files for lucent: the readable TOML format, mesh files, and the build into a
//! render-time [`lucent::scene::Scene`].
//!
//! The flow is one way: text → [`desc::SceneDesc`] (plain data with locations) →
//! [`build::build`] (names resolved, values checked, meshes read) → `Scene`. Every error is a
//! [`LoadError`] naming the file, the line and column where there is one, and the cause.
//!
//! The format is documented in `docs/scene-format.md`.

pub mod build;
pub mod desc;
pub mod error;
pub mod framing;
pub mod gltf_file;
pub mod hash;
pub mod ies;
pub mod images;
pub mod import;
pub mod input;
pub mod limits;
pub mod mesh_file;
pub mod mesh_import;
pub mod mitsuba;
pub mod mtl;
pub mod obj;
pub mod overrides;
pub mod paths;
pub mod ply;
pub mod povray;
pub mod serialized;
pub mod tangents;
pub mod vol;

pub use build::{Loaded, build};
pub use desc::SceneDesc;
pub use error::{LoadError, Source};
pub use import::Imported;
pub use limits::{Limit, Limits};
pub use paths::LoadOptions;
pub use toml::Spanned;

use std::path::{Path, PathBuf};

/// The built-in default scene: Whitted's 1980 picture (also `examples/whitted.toml`).
pub const DEFAULT_SCENE: &str = include_str!("../../../examples/whitted.toml");

/// The built-in moving scene, for frameless displays and their study: balls sliding,
/// orbiting and bobbing over a checkerboard, a turning box, a slowly circling camera (also
/// `examples/moving.toml`; a test holds the two alike).
pub const MOVING_SCENE: &str = include_str!("moving_scene.toml");

/// A scene file read and parsed, not yet built (so its settings can still be overridden):
/// lucent's TOML, or a file of another format imported into the same description.
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The path as given (the default scene: `<built-in default scene>`).
    pub path: PathBuf,
    /// The folder that relative file names start from.
    pub base_dir: PathBuf,
    /// The file's text (empty for imported files: their errors name lines themselves).
    pub text: String,
    /// The parsed description.
    pub desc: SceneDesc,
    /// Whether the file gives a camera; if not, one frames the scene's bounds.
    pub camera_given: bool,
    /// How a scene without a camera is framed (see [`SceneFile::set_framing`]).
    framing: framing::Framing,
    /// The up axis guessed for a bare OBJ or PLY mesh, and why.
    up_guess: Option<framing::UpGuess>,
    /// The light added to a scene without any, which turns with the framing.
    default_light: Option<usize>,
    /// What the import could not render as written.
    pub warnings: Vec<String>,
    /// Path rules for the files it names.
    pub options: LoadOptions,
    /// Fingerprint of the files read while importing.
    imported: u64,
    /// Mesh files the import already parsed, for the build.
    preloaded: mesh_file::MeshFiles,
}

/// The scene formats lucent reads, by extension.
pub const SCENE_EXTENSIONS: [&str; 7] = ["toml", "obj", "ply", "gltf", "glb", "xml", "pov"];

/// An error when `desc` holds more objects than the budget allows, before they are built.
fn within_objects_budget(
    path: &Path,
    desc: &SceneDesc,
    options: &LoadOptions,
) -> Result<(), LoadError> {
    options
        .limits
        .check(Limit::Objects, desc.objects.len() as u64, |n| {
            format!("the scene has {n} objects")
        })
        .map_err(|e| LoadError::file(path, e))
}

impl SceneFile {
    /// Reads the scene file at `path` (TOML, OBJ, PLY, glTF, GLB or Mitsuba XML).
    pub fn read(path: &Path) -> Result<Self, LoadError> {
        Self::read_with(path, &LoadOptions::default())
    }

    /// [`SceneFile::read`] with path rules.
    pub fn read_with(path: &Path, options: &LoadOptions) -> Result<Self, LoadError> {
        let base_dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
        let ext = mesh_file::extension(path);
        if !path.is_file() {
            return Err(LoadError::file(path, "no such scene file"));
        }
        let mut inputs = hash::Fingerprint::default();
        let mut preloaded = mesh_file::MeshFiles::default();
        let imported = match ext.as_deref() {
            Some("toml") | None => None,
            Some("obj") => Some(mesh_import::import_obj(
                path,
                options,
                &mut inputs,
                &mut preloaded,
            )?),
            Some("ply") => Some(mesh_import::import_ply(path)),
            Some("gltf" | "glb") => Some(gltf_file::import_gltf(path, options, &mut inputs)?),
            Some("xml") => Some(mitsuba::import_mitsuba(path, options, &mut inputs)?),
            Some("pov") => Some(povray::import_povray(path, options, &mut inputs)?),
            Some(other) => {
                return Err(LoadError::file(
                    path,
                    format!(
                        "unknown scene format `.{other}` (lucent reads .toml, .obj, .ply, .gltf, .glb, Mitsuba .xml and POV-Ray .pov)"
                    ),
                ));
            }
        };
        let Some(imported) = imported else {
            let bytes = crate::input::read(path)
                .map_err(|e| LoadError::file(path, format!("cannot read the scene file: {e}")))?;
            let text = String::from_utf8(bytes).map_err(|e| {
                LoadError::file(path, format!("the scene file is not UTF-8 text: {e}"))
            })?;
            let mut file = Self::parse(path.to_path_buf(), base_dir, text)?;
            file.options = *options;
            within_objects_budget(path, &file.desc, options)?;
            return Ok(file);
        };
        within_objects_budget(path, &imported.desc, options)?;
        // OBJ and PLY files do not say which way is up (glTF is +y up by its specification,
        // Mitsuba scenes place their own cameras): the geometry is asked. The parsed OBJ is
        // reused; a PLY file is decoded once more by the build.
        let up_guess = match ext.as_deref() {
            Some("obj" | "ply") if !imported.camera_given => {
                let mesh = preloaded.clone().read_part(
                    path,
                    None,
                    options,
                    &mut hash::Fingerprint::default(),
                )?;
                Some(framing::guess_up(&mesh.positions, &mesh.triangles))
            }
            _ => None,
        };
        let mut file = Self::from_import(path, base_dir, imported, options, inputs, preloaded);
        if let Some(g) = up_guess {
            file.up_guess = Some(g);
            file.set_framing(framing::Framing {
                up: g.up,
                view: framing::View::Front,
            });
        }
        Ok(file)
    }

    /// A scene of Mitsuba 3 XML given as text (not read from a file): `path` names it in
    /// errors (`<string>`), and relative file names in it start from `base_dir`.
    pub fn parse_mitsuba(
        path: PathBuf,
        base_dir: PathBuf,
        text: String,
    ) -> Result<Self, LoadError> {
        let options = LoadOptions::default();
        let mut inputs = hash::Fingerprint::default();
        let imported =
            mitsuba::import_mitsuba_text(&path, base_dir.clone(), text, &options, &mut inputs)?;
        within_objects_budget(&path, &imported.desc, &options)?;
        Ok(Self::from_import(
            &path,
            base_dir,
            imported,
            &options,
            inputs,
            mesh_file::MeshFiles::default(),
        ))
    }

    /// The scene of an imported file (within the objects' budget): a default light where it
    /// has none.
    fn from_import(
        path: &Path,
        base_dir: PathBuf,
        mut imported: import::Imported,
        options: &LoadOptions,
        inputs: hash::Fingerprint,
        preloaded: mesh_file::MeshFiles,
    ) -> Self {
        let desc = &mut imported.desc;
        let emits = desc
            .materials
            .iter()
            .any(|m| m.get_ref().emission.is_some());
        let mut default_light = None;
        if desc.lights.is_empty() && !emits && !imported.lit_as_given {
            import::add_default_light(desc);
            default_light = Some(desc.lights.len() - 1);
        }
        Self {
            path: path.to_path_buf(),
            base_dir,
            text: String::new(),
            desc: imported.desc,
            camera_given: imported.camera_given,
            framing: framing::Framing::default(),
            up_guess: None,
            default_light,
            warnings: imported.warnings,
            options: *options,
            imported: inputs.value(),
            preloaded,
        }
    }

    /// How a scene without a camera is framed: the up axis (guessed for OBJ and PLY files,
    /// +y for others) and the view.
    pub fn framing(&self) -> framing::Framing {
        self.framing
    }

    /// The up axis guessed for an OBJ or PLY file without a camera, and why (`None` for other
    /// scenes: nothing was guessed).
    pub fn up_guess(&self) -> Option<framing::UpGuess> {
        self.up_guess
    }

    /// Frames a scene without a camera this way, turning the default light (if it has it) to
    /// stay at the upper left behind the camera. A scene with a camera keeps it: the framing
    /// changes nothing there.
    pub fn set_framing(&mut self, framing: framing::Framing) {
        self.framing = framing;
        if self.camera_given {
            return;
        }
        if let Some(light) = self.default_light.and_then(|i| self.desc.lights.get_mut(i)) {
            let direction = desc::Vector(framing.light_direction());
            light.get_mut().direction = Some(toml::Spanned::new(0..0, direction));
        }
    }

    /// The built-in default scene; relative paths in it start from the working directory.
    pub fn default_scene() -> Self {
        Self::parse(
            PathBuf::from("<built-in default scene>"),
            PathBuf::new(),
            DEFAULT_SCENE.to_string(),
        )
        .expect("the built-in default scene parses (checked by a test)")
    }

    /// The built-in moving scene ([`MOVING_SCENE`]); relative paths in it start from the
    /// working directory.
    pub fn moving_scene() -> Self {
        Self::parse(
            PathBuf::from("<built-in moving scene>"),
            PathBuf::new(),
            MOVING_SCENE.to_string(),
        )
        .expect("the built-in moving scene parses (checked by a test)")
    }

    /// Parses `text` as a TOML scene file named `path`.
    pub fn parse(path: PathBuf, base_dir: PathBuf, text: String) -> Result<Self, LoadError> {
        let desc = toml::from_str::<SceneDesc>(&text).map_err(|e| {
            let source = Source {
                path: &path,
                text: &text,
            };
            // toml's messages may span lines (a snippet of the file); keep the first.
            let message = e
                .message()
                .lines()
                .next()
                .unwrap_or("invalid TOML")
                .to_string();
            match e.span() {
                Some(span) => source.error(span, message),
                None => LoadError::file(&path, message),
            }
        })?;
        Ok(Self {
            path,
            base_dir,
            text,
            desc,
            camera_given: true,
            framing: framing::Framing::default(),
            up_guess: None,
            default_light: None,
            warnings: Vec::new(),
            options: LoadOptions::default(),
            imported: 0,
            preloaded: mesh_file::MeshFiles::default(),
        })
    }

    /// Checks the description and builds the scene; a scene without a camera gets one that
    /// frames its bounds.
    pub fn build(&self) -> Result<Loaded, LoadError> {
        let source = Source {
            path: &self.path,
            text: &self.text,
        };
        let mut loaded = build::build_with_files(
            &self.desc,
            &source,
            &self.base_dir,
            &self.options,
            self.preloaded.clone(),
        )?;
        if !self.camera_given {
            // Framed in the built scene's coordinates (its bounds are).
            let c = &loaded.scene.camera;
            let c = self
                .framing
                .camera(loaded.scene.bounds(), c.width(), c.height());
            loaded.scene.camera = lucent::camera::Camera::new(
                c.eye.0.as_vec3(),
                c.look_at.0.as_vec3(),
                c.up.0,
                c.fov.0,
                loaded.scene.camera.width(),
                loaded.scene.camera.height(),
            )
            .map_err(|e| LoadError::file(&self.path, e.to_string()))?;
        }
        let mut warnings = self.warnings.clone();
        warnings.append(&mut loaded.warnings);
        loaded.warnings = warnings;
        let mut inputs = hash::Fingerprint::default();
        inputs.add(&loaded.inputs.to_le_bytes());
        inputs.add(&self.imported.to_le_bytes());
        loaded.inputs = inputs.value();
        Ok(loaded)
    }

    /// The camera a scene without one gets, framing the built scene's bounds as
    /// [`SceneFile::framing`] says.
    pub fn framing_camera(&self, loaded: &Loaded) -> desc::CameraDesc {
        let c = &loaded.scene.camera;
        let mut framed = self
            .framing
            .camera(loaded.scene.bounds(), c.width(), c.height());
        // In the file's world, as a camera of the file would be.
        let origin = loaded.scene.origin();
        framed.eye.0 += origin;
        framed.look_at.0 += origin;
        framed
    }

    /// Names every file of the description from `dir` instead of the scene's folder (for a
    /// converted scene written elsewhere): relative when both folders can be resolved, else
    /// absolute.
    pub fn rebase(&mut self, dir: &Path) -> std::io::Result<()> {
        // A scene named without a folder is in the current one.
        let from = std::path::absolute(Path::new(".").join(&self.base_dir))?;
        let to = std::path::absolute(dir)?;
        let rename = |name: &mut String| {
            let full = from.join(&*name);
            *name = paths::relative_to(&full, &to)
                .to_string_lossy()
                .replace('\\', "/");
        };
        let d = &mut self.desc;
        for o in &mut d.objects {
            if let Some(f) = o.get_mut().file.as_mut() {
                rename(f.get_mut());
            }
        }
        for l in &mut d.lights {
            if let Some(f) = l.get_mut().file.as_mut() {
                rename(f.get_mut());
            }
        }
        for m in &mut d.materials {
            for t in m.get_mut().textures_mut() {
                t.files_mut(&mut |f| rename(f));
            }
        }
        self.base_dir = dir.to_path_buf();
        Ok(())
    }

    /// The description as lucent's TOML: an imported scene's own description, with the
    /// framing camera written out when it had none (its meshes stay in their files).
    pub fn to_toml(&self, loaded: &Loaded) -> Result<String, LoadError> {
        let mut desc = self.desc.clone();
        if !self.camera_given {
            desc.camera = toml::Spanned::new(0..0, self.framing_camera(loaded));
        }
        toml::to_string(&desc).map_err(|e| {
            LoadError::file(&self.path, format!("cannot write the scene as TOML: {e}"))
        })
    }
}

/// The folder of shared test data (meshes no one here wrote): `$LUCENT_DATA` if set, else
/// `../shared/data` beside the workspace root. Tests and benchmarks that need it skip, with a
/// message, where it is absent.
pub fn data_dir() -> PathBuf {
    match std::env::var_os("LUCENT_DATA") {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"),
    }
}
