//! Writing output files safely: each file is written beside its final name and renamed into
//! place (a killed or failed run never leaves a partial file under a final name, and a symbolic
//! link at the final name is replaced, never followed), one run at a time per output folder, and
//! never over one of the spec's own inputs.

mod atomic;
mod inputs;
mod lock;

pub use atomic::{TEMP_SUFFIX, write_file};
pub use inputs::{InputClash, refuse_inputs};
pub use lock::{LOCK_FILE, LockError, OutputLock};

/// The folder `path` is in (`.` for a bare file name).
fn folder_of(path: &std::path::Path) -> &std::path::Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    }
}
