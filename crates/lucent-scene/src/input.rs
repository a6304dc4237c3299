//! Reading a scene's input files: regular files only, with their size known before a byte is
//! read.
//!
//! A hostile scene can name anything a path can: a FIFO (reading it waits for a writer that
//! never comes), `/dev/zero` or `/dev/urandom` (endless), `/proc/self/pagemap` (gigabytes that
//! `stat` calls zero). Every reader of the crate goes through [`read`], which refuses what is not
//! a regular file before opening it, refuses `/proc`, `/sys` and `/dev` wherever a symlink
//! leads, and reads at most the size `stat` gave ([`MAX_FILE_BYTES`] at most).

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// The largest input file read: 4 GiB, above any mesh, image or scene we have met, and below
/// what a 64-bit machine cannot hold twice.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// The folders of the kernel's pseudo-files and devices, refused wherever a path leads.
const PSEUDO: [&str; 3] = ["/proc", "/sys", "/dev"];

/// The file at `path`, opened for reading, and its size; an error whose message says why it was
/// refused (not a regular file, a pseudo-file, or larger than [`MAX_FILE_BYTES`]).
pub fn open(path: &Path) -> io::Result<(File, u64)> {
    // `metadata` follows symlinks, and does not open: a FIFO is refused before it can block.
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        return Err(io::Error::other(format!("{what}: refused")));
    }
    let real = std::fs::canonicalize(path)?;
    if PSEUDO.iter().any(|p| real.starts_with(p)) {
        return Err(io::Error::other(format!(
            "`{}` is a kernel pseudo-file: refused",
            real.display()
        )));
    }
    let len = meta.len();
    if len > MAX_FILE_BYTES {
        return Err(io::Error::other(format!(
            "the file has {len} bytes; at most {MAX_FILE_BYTES} are read"
        )));
    }
    Ok((File::open(&real)?, len))
}

/// `Ok` when [`open`] would accept the file at `path`, else what to say after its name: `not
/// found`, or why it is refused (for an error at the place a scene names it).
pub fn refused(path: &Path) -> Result<(), String> {
    match open(path) {
        Ok(_) => Ok(()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Err("not found".to_string()),
        Err(e) => Err(format!("cannot be read: {e}")),
    }
}

/// The bytes of the file at `path`, as [`std::fs::read`] gives them, for a file that
/// [`open`] accepts and that does not grow while it is read.
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    let (file, len) = open(path)?;
    let mut bytes = Vec::with_capacity(len as usize);
    // One byte past the size tells a file that grew from one that did not.
    file.take(len + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > len {
        return Err(io::Error::other("the file grew while it was read: refused"));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    fn temp_dir(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("lucent-input-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_regular_file_reads_whole() {
        let dir = temp_dir("regular");
        let path = dir.join("a.obj");
        std::fs::write(&path, "v 0 0 0\n").unwrap();
        assert_eq!(read(&path).unwrap(), b"v 0 0 0\n");
    }

    #[test]
    fn fifos_devices_folders_and_pseudo_files_are_refused_at_once() {
        let dir = temp_dir("special");
        let fifo = dir.join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        let link = dir.join("zero.obj");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        let proc_link = dir.join("pagemap.obj");
        std::os::unix::fs::symlink("/proc/self/pagemap", &proc_link).unwrap();
        let mut cases = vec![
            (dir.clone(), "a folder"),
            (link, "not a regular file"),
            ("/dev/urandom".into(), "not a regular file"),
            (proc_link, "pseudo-file"),
            ("/proc/self/status".into(), "pseudo-file"),
        ];
        // Without mkfifo on the machine the FIFO case is left out, not failed.
        if made.is_ok_and(|s| s.success()) {
            cases.push((fifo, "not a regular file"));
        }
        for (path, why) in cases {
            let began = Instant::now();
            let e = read(&path).unwrap_err().to_string();
            assert!(e.contains(why), "{}: {e}", path.display());
            assert!(began.elapsed().as_secs_f32() < 1.0, "{}", path.display());
        }
    }
}
