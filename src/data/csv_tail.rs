//! The one ending of a CSV file that polars' parser cannot take safely: a field opened by a quote
//! as the file's very last byte (`x,y\n1,2\n"`). Its line parser then reads past the end of its
//! buffer (an unchecked index: an abort in debug builds, undefined behaviour in release), so the
//! file is refused before it is parsed.

use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// Whether `tail` (the last bytes of a CSV file, at least two when the file has them) ends with a
/// quote that opens a field: right after a line break or `separator`.
pub fn ends_in_open_quote(tail: &[u8], separator: u8) -> bool {
    match tail {
        [.., before, b'"'] => matches!(*before, b'\n' | b'\r') || *before == separator,
        _ => false,
    }
}

/// The error for such a file, for the user.
pub const MESSAGE: &str = "the file ends with a quote that opens a field and is never closed (a lone `\"` as the last byte); close the quote or remove it";

/// Check the end of the CSV file at `path`; `Err` with [`MESSAGE`] when it ends in an open quote.
pub fn check_file(path: &Path, separator: u8) -> std::io::Result<Result<(), &'static str>> {
    let mut file = super::regular_file::open(path)?;
    let len = file.metadata()?.len();
    let mut tail = [0u8; 2];
    let take = len.min(2) as usize;
    file.seek(SeekFrom::End(-(take as i64)))?;
    file.read_exact(&mut tail[..take])?;
    Ok(if ends_in_open_quote(&tail[..take], separator) { Err(MESSAGE) } else { Ok(()) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quote_opening_the_last_field_is_found() {
        for bad in [&b"x,y\n1,2\n\""[..], b"x,y\r\n1,2\r\n\"", b"x,y\n1,2\n1,\"", b"x,y\n1,2\n,\""] {
            assert!(ends_in_open_quote(bad, b','), "{:?}", String::from_utf8_lossy(bad));
        }
        // Closed quotes, a tripled quote, a quote then a space, a one-byte file are fine.
        for good in [&b"x,y\n1,\"2\""[..], b"x,y\n1,2\n\"\"\"", b"x,y\n1,2\n\" ", b"\""] {
            assert!(!ends_in_open_quote(good, b','), "{:?}", String::from_utf8_lossy(good));
        }
        // The separator is the file's own.
        assert!(!ends_in_open_quote(b"x;y\n1;2\n1,\"", b';'));
        assert!(ends_in_open_quote(b"1;\"", b';'));
    }
}
