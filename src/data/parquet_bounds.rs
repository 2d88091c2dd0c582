//! Sizes and counts a Parquet file declares, checked against the file before any reader trusts
//! them.
//!
//! The reader casts a page's value count (a signed 32-bit number in the page header) to an
//! unsigned size and reserves that many bits, so one edited count of `-1000` asks for 2⁶¹ bytes
//! and aborts the process; a column chunk or page may also claim bytes past the end of the file
//! or expand to an arbitrary size. Every column chunk of every row group, and every page header
//! in it, is checked here: counts are not negative and not above the chunk's own count, byte
//! ranges lie inside the file (and each page inside its chunk), and a compressed page or chunk
//! expands at most [`MAX_EXPANSION`] times. Only the footer and the page headers are read, not the
//! pages themselves.

use std::io::{BufReader, Read, Seek, SeekFrom};

use polars_parquet::parquet::metadata::ColumnChunkMetadata;
use polars_parquet::parquet::read::read_metadata;
use polars_parquet_format::PageHeader;
use polars_parquet_format::thrift::protocol::TCompactInputProtocol;

/// Most times a compressed page or column chunk may expand (as for Arrow IPC buffers).
pub const MAX_EXPANSION: u64 = 1024;

/// Bytes any page or chunk may expand to regardless of its compressed size.
const EXPANSION_FLOOR: u64 = 1 << 20;

/// Bytes read ahead while walking page headers: the thrift decoder reads a byte at a time, and
/// small pages lie close together, so one read serves many headers.
const HEADER_READ_AHEAD: usize = 8 * 1024;

/// Largest page header read (polars' reader allows the same order of size).
const MAX_HEADER_BYTES: usize = 1 << 24;

/// Check every column chunk `reader` (a Parquet file, at its start) declares; the error is for
/// the user. The reader is left at the start.
pub fn check<R: Read + Seek>(reader: &mut R) -> Result<(), String> {
    let file_len = reader.seek(SeekFrom::End(0)).map_err(|e| e.to_string())?;
    reader.rewind().map_err(|e| e.to_string())?;
    let metadata = read_metadata(reader).map_err(|e| super::transform::first_line(&e.to_string()))?;
    let mut buffered = Positioned { inner: BufReader::with_capacity(HEADER_READ_AHEAD, &mut *reader), at: None };
    for (g, group) in metadata.row_groups.iter().enumerate() {
        for (c, column) in group.parquet_columns().iter().enumerate() {
            check_chunk(&mut buffered, column, file_len)
                .map_err(|m| format!("row group {}, column chunk {}: {m}", g + 1, c + 1))?;
        }
    }
    drop(buffered);
    reader.rewind().map_err(|e| e.to_string())
}

/// A value the file declares, refused when negative.
fn count(value: i64, what: &str) -> Result<u64, String> {
    u64::try_from(value).map_err(|_| format!("a negative {what} ({value})"))
}

/// Whether `uncompressed` is a size `compressed` bytes may expand to.
fn expands_within_bounds(compressed: u64, uncompressed: u64) -> bool {
    uncompressed <= compressed.saturating_mul(MAX_EXPANSION).saturating_add(EXPANSION_FLOOR)
}

/// One column chunk: where it lies, what it declares, then its pages.
fn check_chunk<R: Read + Seek>(
    reader: &mut Positioned<R>,
    column: &ColumnChunkMetadata,
    file_len: u64,
) -> Result<(), String> {
    let start = count(column.dictionary_page_offset().unwrap_or(column.data_page_offset()), "page offset")?;
    let compressed = count(column.compressed_size(), "compressed size")?;
    let uncompressed = count(column.uncompressed_size(), "uncompressed size")?;
    let values = count(column.num_values(), "value count")?;
    let end = start
        .checked_add(compressed)
        .filter(|end| *end <= file_len)
        .ok_or_else(|| format!("it claims bytes {start} to {start}+{compressed} but the file has {file_len} bytes"))?;
    if !expands_within_bounds(compressed, uncompressed) {
        return Err(format!("{compressed} compressed bytes claim to expand to {uncompressed}"));
    }
    check_pages(reader, start, end, values)
}

/// The page headers from `start` to `end`, until the chunk's `values` are seen.
fn check_pages<R: Read + Seek>(reader: &mut Positioned<R>, start: u64, end: u64, values: u64) -> Result<(), String> {
    let (mut at, mut seen) = (start, 0u64);
    while at < end && seen < values {
        reader.go_to(at).map_err(|e| e.to_string())?;
        let mut counted = Counted { inner: (&mut reader.inner).take(end - at), read: 0 };
        let header = {
            let mut protocol = TCompactInputProtocol::new(&mut counted, MAX_HEADER_BYTES);
            PageHeader::read_from_in_protocol(&mut protocol)
                .map_err(|e| format!("an unreadable page header at byte {at}: {e}"))?
        };
        reader.at = Some(at + counted.read);
        let page_values = check_page(&header, values).map_err(|m| format!("the page at byte {at}: {m}"))?;
        let body = count(header.compressed_page_size.into(), "compressed page size")?;
        at = (at + counted.read)
            .checked_add(body)
            .filter(|next| *next <= end)
            .ok_or_else(|| format!("the page at byte {at} runs past its column chunk"))?;
        seen += page_values;
    }
    Ok(())
}

/// One page header's sizes and counts; returns the values it holds (none for a dictionary).
fn check_page(header: &PageHeader, chunk_values: u64) -> Result<u64, String> {
    let compressed = count(header.compressed_page_size.into(), "compressed page size")?;
    let uncompressed = count(header.uncompressed_page_size.into(), "uncompressed page size")?;
    if !expands_within_bounds(compressed, uncompressed) {
        return Err(format!("{compressed} compressed bytes claim to expand to {uncompressed}"));
    }
    let within_chunk = |n: i32, what: &str| {
        let n = count(n.into(), &format!("{what} count"))?;
        if n > chunk_values {
            return Err(format!("{n} {what}s in a column chunk of {chunk_values} values"));
        }
        Ok(n)
    };
    if let Some(dictionary) = &header.dictionary_page_header {
        count(dictionary.num_values.into(), "dictionary size")?;
    }
    if let Some(v1) = &header.data_page_header {
        return within_chunk(v1.num_values, "value");
    }
    if let Some(v2) = &header.data_page_header_v2 {
        within_chunk(v2.num_nulls, "null")?;
        within_chunk(v2.num_rows, "row")?;
        let levels = count(v2.definition_levels_byte_length.into(), "definition level length")?
            + count(v2.repetition_levels_byte_length.into(), "repetition level length")?;
        if levels > uncompressed {
            return Err(format!("{levels} bytes of levels in a page of {uncompressed} bytes"));
        }
        return within_chunk(v2.num_values, "value");
    }
    Ok(0)
}

/// A buffered reader that knows its position, so a jump to a nearby page header stays inside
/// the read-ahead instead of discarding it (file offsets are checked against the file's length,
/// so they fit in `i64`).
struct Positioned<R> {
    inner: BufReader<R>,
    /// Where the next byte comes from; `None` until the first jump.
    at: Option<u64>,
}

impl<R: Read + Seek> Positioned<R> {
    fn go_to(&mut self, target: u64) -> std::io::Result<()> {
        // A relative jump keeps what is buffered when the target lies inside it.
        match self.at {
            Some(at) => self.inner.seek_relative(target as i64 - at as i64)?,
            None => {
                self.inner.seek(SeekFrom::Start(target))?;
            }
        }
        self.at = Some(target);
        Ok(())
    }
}

/// A reader that counts the bytes read through it (the page header's length).
struct Counted<R> {
    inner: R,
    read: u64,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.read += n as u64;
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use std::io::Cursor;

    use polars::prelude::*;

    use super::*;

    fn parquet_bytes(df: &mut DataFrame) -> Vec<u8> {
        let mut out = Vec::new();
        ParquetWriter::new(&mut out).finish(df).expect("Parquet in memory");
        out
    }

    /// The value count of the first data page (the column chunk starts at the fourth byte).
    fn first_page_values(bytes: &[u8]) -> Option<i32> {
        let mut protocol = TCompactInputProtocol::new(&bytes[4..], MAX_HEADER_BYTES);
        let header = PageHeader::read_from_in_protocol(&mut protocol).expect("a page header");
        header.data_page_header.map(|h| h.num_values).or(header.data_page_header_v2.map(|h| h.num_values))
    }

    #[test]
    fn files_polars_writes_pass_and_leave_the_reader_at_the_start() {
        let mut df = df!(
            "x" => [Some(1.5f64), None, Some(3.0)],
            "name" => [Some("a"), Some("b"), None],
            "n" => [1i64, 2, 3]
        )
        .expect("frame");
        let mut reader = Cursor::new(parquet_bytes(&mut df));
        check(&mut reader).expect("a file polars wrote is within bounds");
        assert_eq!(reader.position(), 0);
        assert!(ParquetReader::new(reader).finish().expect("reads").equals_missing(&df));
    }

    #[test]
    fn the_gallery_parquet_files_pass() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data");
        let mut checked = 0;
        for entry in std::fs::read_dir(dir).expect("examples/data") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "parquet") {
                let mut file = std::fs::File::open(&path).expect("open");
                check(&mut file).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                checked += 1;
            }
        }
        assert!(checked >= 2, "the gallery ships Parquet files");
    }

    #[test]
    fn a_file_another_writer_made_passes_and_reads() {
        // pyarrow (scripts/parquet_fixture.py): dictionary pages, data pages V2 of 512 bytes,
        // three row groups, zstd, nulls and a nested list column.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/pyarrow_pages.parquet");
        let mut file = std::fs::File::open(&path).expect("fixture");
        check(&mut file).expect("a file pyarrow wrote is within bounds");
        let df = ParquetReader::new(file).finish().expect("reads");
        assert_eq!(df.height(), 3000);
        // Every seventh `x` (i % 7 == 0) and every fifth list are missing.
        assert_eq!(df.column("x").expect("x").null_count(), 429);
        assert_eq!(df.column("l").expect("l").null_count(), 600);
    }

    /// Encode `value` as a thrift compact zigzag varint.
    fn zigzag_varint(value: i32) -> Vec<u8> {
        let mut v = ((value << 1) ^ (value >> 31)) as u32;
        let mut out = Vec::new();
        loop {
            let byte = (v & 0x7f) as u8;
            v >>= 7;
            if v == 0 {
                out.push(byte);
                return out;
            }
            out.push(byte | 0x80);
        }
    }

    /// `bytes` with the first data page's value count (`old`) replaced by `new`, the header
    /// re-encoded in place (the varints must have the same length).
    fn with_page_values(bytes: &[u8], old: i32, new: i32) -> Vec<u8> {
        let (from, to) = (zigzag_varint(old), zigzag_varint(new));
        assert_eq!(from.len(), to.len(), "same-length varints");
        let header_end = 4 + 64;
        let at = bytes[4..header_end]
            .windows(from.len())
            .position(|w| w == from.as_slice())
            .expect("the value count in the first page header")
            + 4;
        let mut edited = bytes.to_vec();
        edited[at..at + to.len()].copy_from_slice(&to);
        edited
    }

    #[test]
    fn a_negative_page_value_count_is_refused_before_the_reader_allocates() {
        let values: Vec<Option<f64>> = (0..70).map(|i| (i % 3 != 0).then_some(i as f64)).collect();
        let mut df = df!("x" => values).expect("frame");
        let bytes = parquet_bytes(&mut df);
        assert_eq!(first_page_values(&bytes), Some(70));
        // 70 and -70 are both two-byte zigzag varints.
        let edited = with_page_values(&bytes, 70, -70);
        let error = check(&mut Cursor::new(edited)).expect_err("a negative count");
        assert!(error.contains("a negative value count (-70)"), "{error}");
        assert!(error.starts_with("row group 1, column chunk 1: the page at byte 4"), "{error}");
    }

    #[test]
    fn a_page_claiming_more_values_than_its_chunk_is_refused() {
        let mut df = df!("x" => (0..70).map(f64::from).collect::<Vec<_>>()).expect("frame");
        let bytes = parquet_bytes(&mut df);
        let edited = with_page_values(&bytes, 70, 8000);
        let error = check(&mut Cursor::new(edited)).expect_err("more values than the chunk");
        assert!(error.contains("8000 values in a column chunk of 70 values"), "{error}");
    }

    #[test]
    fn sizes_and_ranges_are_bounded() {
        assert!(expands_within_bounds(0, EXPANSION_FLOOR));
        assert!(!expands_within_bounds(0, EXPANSION_FLOOR + 1));
        assert!(expands_within_bounds(10, 10 * MAX_EXPANSION + EXPANSION_FLOOR));
        assert!(!expands_within_bounds(10, 10 * MAX_EXPANSION + EXPANSION_FLOOR + 1));
        assert!(expands_within_bounds(u64::MAX, u64::MAX));
        assert_eq!(count(-1, "value count"), Err("a negative value count (-1)".to_string()));
    }
}
