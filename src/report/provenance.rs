//! Data provenance: where each data source came from and a content hash, so a reader can tell
//! whether two reports were drawn from the same bytes.

use std::fmt::Write as _;
use std::io::Read;
use std::path::{Path, PathBuf};

use serde::Serialize;
use sha2::{Digest, Sha256};

use super::ReportError;
use crate::data::{PathPolicy, Table, resolve_data_path};
use crate::spec::{DataFormat, DataSource};

/// Where one data source came from.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Provenance {
    /// The source's name (`[data.NAME]`).
    pub name: String,
    /// `"file"`, `"inline"` or `"engine"` (the engine address and what it reads in `path`; the hash
    /// is of the path or table and the transform steps sent, not of the cluster's data).
    pub origin: &'static str,
    /// The file path exactly as written in the spec (empty for inline values).
    pub path: String,
    /// The format: `csv`, `parquet`, `json`, `npy`, `matrix`, `tree`, or `inline`.
    pub format: String,
    /// Rows in the loaded table.
    pub rows: usize,
    /// The columns read, in source order (CSV and Parquet sources read only the columns the
    /// charts and selections use).
    pub columns: Vec<String>,
    /// Size of the hashed bytes.
    pub bytes: u64,
    /// Lowercase hex SHA-256 of the file's bytes, or of the inline rows as compact JSON.
    pub sha256: String,
}

/// Provenance of every data source of a spec whose tables are loaded, in name order.
///
/// `spec_dir` is the spec file's folder and `policy` the path policy the data was loaded under;
/// files are read again to hash them, in 64 KiB chunks.
pub fn collect(
    sources: &std::collections::BTreeMap<String, DataSource>,
    tables: &std::collections::BTreeMap<String, Table>,
    spec_dir: &Path,
    policy: PathPolicy,
) -> Result<Vec<Provenance>, ReportError> {
    let mut out = Vec::with_capacity(sources.len());
    for (name, source) in sources {
        let (rows, columns) = match tables.get(name) {
            Some(t) => (t.rows, t.column_names().into_iter().map(str::to_string).collect()),
            None => (0, Vec::new()),
        };
        let entry = match (&source.path, &source.values) {
            // The data is the cluster's: what is recorded is where, and the hash of what was asked.
            _ if source.engine.is_some() => {
                let engine = crate::data::engine::EngineUrl::parse(source.engine.as_deref().unwrap_or_default())
                    .map_or_else(|_| "engine".to_string(), |url| url.to_string());
                let read = source.path.as_deref().or(source.table.as_deref()).unwrap_or_default();
                let asked = serde_json::to_vec(&(read, &source.transform)).unwrap_or_default();
                Provenance {
                    name: name.clone(),
                    origin: "engine",
                    path: format!("{engine} {read}"),
                    format: "engine query".to_string(),
                    rows,
                    columns,
                    bytes: asked.len() as u64,
                    sha256: hex(&Sha256::digest(&asked)),
                }
            }
            (Some(path), _) => {
                let resolved = resolve_data_path(spec_dir, path, policy)
                    .map_err(|error| ReportError::DataPath { name: name.clone(), error })?;
                let (sha256, bytes) = hash_file(&resolved).map_err(|source| ReportError::ReadData {
                    name: name.clone(),
                    path: resolved.clone(),
                    source,
                })?;
                let format = match source.format {
                    Some(f) => format_name(f),
                    None => crate::data::load::infer_format(&resolved).map_or("unknown", format_name),
                };
                Provenance {
                    name: name.clone(),
                    origin: "file",
                    path: path.clone(),
                    format: format.to_string(),
                    rows,
                    columns,
                    bytes,
                    sha256,
                }
            }
            (None, values) => {
                let json = serde_json::to_vec(values.as_deref().unwrap_or(&[])).unwrap_or_default();
                Provenance {
                    name: name.clone(),
                    origin: "inline",
                    path: String::new(),
                    format: "inline".to_string(),
                    rows,
                    columns,
                    bytes: json.len() as u64,
                    sha256: hex(&Sha256::digest(&json)),
                }
            }
        };
        out.push(entry);
    }
    Ok(out)
}

/// The format's name as written in the spec.
fn format_name(format: DataFormat) -> &'static str {
    match format {
        DataFormat::Csv => "csv",
        DataFormat::Parquet => "parquet",
        DataFormat::Json => "json",
        DataFormat::Npy => "npy",
        DataFormat::Matrix => "matrix",
        DataFormat::Tree => "tree",
        DataFormat::Arrow => "arrow",
        DataFormat::Geojson => "geojson",
        DataFormat::Nifti => "nifti",
        DataFormat::Raw => "raw",
    }
}

/// SHA-256 (lowercase hex) and length of a file's bytes, read in chunks.
pub fn hash_file(path: &Path) -> std::io::Result<(String, u64)> {
    let mut file = std::fs::File::open(path)?;
    let mut hasher = Sha256::new();
    let mut buffer = vec![0u8; 64 * 1024];
    let mut total = 0u64;
    loop {
        let n = match file.read(&mut buffer) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        hasher.update(buffer.get(..n).unwrap_or_default());
        total += n as u64;
    }
    Ok((hex(&hasher.finalize()), total))
}

/// Bytes as lowercase hex.
pub fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 2);
    for b in bytes {
        let _ = write!(s, "{b:02x}");
    }
    s
}

/// The folder a spec's relative data paths are resolved against (as [`crate::pipeline::load`]
/// does).
pub fn spec_dir(spec_path: &Path) -> PathBuf {
    spec_path.parent().map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_known_inputs() {
        // FIPS 180-2 test vectors.
        assert_eq!(hex(&Sha256::digest(b"")), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
        assert_eq!(hex(&Sha256::digest(b"abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }

    #[test]
    fn file_hash_streams_across_chunks() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("big.bin");
        // Larger than one 64 KiB chunk, so the streaming path is exercised.
        let bytes: Vec<u8> = (0..200_000u32).map(|i| (i % 251) as u8).collect();
        std::fs::write(&path, &bytes).expect("write");
        let (hash, len) = hash_file(&path).expect("hash");
        assert_eq!(len, 200_000);
        assert_eq!(hash, hex(&Sha256::digest(&bytes)));
    }

    #[test]
    fn format_names_match_the_spec_spelling() {
        assert_eq!(format_name(DataFormat::Csv), "csv");
        assert_eq!(format_name(DataFormat::Parquet), "parquet");
        assert_eq!(format_name(DataFormat::Npy), "npy");
    }
}
