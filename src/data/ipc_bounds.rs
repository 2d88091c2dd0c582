//! Sizes an Arrow IPC file declares, checked against the file before any reader trusts them.
//!
//! The reader allocates each buffer at the length the file's metadata states (and a compressed
//! buffer at the length its first eight bytes state), so one edited number could ask for tens of
//! gigabytes and abort the process. Every record batch and dictionary batch is checked here:
//! its message and body lie inside the file, each buffer inside its body, a compressed buffer
//! expands at most [`MAX_EXPANSION`] times, and the row count fits the bytes that hold it.

use std::io::{Read, Seek, SeekFrom};

use polars_arrow::io::ipc::format::ipc::planus::ReadAsRoot;
use polars_arrow::io::ipc::format::ipc::{Block, MessageHeaderRef, MessageRef, RecordBatchRef};
use polars_arrow::io::ipc::read::read_file_metadata;

/// Most times a compressed buffer may expand (LZ4 frames reach about 255×).
pub const MAX_EXPANSION: u64 = 1024;

/// Rows a batch may hold per byte of (decompressed) body: eight, as in a bit-packed boolean.
const ROWS_PER_BYTE: u64 = 8;

/// Check every batch `reader` (an IPC file, at its start) declares; the error is for the user.
/// The reader is left at the start.
pub fn check<R: Read + Seek>(reader: &mut R) -> Result<(), String> {
    let file_len = reader.seek(SeekFrom::End(0)).map_err(|e| e.to_string())?;
    reader.rewind().map_err(|e| e.to_string())?;
    let metadata = read_file_metadata(reader).map_err(|e| super::load::first_line(&e))?;
    let blocks = metadata.blocks.iter().chain(metadata.dictionaries.iter().flatten());
    for (index, block) in blocks.enumerate() {
        check_block(reader, block, file_len).map_err(|m| format!("record batch {}: {m}", index + 1))?;
    }
    reader.rewind().map_err(|e| e.to_string())
}

/// One batch: where its message and body lie, and what they declare.
fn check_block<R: Read + Seek>(reader: &mut R, block: &Block, file_len: u64) -> Result<(), String> {
    let offset = u64::try_from(block.offset).map_err(|_| "negative offset".to_string())?;
    let meta_len = u64::try_from(block.meta_data_length).map_err(|_| "negative metadata length".to_string())?;
    let body_len = u64::try_from(block.body_length).map_err(|_| "negative body length".to_string())?;
    let body_start = offset.checked_add(meta_len).ok_or("metadata past the end of the file")?;
    let body_end = body_start.checked_add(body_len).ok_or("body past the end of the file")?;
    if body_end > file_len {
        return Err(format!("its body ends at byte {body_end} but the file has {file_len} bytes"));
    }
    let message = read_message(reader, offset, meta_len)?;
    let message = MessageRef::read_as_root(&message).map_err(|e| format!("unreadable message: {e}"))?;
    let batch = match message.header().map_err(|e| format!("unreadable message: {e}"))? {
        Some(MessageHeaderRef::RecordBatch(batch)) => batch,
        Some(MessageHeaderRef::DictionaryBatch(dictionary)) => {
            match dictionary.data().map_err(|e| format!("unreadable dictionary: {e}"))? {
                Some(batch) => batch,
                None => return Ok(()),
            }
        }
        _ => return Ok(()),
    };
    check_batch(reader, &batch, body_start, body_len)
}

/// The message's bytes: an optional continuation marker, its length, then the flatbuffer, all
/// inside the block's metadata.
fn read_message<R: Read + Seek>(reader: &mut R, offset: u64, meta_len: u64) -> Result<Vec<u8>, String> {
    let io = |e: std::io::Error| e.to_string();
    reader.seek(SeekFrom::Start(offset)).map_err(io)?;
    let mut word = [0u8; 4];
    reader.read_exact(&mut word).map_err(io)?;
    let mut prefix = 4;
    if word == [0xff; 4] {
        reader.read_exact(&mut word).map_err(io)?;
        prefix = 8;
    }
    let len = u64::try_from(i32::from_le_bytes(word)).map_err(|_| "negative message length".to_string())?;
    if len + prefix > meta_len {
        return Err(format!("a message of {len} bytes in {meta_len} bytes of metadata"));
    }
    let mut bytes = Vec::new();
    reader.take(len).read_to_end(&mut bytes).map_err(io)?;
    Ok(bytes)
}

/// Buffers inside the body, expansion bounded, rows that fit the bytes.
fn check_batch<R: Read + Seek>(
    reader: &mut R,
    batch: &RecordBatchRef<'_>,
    body_start: u64,
    body_len: u64,
) -> Result<(), String> {
    let unreadable = |e: polars_arrow::io::ipc::format::ipc::planus::Error| format!("unreadable batch: {e}");
    let compressed = batch.compression().map_err(unreadable)?.is_some();
    let mut data_bytes: u64 = 0;
    for buffer in batch.buffers().map_err(unreadable)?.into_iter().flat_map(|b| b.iter()) {
        let (start, len) = (buffer.offset(), buffer.length());
        let (Ok(start), Ok(len)) = (u64::try_from(start), u64::try_from(len)) else {
            return Err(format!("a buffer at {start} of {len} bytes"));
        };
        if start.checked_add(len).is_none_or(|end| end > body_len) {
            return Err(format!("a buffer of {len} bytes at {start} in a body of {body_len} bytes"));
        }
        data_bytes += if compressed && len >= 8 {
            let expanded = decompressed_len(reader, body_start + start)?.unwrap_or(len - 8);
            if expanded > len.saturating_mul(MAX_EXPANSION).saturating_add(1 << 20) {
                return Err(format!(
                    "a compressed buffer of {len} bytes says it expands to {expanded} bytes (at most {MAX_EXPANSION} times is read)"
                ));
            }
            expanded
        } else {
            len
        };
    }
    let rows = u64::try_from(batch.length().map_err(unreadable)?).map_err(|_| "a negative row count".to_string())?;
    let nodes = batch.nodes().map_err(unreadable)?;
    let most = data_bytes.saturating_add(1).saturating_mul(ROWS_PER_BYTE).max(4096);
    let longest = nodes.into_iter().flat_map(|n| n.iter()).map(|n| n.length()).max().unwrap_or(0).max(0) as u64;
    if rows.max(longest) > most {
        return Err(format!("{} rows declared in {data_bytes} bytes of data", rows.max(longest)));
    }
    Ok(())
}

/// The length a compressed buffer's first eight bytes state (`None` for -1: stored as is).
fn decompressed_len<R: Read + Seek>(reader: &mut R, at: u64) -> Result<Option<u64>, String> {
    let mut word = [0u8; 8];
    reader.seek(SeekFrom::Start(at)).and_then(|_| reader.read_exact(&mut word)).map_err(|e| e.to_string())?;
    match i64::from_le_bytes(word) {
        -1 => Ok(None),
        n => u64::try_from(n).map(Some).map_err(|_| format!("a compressed buffer of length {n}")),
    }
}
