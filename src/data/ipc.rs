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
    reader: R,
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
}
