//! A [`Table`] back into a polars frame, so sources read by dataink's own readers (grids, trees,
//! inline values) go through the same transforms as files scanned by polars.

use polars::prelude::*;

use super::table::{ColumnValues, Table};

/// The table as a frame: numbers as `f64` (NaN kept), times as millisecond date-times (missing
/// ones null), categories as text (missing ones null).
pub fn table_to_frame(table: &Table) -> PolarsResult<DataFrame> {
    let mut columns = Vec::with_capacity(table.columns.len());
    for column in &table.columns {
        let name = PlSmallStr::from(column.name.as_str());
        let series = match &column.values {
            ColumnValues::Number(values) => Series::new(name, values.as_slice()),
            ColumnValues::Axis(axis) => Series::new(name, axis.values()),
            ColumnValues::Time(values) => {
                let ms: Vec<Option<i64>> = values.iter().map(|v| v.is_finite().then_some(*v as i64)).collect();
                Series::new(name, ms).cast(&DataType::Datetime(TimeUnit::Milliseconds, None))?
            }
            ColumnValues::Text(cats) => {
                let texts: Vec<Option<&str>> = (0..cats.codes.len()).map(|row| cats.value(row)).collect();
                Series::new(name, texts)
            }
        };
        columns.push(series.into());
    }
    DataFrame::new(table.rows, columns)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::table::{Categories, Column};

    #[test]
    fn round_trip_through_the_loader() -> PolarsResult<()> {
        let table = Table {
            rows: 3,
            columns: vec![
                Column { name: "x".into(), values: ColumnValues::Number(vec![1.5, f64::NAN, -2.0]) },
                Column { name: "t".into(), values: ColumnValues::Time(vec![0.0, 86_400_000.0, f64::NAN]) },
                Column {
                    name: "c".into(),
                    values: ColumnValues::Text(Categories::from_values([Some("a"), None, Some("b")])),
                },
            ],
        };
        let df = table_to_frame(&table)?;
        assert_eq!(df.height(), 3);
        let back = crate::data::load::frame_to_table(&df, "test").map_err(|e| polars_err!(ComputeError: "{e}"))?;
        assert_eq!(back.rows, 3);
        let ColumnValues::Number(x) = &back.columns[0].values else { panic!("x is numbers") };
        assert_eq!((x[0], x[1].is_nan(), x[2]), (1.5, true, -2.0));
        assert!(matches!(&back.columns[1].values, ColumnValues::Time(t) if t[1] == 86_400_000.0 && t[2].is_nan()));
        assert!(
            matches!(&back.columns[2].values, ColumnValues::Text(c) if c.levels == ["a", "b"] && c.codes[1] == Categories::MISSING)
        );
        Ok(())
    }
}
