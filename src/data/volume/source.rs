//! Which data sources are volumes, and reading them: a NIfTI file (`.nii`, `.nii.gz`, `.hdr`
//! with its `.img`, or `format = "nifti"`), a 3-D `.npy` array, or `format = "raw"` with `dims`
//! and `dtype`. Keys that only tables take are refused on a volume, and the other way round.

use std::path::{Path, PathBuf};

use super::Volume;
use super::raw::RawLayout;
use crate::data::compressed::{self, Compression};
use crate::data::load::{LoadError, infer_format};
use crate::data::{PathPolicy, resolve_data_path};
use crate::spec::{ByteOrder, DataFormat, DataSource};

/// A volume read for a data source.
#[derive(Debug)]
pub struct VolumeData {
    /// The volume.
    pub volume: Volume,
    /// The format it was read as.
    pub format: DataFormat,
    /// The files read (a `.hdr`/`.img` pair is two).
    pub files: Vec<PathBuf>,
    /// Notes for the user, each a sentence with its fix.
    pub warnings: Vec<String>,
}

/// The first key given that only volumes take (for a table source's error).
pub fn volume_key(source: &DataSource) -> Option<&'static str> {
    [
        ("spacing", source.spacing.is_some()),
        ("origin", source.origin.is_some()),
        ("dims", source.dims.is_some()),
        ("dtype", source.dtype.is_some()),
        ("byte_order", source.byte_order.is_some()),
        ("header_bytes", source.header_bytes.is_some()),
        ("frame", source.frame.is_some()),
    ]
    .into_iter()
    .find_map(|(key, given)| given.then_some(key))
}

/// The first key given that a volume of `format` does not take.
fn misplaced_key(source: &DataSource, format: DataFormat) -> Option<&'static str> {
    let table_only = [
        ("json_path", source.json_path.is_some()),
        ("parse", source.parse.is_some()),
        ("extent", source.extent.is_some()),
        ("delimiter", source.delimiter.is_some()),
        ("null_values", source.null_values.is_some()),
        ("transform", source.transform.is_some()),
    ];
    let raw_only = [
        ("dims", source.dims.is_some()),
        ("dtype", source.dtype.is_some()),
        ("byte_order", source.byte_order.is_some()),
        ("header_bytes", source.header_bytes.is_some()),
    ];
    let nifti_only = [("frame", source.frame.is_some())];
    let header_given = [("spacing", source.spacing.is_some()), ("origin", source.origin.is_some())];
    let others = if format == DataFormat::Nifti { &header_given[..] } else { &nifti_only[..] };
    let raw_only = if format == DataFormat::Raw { &[][..] } else { &raw_only[..] };
    table_only.iter().chain(raw_only).chain(others).find_map(|&(key, given)| given.then_some(key))
}

/// Whether a file name's format (its extension before any `.gz`/`.zst`) is `ext`.
fn has_inner_extension(path: &Path, ext: &str) -> bool {
    compressed::inner_path(path).extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// `path` with its format extension replaced by `img` (keeping a compression extension).
fn img_beside(path: &str) -> String {
    let p = Path::new(path);
    let compression = Compression::of(p).and_then(|_| p.extension()).and_then(|e| e.to_str()).map(str::to_owned);
    let mut img = compressed::inner_path(p).with_extension("img");
    if let Some(ext) = compression {
        img = PathBuf::from(format!("{}.{ext}", img.display()));
    }
    img.display().to_string()
}

/// Whether `source` is a volume, telling by its `format`, its extension and, for a `.npy` file,
/// its header: `None` for a table source; else its resolved path and format, or why the path is
/// refused.
pub fn classify(
    source: &DataSource,
    spec_dir: &Path,
    policy: PathPolicy,
) -> Option<Result<(PathBuf, DataFormat), LoadError>> {
    let path = source.path.as_deref()?;
    if source.values.is_some() {
        return None;
    }
    let named_volume = matches!(source.format, Some(DataFormat::Nifti | DataFormat::Raw))
        || (source.format.is_none() && ["nii", "hdr"].iter().any(|e| has_inner_extension(Path::new(path), e)));
    let resolved = match resolve_data_path(spec_dir, path, policy) {
        Ok(r) => r,
        Err(e) if named_volume => return Some(Err(LoadError::Path(e))),
        Err(_) => return None,
    };
    let format = source.format.or_else(|| infer_format(&resolved))?;
    let is_volume = match format {
        DataFormat::Nifti | DataFormat::Raw => true,
        // A 3-D array is a volume; anything else (or an unreadable header) is left to the grid
        // reader, whose message says what it needs.
        DataFormat::Npy => super::npy::ndim(&resolved).is_ok_and(|n| n == 3),
        _ => false,
    };
    is_volume.then_some(Ok((resolved, format)))
}

/// Read `source` as a volume if it is one; `None` for a table source (read by
/// [`crate::data::load_source`]).
pub fn load(source: &DataSource, spec_dir: &Path, policy: PathPolicy) -> Option<Result<VolumeData, LoadError>> {
    let path = source.path.as_deref()?;
    let classified = classify(source, spec_dir, policy)?;
    Some(classified.and_then(|(resolved, format)| read(source, path, &resolved, format, spec_dir, policy)))
}

fn read(
    source: &DataSource,
    path: &str,
    resolved: &Path,
    format: DataFormat,
    spec_dir: &Path,
    policy: PathPolicy,
) -> Result<VolumeData, LoadError> {
    if let Some(key) = misplaced_key(source, format) {
        return Err(LoadError::NotApplicable { key, format });
    }
    let mut files = vec![resolved.to_path_buf()];
    let mut warnings = Vec::new();
    let volume = match format {
        DataFormat::Nifti => {
            let img = if has_inner_extension(resolved, "hdr") {
                let img = resolve_data_path(spec_dir, &img_beside(path), policy).map_err(LoadError::Path)?;
                files.push(img.clone());
                Some(img)
            } else {
                None
            };
            let read = super::nifti::read(resolved, img.as_deref(), source.frame)?;
            warnings = read.warnings;
            read.volume
        }
        DataFormat::Raw => {
            let (Some(dims), Some(dtype)) = (source.dims, source.dtype) else {
                let key = if source.dims.is_none() { "dims" } else { "dtype" };
                return Err(LoadError::MissingKey { key, format });
            };
            let layout = RawLayout {
                dims,
                dtype,
                byte_order: source.byte_order.unwrap_or(ByteOrder::Little),
                spacing: source.spacing.unwrap_or([1.0; 3]),
                header_bytes: source.header_bytes.unwrap_or(0),
            };
            super::raw::read(resolved, layout)?
        }
        _ => super::npy::read(resolved, source.spacing.unwrap_or([1.0; 3]))?,
    };
    let volume = match source.origin {
        Some(origin) if format != DataFormat::Nifti => volume
            .with_origin(origin)
            .map_err(|message| LoadError::Parse { origin: format!("`{}`", resolved.display()), format, message })?,
        _ => volume,
    };
    Ok(VolumeData { volume, format, files, warnings })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_and_keys() {
        assert_eq!(img_beside("a/head.hdr"), "a/head.img");
        assert_eq!(img_beside("head.hdr.gz"), "head.img.gz");
        let mut source = DataSource { path: Some("v.nii".into()), spacing: Some([1.0; 3]), ..DataSource::default() };
        assert_eq!(misplaced_key(&source, DataFormat::Nifti), Some("spacing"));
        assert_eq!(misplaced_key(&source, DataFormat::Npy), None);
        assert_eq!(volume_key(&source), Some("spacing"));
        source.dims = Some([1, 1, 1]);
        assert_eq!(misplaced_key(&source, DataFormat::Npy), Some("dims"));
        assert_eq!(misplaced_key(&source, DataFormat::Raw), None);
        source.parse = Some(Default::default());
        assert_eq!(misplaced_key(&source, DataFormat::Raw), Some("parse"));
    }
}
