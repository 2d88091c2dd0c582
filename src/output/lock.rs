//! One run at a time per output folder: an advisory lock on the folder itself, held while the
//! run writes, so two renders into one folder never leave one's SVG beside the other's PNG. On
//! Unix the folder is locked directly (nothing is created in it); elsewhere through a lock file.

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};

/// The lock file an output folder gets where folders cannot be locked directly (not on Unix).
pub const LOCK_FILE: &str = ".dataink.lock";

/// The held lock of an output folder; released when dropped (or when the process ends, however
/// it ends).
#[derive(Debug)]
pub struct OutputLock {
    _file: File,
}

/// Why the lock could not be taken.
#[derive(Debug)]
pub struct LockError {
    /// The folder (or its lock file).
    pub path: PathBuf,
    /// What went wrong.
    pub source: io::Error,
}

impl std::fmt::Display for LockError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot lock the output folder `{}`: {}", self.path.display(), self.source)
    }
}

impl std::error::Error for LockError {}

impl OutputLock {
    /// Create `dir` if missing and take its lock, waiting for another run that holds it
    /// (`waiting` is called once before the wait). Temporary files that a killed run left in
    /// `dir` are removed once the lock is held.
    pub fn acquire(dir: &Path, waiting: impl FnOnce()) -> Result<OutputLock, LockError> {
        let fail = |source| LockError { path: dir.to_path_buf(), source };
        std::fs::create_dir_all(dir).map_err(fail)?;
        let (file, path) = open_lock_target(dir).map_err(fail)?;
        let fail = |source| LockError { path: path.clone(), source };
        match file.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                waiting();
                file.lock().map_err(fail)?;
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(fail(e)),
        }
        remove_leftovers(dir);
        Ok(OutputLock { _file: file })
    }
}

/// What is locked: the folder itself on Unix, where `flock` works on a folder's descriptor.
#[cfg(unix)]
fn open_lock_target(dir: &Path) -> io::Result<(File, PathBuf)> {
    Ok((File::open(dir)?, dir.to_path_buf()))
}

/// What is locked: a lock file in the folder (created if missing).
#[cfg(not(unix))]
fn open_lock_target(dir: &Path) -> io::Result<(File, PathBuf)> {
    let path = dir.join(LOCK_FILE);
    let file = std::fs::OpenOptions::new().read(true).write(true).create(true).truncate(false).open(&path)?;
    Ok((file, path))
}

/// Remove the temporary files of earlier runs (only this module's names; nothing else).
fn remove_leftovers(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name();
        if name.to_str().is_some_and(super::atomic::is_temporary) && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};

    #[test]
    fn a_second_taker_waits_until_the_first_releases() {
        let dir = tempfile::tempdir().unwrap();
        let first = OutputLock::acquire(dir.path(), || panic!("nobody holds it yet")).unwrap();
        let released = Arc::new(AtomicBool::new(false));
        let waited = Arc::new(AtomicBool::new(false));
        let handle = {
            let (dir, released, waited) = (dir.path().to_path_buf(), released.clone(), waited.clone());
            std::thread::spawn(move || {
                let _second = OutputLock::acquire(&dir, || waited.store(true, Ordering::SeqCst)).unwrap();
                // Taken only after the first was dropped.
                assert!(released.load(Ordering::SeqCst));
            })
        };
        while !waited.load(Ordering::SeqCst) {
            std::thread::yield_now();
        }
        released.store(true, Ordering::SeqCst);
        drop(first);
        handle.join().unwrap();
    }

    #[test]
    fn leftovers_of_a_killed_run_are_removed_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(".dataink-99999-3.tmp"), "partial").unwrap();
        std::fs::write(dir.path().join("notes.tmp"), "mine").unwrap();
        std::fs::write(dir.path().join("c.svg"), "<svg/>").unwrap();
        let _lock = OutputLock::acquire(dir.path(), || {}).unwrap();
        let mut names: Vec<String> =
            std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        names.sort();
        assert_eq!(names, ["c.svg", "notes.tmp"]);
    }

    #[cfg(unix)]
    #[test]
    fn the_folder_is_locked_without_a_file_in_it() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let _lock = OutputLock::acquire(&out, || {}).unwrap();
        assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0);
    }
}
