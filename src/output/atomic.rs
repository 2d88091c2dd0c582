//! One file written atomically: a temporary file in the same folder, flushed to disk, then
//! renamed over the final name.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// How temporary files end (`.dataink-PID-N.tmp`); a folder's leftovers from a killed run are
/// removed by the next run that takes its [`OutputLock`](super::OutputLock).
pub const TEMP_SUFFIX: &str = ".tmp";

/// The temporary name's prefix.
pub(crate) const TEMP_PREFIX: &str = ".dataink-";

static NEXT: AtomicU64 = AtomicU64::new(0);

/// A fresh temporary path in `dir`, unique within this process.
fn temporary_in(dir: &Path) -> PathBuf {
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    dir.join(format!("{TEMP_PREFIX}{}-{n}{TEMP_SUFFIX}", std::process::id()))
}

/// Write `bytes` to `path` so that `path` holds either its old content or all of `bytes`, never
/// a part: the bytes go to a new temporary file in the same folder (created exclusively, so no
/// link is followed), are synced, and the file is renamed over `path`. A symbolic link at `path`
/// is replaced by the file, its target left untouched.
pub fn write_file(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let dir = super::folder_of(path);
    let temporary = temporary_in(dir);
    let written = write_new(&temporary, bytes).and_then(|()| std::fs::rename(&temporary, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// Create `path` (which must not exist) and write all of `bytes` to disk.
fn write_new(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut file: File = OpenOptions::new().write(true).create_new(true).open(path)?;
    file.write_all(bytes)?;
    file.sync_data()
}

/// Whether `name` is one of this module's temporary files.
pub(crate) fn is_temporary(name: &str) -> bool {
    name.strip_prefix(TEMP_PREFIX).and_then(|rest| rest.strip_suffix(TEMP_SUFFIX)).is_some_and(|middle| {
        middle.split_once('-').is_some_and(|(pid, n)| {
            !pid.is_empty()
                && !n.is_empty()
                && pid.bytes().all(|b| b.is_ascii_digit())
                && n.bytes().all(|b| b.is_ascii_digit())
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_content_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.svg");
        std::fs::write(&path, "old").unwrap();
        write_file(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, vec![std::ffi::OsString::from("c.svg")]);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_at_the_final_name_is_replaced_not_followed() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("elsewhere.txt");
        std::fs::write(&target, "precious").unwrap();
        let path = dir.path().join("c.svg");
        std::os::unix::fs::symlink(&target, &path).unwrap();
        write_file(&path, b"chart").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious");
        assert!(!std::fs::symlink_metadata(&path).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "chart");
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        // A folder at the final name: the rename fails after the temporary was written.
        let path = dir.path().join("c.svg");
        std::fs::create_dir(&path).unwrap();
        std::fs::write(path.join("inside"), "x").unwrap();
        assert!(write_file(&path, b"chart").is_err());
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, vec![std::ffi::OsString::from("c.svg")]);
    }

    #[test]
    fn temporary_names_are_recognised_exactly() {
        let dir = Path::new("/x");
        let t = temporary_in(dir);
        assert!(is_temporary(t.file_name().unwrap().to_str().unwrap()));
        for other in [
            ".dataink-1-.tmp",
            ".dataink--1.tmp",
            ".dataink-a-1.tmp",
            "dataink-1-1.tmp",
            ".dataink-1-1.tmp.svg",
            ".dataink.lock",
        ] {
            assert!(!is_temporary(other), "{other}");
        }
    }
}
