//! What several of this crate's tests share.

use std::path::{Path, PathBuf};

/// The example scenes (`examples/*.toml`, `*.xml`), in name order — less those that need
/// `../shared/data` where it is not here (a user's clone), with a note.
pub fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let data_here = dir.join("../../shared/data").is_dir();
    let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml" || e == "xml"))
        .filter(|p| {
            let needs_data = std::fs::read_to_string(p).is_ok_and(|t| t.contains("shared/data"));
            if needs_data && !data_here {
                eprintln!("skipping {}: ../shared/data is not here", p.display());
            }
            data_here || !needs_data
        })
        .collect();
    found.sort();
    found
}
