//! A spec's engine source (`engine = "sc://..."`) made into its query: the relation the
//! cluster reads, then the source's transform steps.

use std::path::Path;
use std::time::Duration;

use super::{DEFAULT_TIMEOUT, EngineQuery, EngineUrl, sql};
use crate::spec::{DataFormat, DataSource};

/// The query of engine source `name`; on an error, the source's key it is about and why.
pub fn query_of(source: &DataSource, name: &str, spec_dir: &Path) -> Result<EngineQuery, (&'static str, String)> {
    let engine = source.engine.as_deref().unwrap_or_default();
    let url = EngineUrl::parse(engine).map_err(|e| ("engine", e))?;
    let format = match source.format {
        None => None,
        Some(DataFormat::Parquet) => Some("parquet"),
        Some(DataFormat::Json) => Some("json"),
        Some(other) => {
            return Err(("format", format!("the engine reads Parquet or JSON paths, not {other:?}")));
        }
    };
    let path = source.path.as_deref().map(|p| cluster_path(p, spec_dir));
    let base = sql::relation(source.table.as_deref(), path.as_deref(), format).map_err(|e| ("path", e))?;
    let steps = source.transform.as_deref().unwrap_or_default();
    let query =
        sql::with_steps(base, steps, name).map_err(|(i, e)| ("transform", format!("transform step {}: {e}", i + 1)))?;
    let timeout = source.timeout.map_or(DEFAULT_TIMEOUT, Duration::from_secs_f64);
    Ok(EngineQuery { url, query, timeout })
}

/// A path as the cluster should read it: as written when it is absolute or has a scheme
/// (`s3a://`, `hdfs://`), else relative to the spec's directory, made absolute (a cluster on
/// this machine then reads the file next to the spec).
fn cluster_path(path: &str, spec_dir: &Path) -> String {
    if path.contains("://") || Path::new(path).is_absolute() {
        return path.to_string();
    }
    let joined = spec_dir.join(path);
    let absolute = std::path::absolute(&joined).unwrap_or(joined);
    absolute.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths_are_the_spec_directory_s_and_steps_follow() {
        let source = DataSource {
            engine: Some("sc://127.0.0.1:15002".into()),
            path: Some("data/p.parquet".into()),
            timeout: Some(2.5),
            transform: Some(vec![crate::spec::transform::TransformStep {
                filter: Some("x > 1".into()),
                ..Default::default()
            }]),
            ..Default::default()
        };
        let q = query_of(&source, "p", Path::new("/specs")).unwrap();
        assert_eq!(
            q.query,
            "SELECT * FROM (SELECT * FROM parquet.`/specs/data/p.parquet`) AS rows WHERE (`x` > (1e0))"
        );
        assert_eq!(q.timeout, Duration::from_millis(2500));
        assert_eq!(cluster_path("s3a://b/k.parquet", Path::new("/x")), "s3a://b/k.parquet");
        let bad = DataSource {
            engine: Some("sc://h".into()),
            table: Some("t".into()),
            format: Some(DataFormat::Csv),
            ..Default::default()
        };
        assert_eq!(query_of(&bad, "t", Path::new(".")).unwrap_err().0, "format");
    }
}
