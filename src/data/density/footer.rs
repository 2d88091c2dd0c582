//! The range of a Parquet file's float column from the minima and maxima its footer records for
//! every row group, so that a density view of a plain Parquet file reads its rows once (for the
//! counts) instead of twice. Used only when the statistics settle it exactly: every row group
//! has them (or holds only nulls), the column is `f32` or `f64`, and both ends are finite (and
//! positive for a log axis); otherwise the caller scans the rows.

use std::fs::File;
use std::path::Path;

use polars_parquet::parquet::read::read_metadata;
use polars_parquet::parquet::statistics::Statistics;

/// The smallest and largest value of column `field` of the Parquet file at `path`, from its
/// footer; `None` when the footer cannot settle it (see the module).
pub fn float_range(path: &Path, field: &str, log: bool) -> Option<(f64, f64)> {
    let mut file = File::open(path).ok()?;
    let metadata = read_metadata(&mut file).ok()?;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for group in &metadata.row_groups {
        let mut chunks = group.columns_under_root_iter(field)?;
        let (Some(chunk), None) = (chunks.next(), chunks.next()) else { return None };
        let (min, max, nulls) = match chunk.statistics(&metadata.footer_buf)?.ok()? {
            Statistics::Float(s) => (s.min_value.map(f64::from), s.max_value.map(f64::from), s.null_count),
            Statistics::Double(s) => (s.min_value, s.max_value, s.null_count),
            _ => return None,
        };
        match (min, max) {
            (Some(a), Some(b)) => {
                lo = lo.min(a);
                hi = hi.max(b);
            }
            // A group of nulls only has no minimum or maximum.
            _ if nulls == Some(chunk.num_values()) => {}
            _ => return None,
        }
    }
    (lo.is_finite() && hi.is_finite() && lo <= hi && (!log || lo > 0.0)).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use polars::prelude::*;

    fn write(frame: &mut DataFrame, rows_per_group: usize) -> tempfile::NamedTempFile {
        let file = tempfile::NamedTempFile::new().expect("temp file");
        ParquetWriter::new(file.reopen().expect("reopen"))
            .with_row_group_size(Some(rows_per_group))
            .finish(frame)
            .expect("write parquet");
        file
    }

    #[test]
    fn the_footer_gives_the_columns_range_over_every_row_group() {
        let xs: Vec<f32> = (0..10_000).map(|i| ((i * 7919) % 10_007) as f32 / 100.0 - 20.0).collect();
        let ys: Vec<Option<f64>> =
            (0..10_000).map(|i| if i % 10 == 0 { None } else { Some(i as f64 * 0.5 + 1.0) }).collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v.into()), b.max(v.into())));
        let mut frame = df!("x" => xs, "y" => ys, "t" => vec!["a"; 10_000]).expect("frame");
        let file = write(&mut frame, 1_000);
        assert_eq!(float_range(file.path(), "x", false), Some((lo, hi)));
        assert_eq!(float_range(file.path(), "y", false), Some((1.5, 5_000.5)));
        assert_eq!(float_range(file.path(), "x", true), None, "the smallest x is negative");
        assert_eq!(float_range(file.path(), "t", false), None, "text has no float range");
        assert_eq!(float_range(file.path(), "nope", false), None);
    }

    #[test]
    fn infinities_leave_it_to_a_scan() {
        let mut frame = df!("x" => [1.0, f64::INFINITY, 3.0]).expect("frame");
        let file = write(&mut frame, 2);
        assert_eq!(float_range(file.path(), "x", false), None);
    }
}
