//! POV-Ray 3.7 scene files (`.pov`) read into a [`SceneDesc`].
//!
//! ```pov
//! #include "colors.inc"
//! camera { location <0, 2, -5> look_at <0, 1, 0> angle 50 right x*image_width/image_height }
//! light_source { <5, 10, -5> color White }
//! plane { y, 0 pigment { checker color White color Gray50 } }
//! #declare R = 1;
//! #for (I, -1, 1)
//!     sphere { <I * 2, R, 0>, R pigment { rgb <0.8, 0.2, 0.2> } finish { phong 0.6 reflection 0.2 } }
//! #end
//! ```
//!
//! The reading goes in three stages:
//!
//! 1. [`lexer`]: each file's tokens, with their places;
//! 2. [`parser`]: the language carried out as the tokens are read — directives (`#declare`,
//!    `#local`, `#include`, `#macro`, `#if`/`#else`/`#elseif`, `#ifdef`, `#switch`, `#while`,
//!    `#for`, `#version`, `#default`, `#undef`, `#debug`, `#error`), expressions ([`expr`],
//!    [`functions`]) and arrays — while [`scene`], [`shapes`] and [`texture`] read the
//!    statements into POV-Ray's own model of the scene;
//! 3. [`convert`]: that model mapped onto lucent's description.
//!
//! Include files are looked for in the scene's folder, then in the folders of the
//! `LUCENT_POVRAY_LIBRARY` environment variable (separated by `:`), then in POV-Ray's usual
//! include folders (`/usr/share/povray-3.7/include`, `/usr/local/share/povray-3.7/include`).
//! What lucent reads but renders otherwise than POV-Ray is a warning naming the file and
//! line; a syntax error names the file, line and column and what was expected.

mod algebraic;
mod convert;
pub mod expr;
mod functions;
pub mod lexer;
pub mod normal;
pub mod parser;
pub mod scene;
mod shapes;
pub mod texture;
pub mod value;

#[cfg(test)]
mod tests;

use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::import::Imported;
use crate::paths::LoadOptions;
use parser::Parser;
use std::path::{Path, PathBuf};

/// The image size `image_width` and `image_height` give when the caller sets none (POV-Ray
/// 3.7's own default).
pub const DEFAULT_SIZE: (u32, u32) = (800, 600);

/// Where include files are looked for after the scene's folder.
pub fn library_path() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::env::var_os("LUCENT_POVRAY_LIBRARY")
        .map(|v| std::env::split_paths(&v).collect())
        .unwrap_or_default();
    for standard in [
        "/usr/share/povray-3.7/include",
        "/usr/local/share/povray-3.7/include",
    ] {
        let p = PathBuf::from(standard);
        if p.is_dir() {
            out.push(p);
        }
    }
    out
}

/// The scene of a POV-Ray file as a description, at `options.image_size` pixels (or
/// [`DEFAULT_SIZE`]). The bytes of every file read are added to `inputs`.
pub fn import_povray(
    path: &Path,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Imported, LoadError> {
    let size = options.image_size.unwrap_or(DEFAULT_SIZE);
    let mut p = Parser::open(path, library_path(), options, size, std::mem::take(inputs))?;
    let scene = p.scene();
    *inputs = std::mem::take(&mut p.inputs);
    described(p, scene?, path, size)
}

/// The description of what `p` read, `scene`, from the file `path`.
fn described(
    mut p: Parser,
    scene: scene::PovScene,
    path: &Path,
    size: (u32, u32),
) -> Result<Imported, LoadError> {
    let file = lexer::Loc {
        file: std::rc::Rc::from(path),
        line: 1,
        column: 1,
    };
    let mut warnings = std::mem::take(&mut p.warnings);
    let desc = convert::convert(
        &scene,
        p.main_version,
        &p.defaults,
        size,
        &mut warnings,
        &file,
    )?;
    Ok(Imported {
        desc,
        camera_given: true,
        warnings,
        lit_as_given: true,
    })
}

/// [`import_povray`] of text given in memory, labelled `label` in errors.
pub fn import_povray_text(
    label: &Path,
    text: &str,
    options: &LoadOptions,
) -> Result<Imported, LoadError> {
    let size = options.image_size.unwrap_or(DEFAULT_SIZE);
    let mut p = Parser::of_text(label, text, options)?;
    p.image_size = size;
    p.library = library_path();
    let scene = p.scene()?;
    described(p, scene, label, size)
}
