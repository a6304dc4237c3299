//! Paths named inside scene files, resolved against the scene's folder — and, with
//! `--sandbox`, kept inside it.

use std::path::{Component, Path, PathBuf};

/// How files named inside a scene may be reached.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Refuse absolute paths and paths that climb out of the scene's folder with `..`
    /// (for scenes from untrusted sources).
    pub sandbox: bool,
    /// The budgets the scene is held to.
    pub limits: crate::limits::Limits,
    /// The image's size when the caller knows it before reading (a POV-Ray scene's
    /// `image_width` and `image_height`).
    pub image_size: Option<(u32, u32)>,
}

/// `name` (as written in a scene file) resolved against `base_dir`; with `options.sandbox`, an
/// error when it is absolute, climbs out of `base_dir` with `..`, or is a file inside it in name
/// only (a symbolic link, or a linked folder on the way, that leads out).
pub fn resolve(base_dir: &Path, name: &str, options: &LoadOptions) -> Result<PathBuf, String> {
    let rel = Path::new(name);
    if options.sandbox {
        if rel.is_absolute() || rel.has_root() {
            return Err(format!(
                "`{name}` is an absolute path, refused by --sandbox"
            ));
        }
        let mut depth = 0i32;
        for c in rel.components() {
            match c {
                Component::ParentDir => depth -= 1,
                Component::Normal(_) => depth += 1,
                Component::CurDir => {}
                Component::RootDir | Component::Prefix(_) => depth = -1,
            }
            if depth < 0 {
                return Err(format!(
                    "`{name}` leaves the scene's folder, refused by --sandbox"
                ));
            }
        }
        // Lexically inside, but a symbolic link on the way can still lead out: where the file
        // exists, its real path must be inside the folder's real path.
        let joined = base_dir.join(rel);
        // A scene in the working folder has an empty one, which does not canonicalise.
        let folder = if base_dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            base_dir
        };
        if let (Ok(real), Ok(folder)) = (joined.canonicalize(), folder.canonicalize())
            && !real.starts_with(&folder)
        {
            return Err(format!(
                "`{name}` leads out of the scene's folder through a symbolic link (to `{}`), refused by --sandbox",
                real.display()
            ));
        }
        return Ok(joined);
    }
    Ok(base_dir.join(rel))
}

/// `path` named from folder `dir` (both absolute): `../x/y` when they share a root, else
/// `path` itself.
pub fn relative_to(path: &Path, dir: &Path) -> PathBuf {
    let p: Vec<Component> = normalize(path);
    let d: Vec<Component> = normalize(dir);
    if p.first() != d.first() {
        return path.to_path_buf();
    }
    let common = p.iter().zip(&d).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..d.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c.as_os_str());
    }
    out
}

/// Components with `.` dropped and `..` applied.
fn normalize(path: &Path) -> Vec<Component<'_>> {
    let mut out = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir if matches!(out.last(), Some(Component::Normal(_))) => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sandbox_keeps_paths_inside() {
        let sandbox = LoadOptions {
            sandbox: true,
            ..LoadOptions::default()
        };
        let base = Path::new("scenes");
        assert_eq!(
            resolve(base, "a/b.obj", &sandbox).unwrap(),
            base.join("a/b.obj")
        );
        assert!(resolve(base, "a/../b.obj", &sandbox).is_ok());
        assert!(
            resolve(base, "../b.obj", &sandbox)
                .unwrap_err()
                .contains("leaves")
        );
        assert!(resolve(base, "a/../../b.obj", &sandbox).is_err());
        assert!(
            resolve(base, "/etc/passwd", &sandbox)
                .unwrap_err()
                .contains("absolute")
        );
        assert!(resolve(base, "/etc/passwd", &LoadOptions::default()).is_ok());
    }

    #[test]
    fn paths_named_from_another_folder() {
        let r = |p: &str, d: &str| relative_to(Path::new(p), Path::new(d));
        assert_eq!(r("/a/b/m.obj", "/a/b"), PathBuf::from("m.obj"));
        assert_eq!(r("/a/b/m.obj", "/a/c/d"), PathBuf::from("../../b/m.obj"));
        assert_eq!(r("/a/./b/../m.obj", "/a"), PathBuf::from("m.obj"));
    }
}
