//! Compressed data files: `data.csv.gz`, `data.json.zst`, `data.geojson.gz`, … The outer
//! extension names the compression (`.gz`/`.gzip`, `.zst`/`.zstd`), the inner one the format.
//! The file is decompressed into memory, at most [`MAX_DECOMPRESSED`] bytes (a small file that
//! inflates without end is refused, not allocated), and then read like the uncompressed file.

use std::io::Read;
use std::path::{Path, PathBuf};

use super::load::LoadError;

/// Largest decompressed size accepted, in bytes (1 GiB).
pub const MAX_DECOMPRESSED: u64 = 1 << 30;

/// A compression a data file can be stored with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    /// gzip (`.gz`, `.gzip`).
    Gzip,
    /// Zstandard (`.zst`, `.zstd`).
    Zstd,
}

impl Compression {
    /// The compression named by a path's last extension, if any.
    pub fn of(path: &Path) -> Option<Compression> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "gz" | "gzip" => Some(Compression::Gzip),
            "zst" | "zstd" => Some(Compression::Zstd),
            _ => None,
        }
    }

    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Compression::Gzip => "gzip",
            Compression::Zstd => "zstd",
        }
    }
}

/// The path without its compression extension (`a/data.csv.gz` → `a/data.csv`), so that the
/// inner extension names the format; other paths are returned as they are.
pub fn inner_path(path: &Path) -> PathBuf {
    match Compression::of(path) {
        Some(_) => path.with_extension(""),
        None => path.to_path_buf(),
    }
}

/// The bytes of a data file, decompressed when its extension names a compression.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, LoadError> {
    let file = super::regular_file::open(path).map_err(|e| LoadError::from_io(path, e))?;
    let Some(compression) = Compression::of(path) else {
        // Sized from the metadata up front: one allocation, no regrowing copies of a large file.
        let size = file.metadata().map_or(0, |m| m.len()).min(MAX_DECOMPRESSED);
        let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0).saturating_add(1));
        let mut file = file;
        file.read_to_end(&mut bytes).map_err(|e| LoadError::from_io(path, e))?;
        return Ok(bytes);
    };
    let corrupt = |message: String| LoadError::Decompress { path: path.to_path_buf(), compression, message };
    let reader: Box<dyn Read> = match compression {
        Compression::Gzip => Box::new(flate2::read::MultiGzDecoder::new(std::io::BufReader::new(file))),
        Compression::Zstd => Box::new(zstd::stream::read::Decoder::new(file).map_err(|e| corrupt(e.to_string()))?),
    };
    decompress(reader, MAX_DECOMPRESSED).map_err(corrupt)
}

/// Read a decoder to the end, refusing more than `cap` bytes.
fn decompress(reader: impl Read, cap: u64) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    reader.take(cap + 1).read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    if bytes.len() as u64 > cap {
        return Err(format!("it decompresses to more than {cap} bytes"));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    fn gzip(bytes: &[u8]) -> Vec<u8> {
        let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        encoder.write_all(bytes).expect("gzip in memory");
        encoder.finish().expect("gzip in memory")
    }

    #[test]
    fn compression_comes_from_the_last_extension() {
        assert_eq!(Compression::of(Path::new("a/data.csv.gz")), Some(Compression::Gzip));
        assert_eq!(Compression::of(Path::new("data.JSON.ZST")), Some(Compression::Zstd));
        assert_eq!(Compression::of(Path::new("data.csv")), None);
        assert_eq!(inner_path(Path::new("a/data.jsonl.gz")), Path::new("a/data.jsonl"));
        assert_eq!(inner_path(Path::new("a/data.csv")), Path::new("a/data.csv"));
    }

    #[test]
    fn gzip_and_zstd_round_trip() {
        let text = b"x,y\n1,2\n3,4\n";
        let dir = tempfile::tempdir().expect("temp dir");
        let gz = dir.path().join("d.csv.gz");
        std::fs::write(&gz, gzip(text)).expect("write");
        assert_eq!(read_bytes(&gz).expect("gzip reads"), text);
        let zst = dir.path().join("d.csv.zst");
        std::fs::write(&zst, zstd::encode_all(&text[..], 3).expect("zstd in memory")).expect("write");
        assert_eq!(read_bytes(&zst).expect("zstd reads"), text);
    }

    #[test]
    fn corrupt_and_truncated_files_are_errors() {
        let dir = tempfile::tempdir().expect("temp dir");
        let bad = dir.path().join("d.csv.gz");
        std::fs::write(&bad, b"x,y\n1,2\n").expect("write");
        let err = read_bytes(&bad).expect_err("not gzip");
        assert!(err.to_string().starts_with("cannot decompress"), "{err}");
        assert!(err.to_string().contains("as gzip"), "{err}");
        let full = gzip(&b"x,y\n1,2\n".repeat(1000));
        std::fs::write(&bad, &full[..full.len() / 2]).expect("write");
        assert!(matches!(read_bytes(&bad), Err(LoadError::Decompress { compression: Compression::Gzip, .. })));
        let zst = dir.path().join("d.json.zst");
        std::fs::write(&zst, b"\x28\xb5\x2f\xfd garbage").expect("write");
        assert!(matches!(read_bytes(&zst), Err(LoadError::Decompress { compression: Compression::Zstd, .. })));
    }

    #[test]
    fn the_size_cap_refuses_a_bomb() {
        let zeros = gzip(&vec![0u8; 10_000]);
        let err = decompress(flate2::read::GzDecoder::new(&zeros[..]), 1000).expect_err("over the cap");
        assert_eq!(err, "it decompresses to more than 1000 bytes");
        assert_eq!(decompress(flate2::read::GzDecoder::new(&zeros[..]), 10_000).map(|b| b.len()), Ok(10_000));
    }
}
