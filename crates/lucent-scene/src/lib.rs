//! Scene files for lucent: the readable TOML format, mesh files, and the build into a
//! render-time [`lucent::scene::Scene`].
//!
//! The flow is one way: text → [`desc::SceneDesc`] (plain data with locations) →
//! [`build::build`] (names resolved, values checked, meshes read) → `Scene`. Every error is a
//! [`LoadError`] naming the file, the line and column where there is one, and the cause.
//!
//! The format is documented in `docs/scene-format.md`.

pub mod bare_mesh;
pub mod build;
pub mod desc;
pub mod error;
pub mod hash;
pub mod import;
pub mod materials;
pub mod mesh_file;
pub mod obj;
pub mod paths;
pub mod ply;

pub use bare_mesh::bare_mesh_scene;
pub use build::{Loaded, build};
pub use desc::SceneDesc;
pub use error::{LoadError, Source};
pub use import::Imported;
pub use paths::LoadOptions;
pub use toml::Spanned;

use std::path::{Path, PathBuf};

/// The built-in default scene: Whitted's 1980 picture (also `examples/whitted.toml`).
pub const DEFAULT_SCENE: &str = include_str!("../../../examples/whitted.toml");

/// A scene file read and parsed, not yet built (so its settings can still be overridden).
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The path as given (the default scene: `<built-in default scene>`).
    pub path: PathBuf,
    /// The folder that relative mesh paths start from.
    pub base_dir: PathBuf,
    /// The file's text.
    pub text: String,
    /// The parsed description.
    pub desc: SceneDesc,
}

impl SceneFile {
    /// Reads and parses the TOML scene file at `path`.
    pub fn read(path: &Path) -> Result<Self, LoadError> {
        let bytes = std::fs::read(path)
            .map_err(|e| LoadError::file(path, format!("cannot read the scene file: {e}")))?;
        let text = String::from_utf8(bytes)
            .map_err(|e| LoadError::file(path, format!("the scene file is not UTF-8 text: {e}")))?;
        let base_dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
        Self::parse(path.to_path_buf(), base_dir, text)
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
        })
    }

    /// Checks the description and builds the scene.
    pub fn build(&self) -> Result<Loaded, LoadError> {
        build(
            &self.desc,
            &Source {
                path: &self.path,
                text: &self.text,
            },
            &self.base_dir,
        )
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
