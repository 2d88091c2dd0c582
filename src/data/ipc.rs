//! Arrow IPC files (Feather v2): `.arrow`, `.feather`, `.ipc`, as pyarrow, polars, DuckDB and
//! apache-arrow for JavaScript write them, read through polars.
//!
//! Only the IPC *file* format is read (it starts with the magic bytes `ARROW1`); the streaming
//! format has no footer to find the record batches by and is refused with a message saying so.

use polars::prelude::*;

use super::load::first_line;

/// The magic bytes that open (and close) an Arrow IPC file.
const MAGIC: &[u8] = b"ARROW1";

/// Read an Arrow IPC file's bytes (from a file or decompressed into memory) into a frame,
/// optionally only some columns. The error is a message for the user.
pub fn read_ipc<R: polars::io::mmap::MmapBytesReader>(
    mut reader: R,
    head: &[u8],
    columns: Option<&[String]>,
) -> Result<DataFrame, String> {
    if head.get(..MAGIC.len()) != Some(MAGIC) {
        return Err(if head.get(..4) == Some(&[0xff; 4]) {
            "this is an Arrow IPC stream, not an IPC file; write it with the file format (Feather v2)".into()
        } else {
            "not an Arrow IPC file (it does not start with `ARROW1`)".into()
        });
    }
    super::ipc_bounds::check(&mut reader)?;
    IpcReader::new(reader).with_columns(columns.map(<[String]>::to_vec)).finish().map_err(|e| first_line(&e))
}

#[cfg(test)]
mod tests {
    use std::io::Cursor;

    use super::*;

    fn ipc_bytes(df: &mut DataFrame) -> Vec<u8> {
        let mut out = Vec::new();
        IpcWriter::new(&mut out).finish(df).expect("IPC in memory");
        out
    }

    #[test]
    fn a_file_written_by_polars_reads_back() {
        let mut df = df!("x" => [1i32, 2, 3], "name" => ["a", "b", "c"]).expect("frame");
        let bytes = ipc_bytes(&mut df);
        let back = read_ipc(Cursor::new(bytes.clone()), &bytes, None).expect("reads");
        assert!(back.equals(&df));
        let only = read_ipc(Cursor::new(bytes.clone()), &bytes, Some(&["name".to_string()])).expect("reads");
        assert_eq!(only.get_column_names(), ["name"]);
    }

    #[test]
    fn streams_truncated_and_foreign_bytes_are_refused() {
        let bytes = b"\xff\xff\xff\xff\x10\x00\x00\x00";
        assert_eq!(
            read_ipc(Cursor::new(bytes.to_vec()), bytes, None).expect_err("stream"),
            "this is an Arrow IPC stream, not an IPC file; write it with the file format (Feather v2)"
        );
        let csv = b"x,y\n1,2\n";
        assert_eq!(
            read_ipc(Cursor::new(csv.to_vec()), csv, None).expect_err("csv"),
            "not an Arrow IPC file (it does not start with `ARROW1`)"
        );
        let mut df = df!("x" => [1.5f64; 100]).expect("frame");
        let full = ipc_bytes(&mut df);
        let cut = full[..full.len() / 2].to_vec();
        assert!(read_ipc(Cursor::new(cut.clone()), &cut, None).is_err());
    }

    /// Replace every little-endian `from` in `bytes` by `to`; returns how many were replaced.
    fn replace_i64(bytes: &mut [u8], from: i64, to: i64) -> usize {
        let (from, to) = (from.to_le_bytes(), to.to_le_bytes());
        let mut n = 0;
        for at in 0..bytes.len().saturating_sub(7) {
            if bytes[at..at + 8] == from {
                bytes[at..at + 8].copy_from_slice(&to);
                n += 1;
            }
        }
        n
    }

    #[test]
    fn declared_sizes_beyond_the_file_are_refused_before_allocating() {
        // 100 doubles: an 800-byte buffer in a 100-row batch. Declaring 5,368,709,120 rows in a
        // 42,949,672,960-byte buffer made the reader allocate 40 GiB and abort the process.
        let mut df = df!("x" => [1.5f64; 100]).expect("frame");
        let mut bytes = ipc_bytes(&mut df);
        assert!(replace_i64(&mut bytes, 800, 42_949_672_960) > 0);
        assert!(replace_i64(&mut bytes, 100, 5_368_709_120) > 0);
        let err = read_ipc(Cursor::new(bytes.clone()), &bytes, None).expect_err("refused");
        assert!(err.starts_with("record batch 1: "), "{err}");
        // Only the row count: the rows no longer fit the bytes that hold them.
        let mut bytes = ipc_bytes(&mut df);
        assert!(replace_i64(&mut bytes, 100, 5_368_709_120) > 0);
        let err = read_ipc(Cursor::new(bytes.clone()), &bytes, None).expect_err("refused");
        assert_eq!(err, "record batch 1: 5368709120 rows declared in 800 bytes of data");
    }
}
