//! Open input paths only when they name regular files, and read them under a size cap.
//!
//! The file type is checked from the path's metadata (following symlinks) before the file is
//! opened, so a FIFO never blocks the open and a device such as `/dev/zero` is refused before a
//! single byte is read.

use std::fs::File;
use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// Largest spec file read, in bytes (16 MiB).
pub const MAX_SPEC_BYTES: u64 = 16 * 1024 * 1024;
/// Largest report template read, in bytes (1 MiB).
pub const MAX_TEMPLATE_BYTES: u64 = 1024 * 1024;

/// What kind of file a non-regular path is, for the error message.
fn kind_name(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_socket() {
            return "a socket";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
    }
    if file_type.is_dir() {
        return "a directory";
    }
    "not a regular file"
}

/// Open `path` for reading if it is a regular file (after following symlinks).
pub fn open(path: &Path) -> Result<File, Error> {
    let metadata = std::fs::metadata(path)?;
    if !metadata.is_file() {
        let kind = kind_name(metadata.file_type());
        return Err(Error::new(ErrorKind::InvalidInput, format!("it is {kind}; only regular files are read")));
    }
    File::open(path)
}

/// Read all of the regular file `path`, refusing files larger than `cap` bytes; `what` names the
/// limit in the error ("spec", "template").
pub fn read_capped(path: &Path, cap: u64, what: &str) -> Result<Vec<u8>, Error> {
    let file = open(path)?;
    let mut bytes = Vec::new();
    file.take(cap + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("it is larger than the {what} size limit of {} MiB", cap / (1024 * 1024)),
        ));
    }
    Ok(bytes)
}
