//! Which data paths a spec may read: by default only files inside the spec's own folder.

use std::fmt;
use std::path::{Component, Path, PathBuf};

/// Whether paths outside the spec's folder are allowed (`--allow-outside-paths`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PathPolicy {
    /// Only relative paths that stay inside the spec's folder (the default).
    #[default]
    InsideSpecFolder,
    /// Any path, absolute or relative.
    AllowOutside,
}

/// Why a data path was refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PathError {
    /// The path is absolute.
    Absolute(String),
    /// The path climbs out of the spec's folder with `..`.
    Escapes(String),
    /// The path is empty.
    Empty,
    /// The path stays inside lexically, but a symbolic link on it leads out of the spec's folder.
    LinksOutside(String),
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PathError::Absolute(p) => write!(f, "data path `{p}` is absolute"),
            PathError::Escapes(p) => write!(f, "data path `{p}` leaves the spec's folder"),
            PathError::Empty => write!(f, "data path is empty"),
            PathError::LinksOutside(p) => {
                write!(f, "data path `{p}` leaves the spec's folder through a symbolic link")
            }
        }
    }
}

impl std::error::Error for PathError {}

impl PathError {
    /// How to fix it.
    pub fn hint(&self) -> &'static str {
        match self {
            PathError::Empty => "give the file name relative to the spec file, e.g. path = \"data/iris.csv\"",
            _ => "write the path relative to the spec file and keep the data beside it, or pass --allow-outside-paths",
        }
    }
}

/// Resolve `path` (as written in the spec) against the spec's folder under `policy`.
///
/// The path is first checked lexically (so it also refuses paths to files that do not exist yet),
/// then, when it exists, on its real location: symbolic links are resolved and the result must
/// lie inside the spec's real folder. Links that stay inside the folder are allowed.
pub fn resolve_data_path(spec_dir: &Path, path: &str, policy: PathPolicy) -> Result<PathBuf, PathError> {
    if path.trim().is_empty() {
        return Err(PathError::Empty);
    }
    let candidate = Path::new(path);
    if policy == PathPolicy::AllowOutside {
        return Ok(if candidate.is_absolute() { candidate.to_path_buf() } else { spec_dir.join(candidate) });
    }
    if candidate.is_absolute() || candidate.has_root() {
        return Err(PathError::Absolute(path.to_string()));
    }
    let mut depth: i64 = 0;
    for component in candidate.components() {
        match component {
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return Err(PathError::Absolute(path.to_string())),
        }
        if depth < 0 {
            return Err(PathError::Escapes(path.to_string()));
        }
    }
    let joined = spec_dir.join(candidate);
    let dir = if spec_dir.as_os_str().is_empty() { Path::new(".") } else { spec_dir };
    if let (Ok(real), Ok(real_dir)) = (joined.canonicalize(), dir.canonicalize()) {
        if !real.starts_with(&real_dir) {
            return Err(PathError::LinksOutside(path.to_string()));
        }
    }
    Ok(joined)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_paths_resolve_against_the_spec_folder() {
        let p = resolve_data_path(Path::new("/specs"), "data/a.csv", PathPolicy::InsideSpecFolder);
        assert_eq!(p, Ok(PathBuf::from("/specs/data/a.csv")));
        let p = resolve_data_path(Path::new("/specs"), "data/../b.csv", PathPolicy::InsideSpecFolder);
        assert_eq!(p, Ok(PathBuf::from("/specs/data/../b.csv")));
    }

    #[test]
    fn escaping_and_absolute_paths_are_refused_by_default() {
        let dir = Path::new("/specs");
        assert_eq!(
            resolve_data_path(dir, "../secret.csv", PathPolicy::InsideSpecFolder),
            Err(PathError::Escapes("../secret.csv".into()))
        );
        assert_eq!(
            resolve_data_path(dir, "a/../../b.csv", PathPolicy::InsideSpecFolder),
            Err(PathError::Escapes("a/../../b.csv".into()))
        );
        assert_eq!(
            resolve_data_path(dir, "/etc/passwd", PathPolicy::InsideSpecFolder),
            Err(PathError::Absolute("/etc/passwd".into()))
        );
        assert_eq!(resolve_data_path(dir, " ", PathPolicy::InsideSpecFolder), Err(PathError::Empty));
    }

    #[test]
    fn allow_outside_accepts_both() {
        let dir = Path::new("/specs");
        assert_eq!(resolve_data_path(dir, "../x.csv", PathPolicy::AllowOutside), Ok(PathBuf::from("/specs/../x.csv")));
        assert_eq!(resolve_data_path(dir, "/x.csv", PathPolicy::AllowOutside), Ok(PathBuf::from("/x.csv")));
    }
}
