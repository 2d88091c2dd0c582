//! The `transform = [ ... ]` steps of a data source, as the spec writes them.
//!
//! Each step is one inline table whose *step key* says what it does (`filter`, `calculate`,
//! `cast`, `bin`, `aggregate`, `fold`, `pivot`, `sort`, `sample`, `head`, `window`, `join`, `lookup`,
//! `flatten`, `sql`); the other keys are that step's options. The schema lists every key so
//! unknown ones get "did you mean"; which options belong to which step is checked when the steps
//! are compiled (`data::transform`), with positions.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::types::OneOrMany;

/// One transform step: exactly one step key, plus that step's options.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct TransformStep {
    /// Keep the rows where an expression is true, e.g. `"Horsepower > 100 and Origin != 'Japan'"`.
    #[serde(default)]
    #[schemars(example = &"Horsepower > 100 and Origin != 'Japan'")]
    pub filter: Option<String>,
    /// A new column from an expression (arithmetic, math, string and date functions, `if`),
    /// named by `as`.
    #[serde(default)]
    #[schemars(example = &"Weight_in_lbs / 2.2046")]
    pub calculate: Option<String>,
    /// Column types by name: `"number"`, `"text"`, `"boolean"`, `"category"`, `"date"` (ISO) or
    /// `"date:FORMAT"` with a strftime format such as `"date:%b %d %Y"`.
    #[serde(default)]
    pub cast: Option<BTreeMap<String, String>>,
    /// Like `cast`: text parsed into the given types.
    #[serde(default)]
    pub parse: Option<BTreeMap<String, String>>,
    /// Bin a numeric column into nice intervals (as Vega-Lite makes them); writes the bin start
    /// to `as` (default `NAME_bin`) and its end to `AS_end`.
    #[serde(default)]
    pub bin: Option<String>,
    /// `bin`: the largest number of bins (default 10).
    #[serde(default)]
    #[schemars(range(min = 1, max = 100000))]
    pub maxbins: Option<u32>,
    /// `bin`: an exact bin width instead of `maxbins`.
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    pub step: Option<f64>,
    /// `bin`: the range to bin `[lo, hi]` (default: the column's minimum and maximum).
    #[serde(default)]
    pub extent: Option<[f64; 2]>,
    /// Output columns by name, each an aggregate call: `count()`, `count(x)`, `sum(x)`,
    /// `mean(x)`, `median(x)`, `min(x)`, `max(x)`, `quantile(x, 0.9)`, `stdev(x)`,
    /// `variance(x)`, `distinct(x)`, `first(x)`, `last(x)`.
    #[serde(default)]
    pub aggregate: Option<BTreeMap<String, String>>,
    /// `aggregate`, `pivot`, `window`: the columns to group by.
    #[serde(default)]
    pub groupby: Option<OneOrMany<String>>,
    /// Columns folded into key/value rows (wide to long); names the two new columns with
    /// `as = ["key", "value"]`.
    #[serde(default)]
    pub fold: Option<Vec<String>>,
    /// A column whose values become new columns (long to wide), filled from `value`.
    #[serde(default)]
    pub pivot: Option<String>,
    /// `pivot`: the column whose values fill the new columns.
    #[serde(default)]
    pub value: Option<String>,
    /// `pivot`: how several values of one cell combine: `sum` (default), `mean`, `median`, `min`,
    /// `max`, `count`, `first`, `last`.
    #[serde(default)]
    pub op: Option<String>,
    /// Sort by columns, `-name` for descending: `sort = ["-count", "name"]`. In `window`, the
    /// order the window functions see.
    #[serde(default)]
    pub sort: Option<OneOrMany<String>>,
    /// Keep this many rows picked at random (without replacement, seeded).
    #[serde(default)]
    #[schemars(range(min = 1))]
    pub sample: Option<u64>,
    /// `sample`: the random seed (default 0), so the same rows are picked on every run.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Keep the first this many rows.
    #[serde(default)]
    pub head: Option<u64>,
    /// New columns by name, each a window function over the rows in `sort` order within
    /// `groupby`: `rank()`, `dense_rank()`, `row_number()`, `cumsum(x)`, `cumcount()`,
    /// `cummax(x)`, `cummin(x)`, `rolling_mean(x, 7)`, `rolling_sum(x, 7)`, `rolling_min(x, 7)`,
    /// `rolling_max(x, 7)`, `lag(x)`, `lead(x)`.
    #[serde(default)]
    pub window: Option<BTreeMap<String, String>>,
    /// Join another data source: `join = "OTHER", on = "key"` (or `on = ["a", "b"]`).
    #[serde(default)]
    pub join: Option<String>,
    /// Look up columns of another source by key (a left join keeping every row): `lookup =
    /// "OTHER", on = "key", fields = ["a", "b"]`.
    #[serde(default)]
    pub lookup: Option<String>,
    /// `join`, `lookup`: the key columns, the same name on both sides.
    #[serde(default)]
    pub on: Option<OneOrMany<String>>,
    /// `join`: `inner` (default), `left` or `full`.
    #[serde(default)]
    pub how: Option<String>,
    /// `lookup`, `join`: the other source's columns to bring (default: all).
    #[serde(default)]
    pub fields: Option<Vec<String>>,
    /// List columns unnested into one row per item.
    #[serde(default)]
    pub flatten: Option<OneOrMany<String>>,
    /// A polars SQL query over the rows so far, which are the table `source` (and the data
    /// source's own name): `sql = "SELECT Origin, count(*) AS n FROM source GROUP BY Origin"`.
    #[serde(default)]
    pub sql: Option<String>,
    /// The new column's name (`calculate`, `bin`), or names (`fold`: key and value).
    #[serde(default, rename = "as")]
    pub as_: Option<OneOrMany<String>>,
}
