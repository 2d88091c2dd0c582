//! Transform steps of `[data.NAME]`: known answers for every step (hand-computed), derived
//! sources, and bad input reported at its line and column before any chart is drawn.

use crate::common::Fixture;
use dataink::data::{ColumnValues, Table};

const CARS: &str = "Name,Origin,Horsepower,Weight_in_lbs,Miles_per_Gallon,Year\n\
a,USA,130,3504,18,1970-01-01\n\
b,USA,165,3693,15,1971-01-01\n\
c,Japan,95,2372,24,1970-01-01\n\
d,Japan,88,2130,27,1972-01-01\n\
e,Europe,110,2950,,1971-01-01\n\
f,Europe,105,2800,26,1972-01-01\n\
g,USA,90,2600,22,1972-01-01\n";

/// A bar chart over `data` so the spec is complete; the tests read the loaded tables.
fn spec(sources: &str, data: &str, x: &str, y: &str) -> String {
    format!("{sources}\n[[chart]]\nname = \"c\"\nkind = \"bar\"\ndata = \"{data}\"\nx = \"{x}\"\ny = \"{y}\"\n")
}

/// A parallel-coordinates chart over `columns` of `data`, so every one of them is loaded.
fn spec_columns(sources: &str, data: &str, columns: &[&str]) -> String {
    let list: Vec<String> = columns.iter().map(|c| format!("\"{c}\"")).collect();
    format!(
        "{sources}\n[[chart]]\nname = \"c\"\nkind = \"parallel\"\ndata = \"{data}\"\ncolumns = [{}]\n",
        list.join(", ")
    )
}

fn load(text: &str) -> dataink::pipeline::Loaded {
    Fixture::new(text, &[("cars.csv", CARS.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"))
}

fn load_error(text: &str) -> String {
    Fixture::new(text, &[("cars.csv", CARS.as_bytes())]).load().expect_err("the spec should fail")
}

fn numbers(table: &Table, name: &str) -> Vec<f64> {
    table.column(name).and_then(|c| c.numbers()).unwrap_or_else(|| panic!("no numeric column {name}")).to_vec()
}

fn texts(table: &Table, name: &str) -> Vec<String> {
    let cats = table.column(name).and_then(|c| c.categories()).unwrap_or_else(|| panic!("no text column {name}"));
    (0..cats.codes.len()).map(|i| cats.value(i).unwrap_or("(missing)").to_string()).collect()
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x.is_nan() && y.is_nan()) || (x - y).abs() < 1e-9)
}

/// `line:column` of the first occurrence of `needle` in `text` (1-based, as diagnostics print).
fn place(text: &str, needle: &str) -> String {
    let offset = text.find(needle).unwrap_or_else(|| panic!("{needle} not in the spec"));
    let line = text[..offset].matches('\n').count() + 1;
    let column = offset - text[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("spec.toml:{line}:{column}")
}

#[test]
fn filter_calculate_aggregate_as_in_the_readme_sketch() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [
  { filter = "Horsepower > 100 and Origin != 'Japan'" },
  { calculate = "Weight_in_lbs / 2.2046", as = "weight_kg" },
  { aggregate = { mean_mpg = "mean(Miles_per_Gallon)", n = "count()", kg = "max(weight_kg)" }, groupby = ["Origin"] },
]"#,
        "cars",
        "Origin",
        "mean_mpg",
    );
    let loaded = load(&text);
    let t = &loaded.tables["cars"];
    // USA: a (130) and b (165); Europe: e (110, no mpg) and f (105). Japan is filtered out.
    assert_eq!(texts(t, "Origin"), ["USA", "Europe"]);
    assert!(close(&numbers(t, "mean_mpg"), &[16.5, 26.0]), "{:?}", numbers(t, "mean_mpg"));
    // The charts read only what they use: the other aggregates are not loaded.
    assert!(t.column("n").is_none() && t.column("kg").is_none());
}

#[test]
fn every_aggregate_against_hand_computed_values() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ aggregate = { n = "count()", values = "count(Miles_per_Gallon)", total = "sum(Horsepower)", mean = "mean(Horsepower)", median = "median(Horsepower)", lo = "min(Horsepower)", hi = "max(Horsepower)", q = "quantile(Horsepower, 0.25)", sd = "stdev(Miles_per_Gallon)", var = "variance(Miles_per_Gallon)", origins = "distinct(Origin)", first = "first(Horsepower)", last = "last(Horsepower)" } }]
[[chart]]
name = "d"
kind = "scatter"
data = "cars"
x = "n"
y = { field = "values" }
color = "total"
point_size = "mean"
"#,
        "cars",
        "median",
        "lo",
    );
    let fx = Fixture::new(&text, &[("cars.csv", CARS.as_bytes())]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["cars"];
    assert_eq!(t.rows, 1);
    // Horsepower: 130 165 95 88 110 105 90 → sorted 88 90 95 105 110 130 165.
    let one = |name: &str| numbers(t, name)[0];
    assert_eq!((one("n"), one("values"), one("total")), (7.0, 6.0, 783.0));
    assert!((one("mean") - 783.0 / 7.0).abs() < 1e-9);
    assert_eq!((one("median"), one("lo")), (105.0, 88.0));
}

#[test]
fn aggregates_skip_nulls_and_nan_and_stdev_is_the_sample_one() {
    // mpg of the six cars that have one: 18 15 24 27 26 22, mean 22, squared deviations
    // 16 49 4 25 16 0 = 110, sample variance 110 / 5 = 22.
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ aggregate = { sd = "stdev(Miles_per_Gallon)", var = "variance(Miles_per_Gallon)" } }]"#,
        "cars",
        "sd",
        "var",
    );
    let loaded = load(&text);
    let t = &loaded.tables["cars"];
    assert!(close(&numbers(t, "var"), &[22.0]), "{:?}", numbers(t, "var"));
    assert!(close(&numbers(t, "sd"), &[22f64.sqrt()]));
}

#[test]
fn unknown_column_in_an_expression_points_inside_the_string() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ filter = "Horsepowr > 100" }]"#,
        "cars",
        "Origin",
        "Horsepower",
    );
    let out = load_error(&text);
    assert!(out.contains("error: data \"cars\": no column `Horsepowr`"), "{out}");
    assert!(out.contains(&format!("{}\n", place(&text, "Horsepowr"))), "{out}");
    assert!(out.contains("did you mean `Horsepower`?"), "{out}");
}

#[test]
fn problems_in_several_sources_are_reported_together() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ filter = "Origin > 3" }]

[data.more]
path = "cars.csv"
transform = [{ calculate = "year(Name)", as = "y" }]

[data.third]
path = "cars.csv"
transform = [{ aggregate = { m = "mean(Origin)" } }, { filter = "x = ", maxbins = 3 }]"#,
        "cars",
        "Origin",
        "Horsepower",
    );
    let out = load_error(&text);
    assert!(out.contains("error: data \"cars\": `>` compares text with a number"), "{out}");
    assert!(out.contains(&format!("{}\n", place(&text, "Origin > 3"))), "{out}");
    assert!(out.contains("error: data \"more\": `year` needs a date, but column `Name` is text"), "{out}");
    assert!(out.contains("cast it first: { cast = { Name = \"date\" } }"), "{out}");
    // The misplaced option is found before the step is run.
    assert!(out.contains("error: data \"third\": `maxbins` belongs to bin steps, not `filter`"), "{out}");
}

#[test]
fn a_step_needs_exactly_one_step_key() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ filter = "Horsepower > 1", calculate = "1", as = "one" }]"#,
        "cars",
        "Origin",
        "Horsepower",
    );
    let out = load_error(&text);
    assert!(out.contains("one step per table: this one has both `filter` and `calculate`"), "{out}");
    let text = spec("[data.cars]\npath = \"cars.csv\"\ntransform = [{ as = \"x\" }]", "cars", "Origin", "Horsepower");
    let out = load_error(&text);
    assert!(out.contains("this transform step has no step key"), "{out}");
    let text =
        spec("[data.cars]\npath = \"cars.csv\"\ntransform = [{ fitler = \"x\" }]", "cars", "Origin", "Horsepower");
    let out = load_error(&text);
    assert!(out.contains("did you mean `filter`?"), "{out}");
}

#[test]
fn an_empty_result_loads_as_zero_rows() {
    let text = spec(
        "[data.cars]\npath = \"cars.csv\"\ntransform = [{ filter = \"Horsepower > 1000\" }]",
        "cars",
        "Origin",
        "Horsepower",
    );
    let loaded = load(&text);
    assert_eq!(loaded.tables["cars"].rows, 0);
}

#[test]
fn null_tests_in_lists_and_text_functions() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [
  { filter = "Miles_per_Gallon is not null and Origin in ('USA', 'Europe') and not starts_with(Name, 'b')" },
  { calculate = "if(contains(lower(Origin), 'us'), concat(Name, '!'), upper(Name))", as = "label" },
]"#,
        "cars",
        "label",
        "Horsepower",
    );
    let t = &load(&text).tables["cars"];
    assert_eq!(texts(t, "label"), ["a!", "F", "g!"]);
    assert_eq!(numbers(t, "Horsepower"), [130.0, 105.0, 90.0]);
}

#[test]
fn dates_compare_with_iso_text_and_give_their_parts() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ filter = "Year >= '1971-01-01'" }, { calculate = "year(Year) * 10 + month(Year)", as = "ym" }]"#,
        "cars",
        "Name",
        "ym",
    );
    let t = &load(&text).tables["cars"];
    assert_eq!(texts(t, "Name"), ["b", "d", "e", "f", "g"]);
    assert_eq!(numbers(t, "ym"), [19711.0, 19721.0, 19711.0, 19721.0, 19721.0]);
}

#[test]
fn cast_and_parse_with_a_strftime_format() {
    let data = "when,n,flag\n\"Jun 12 1998\",1,yes\n\"Jan 02 2001\",2,no\n";
    let text = spec_columns(
        r#"[data.d]
path = "d.csv"
transform = [{ parse = { when = "date:%b %d %Y", flag = "boolean" } }, { cast = { n = "text" } }, { calculate = "concat(text(year(when)), '/', text(length(n) * 1.5))", as = "label" }]"#,
        "d",
        &["n", "when", "label"],
    );
    let loaded = Fixture::new(&text, &[("d.csv", data.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["d"];
    let Some(ColumnValues::Time(ms)) = t.column("when").map(|c| &c.values) else { panic!("when is a time") };
    // 1998-06-12 and 2001-01-02 at midnight UTC.
    assert_eq!(ms, &[897_609_600_000.0, 978_393_600_000.0]);
    assert_eq!(texts(t, "n"), ["1", "2"]);
    // Whole numbers read as text without a fraction: the year, not "1998.0".
    assert_eq!(texts(t, "label"), ["1998/1.5", "2001/1.5"]);
    let bad = spec("[data.d]\npath = \"d.csv\"\ntransform = [{ cast = { n = \"integer\" } }]", "d", "n", "when");
    let out = Fixture::new(&bad, &[("d.csv", data.as_bytes())]).load().expect_err("no such type");
    assert!(out.contains("no type `integer` to cast to"), "{out}");
}

#[test]
fn bins_as_vega_lite_makes_them() {
    // Horsepower 88..165, maxbins 10: step 10 from 80 to 170.
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ bin = "Horsepower", as = "hp" }, { aggregate = { n = "count()" }, groupby = ["hp", "hp_end"] }, { sort = "hp" }]"#,
        "cars",
        "hp",
        "n",
    );
    let t = &load(&text).tables["cars"];
    assert_eq!(numbers(t, "hp"), [80.0, 90.0, 100.0, 110.0, 130.0, 160.0]);
    assert_eq!(numbers(t, "n"), [1.0, 2.0, 1.0, 1.0, 1.0, 1.0]);
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ bin = "Horsepower", step = 50, extent = [0, 200] }, { aggregate = { n = "count()" }, groupby = ["Horsepower_bin"] }, { sort = "Horsepower_bin" }]"#,
        "cars",
        "Horsepower_bin",
        "n",
    );
    let t = &load(&text).tables["cars"];
    assert_eq!(numbers(t, "Horsepower_bin"), [50.0, 100.0, 150.0]);
    assert_eq!(numbers(t, "n"), [3.0, 3.0, 1.0]);
}

#[test]
fn fold_then_pivot_round_trips() {
    let data = "date,temp_max,temp_min\n2015-01-01,5.0,-1.0\n2015-01-02,7.5,0.5\n";
    let text = spec(
        r#"[data.long]
path = "w.csv"
transform = [{ fold = ["temp_max", "temp_min"], as = ["kind", "temp"] }]

[data.wide]
from = "long"
transform = [{ pivot = "kind", value = "temp", groupby = ["date"] }]"#,
        "long",
        "kind",
        "temp",
    );
    let loaded = Fixture::new(&text, &[("w.csv", data.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let long = &loaded.tables["long"];
    assert_eq!(long.rows, 4);
    assert_eq!(texts(long, "kind"), ["temp_max", "temp_max", "temp_min", "temp_min"]);
    assert_eq!(numbers(long, "temp"), [5.0, 7.5, -1.0, 0.5]);
    let wide = &loaded.tables["wide"];
    assert_eq!(wide.rows, 2);
    assert_eq!(numbers(wide, "temp_max"), [5.0, 7.5]);
    assert_eq!(numbers(wide, "temp_min"), [-1.0, 0.5]);
}

#[test]
fn sort_sample_and_window_functions() {
    let text = spec_columns(
        r#"[data.cars]
path = "cars.csv"
transform = [
  { sort = ["Origin", "-Horsepower"] },
  { window = { rank = "rank()", row = "row_number()", total = "cumsum(Horsepower)", avg = "rolling_mean(Horsepower, 2)", prev = "lag(Horsepower)" }, groupby = ["Origin"], sort = ["-Horsepower"] },
]"#,
        "cars",
        &["Name", "rank", "row", "total", "avg", "prev"],
    );
    let t = &load(&text).tables["cars"];
    // Sorted by Origin, then horsepower descending within it.
    assert_eq!(texts(t, "Name"), ["e", "f", "c", "d", "b", "a", "g"]);
    assert_eq!(numbers(t, "rank"), [1.0, 2.0, 1.0, 2.0, 1.0, 2.0, 3.0]);
    assert_eq!(numbers(t, "row"), [1.0, 2.0, 1.0, 2.0, 1.0, 2.0, 3.0]);
    assert_eq!(numbers(t, "total"), [110.0, 215.0, 95.0, 183.0, 165.0, 295.0, 385.0]);
    assert_eq!(numbers(t, "avg"), [110.0, 107.5, 95.0, 91.5, 165.0, 147.5, 110.0]);
    assert!(close(&numbers(t, "prev"), &[f64::NAN, 110.0, f64::NAN, 95.0, f64::NAN, 165.0, 130.0]));

    let sampled =
        spec("[data.cars]\npath = \"cars.csv\"\ntransform = [{ sample = 3, seed = 7 }]", "cars", "Name", "Horsepower");
    let a = texts(&load(&sampled).tables["cars"], "Name");
    let b = texts(&load(&sampled).tables["cars"], "Name");
    assert_eq!(a.len(), 3);
    assert_eq!(a, b, "the same seed picks the same rows");
    let order: Vec<usize> = a.iter().map(|n| "abcdefg".find(n.as_str()).unwrap_or(99)).collect();
    assert!(order.windows(2).all(|w| w[0] < w[1]), "sampled rows keep their order: {a:?}");
}

#[test]
fn ties_share_a_rank_and_dense_rank_has_no_gaps() {
    let data = "k,v\na,3\nb,1\nc,3\nd,2\n";
    let text = spec_columns(
        r#"[data.d]
path = "d.csv"
transform = [{ window = { r = "rank()", dr = "dense_rank()" }, sort = ["-v"] }]"#,
        "d",
        &["k", "r", "dr"],
    );
    let loaded = Fixture::new(&text, &[("d.csv", data.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["d"];
    assert_eq!(texts(t, "k"), ["a", "c", "d", "b"]);
    assert_eq!(numbers(t, "r"), [1.0, 1.0, 3.0, 4.0]);
    assert_eq!(numbers(t, "dr"), [1.0, 1.0, 2.0, 3.0]);
}

#[test]
fn lookup_and_join_another_source() {
    let regions = "Origin,continent\nUSA,America\nJapan,Asia\n";
    let text = spec(
        r#"[data.regions]
path = "regions.csv"

[data.cars]
path = "cars.csv"
transform = [{ lookup = "regions", on = "Origin", fields = ["continent"] }]

[data.inner]
path = "cars.csv"
transform = [{ join = "regions", on = "Origin" }]"#,
        "cars",
        "Name",
        "continent",
    );
    let loaded = Fixture::new(&text, &[("cars.csv", CARS.as_bytes()), ("regions.csv", regions.as_bytes())])
        .load()
        .unwrap_or_else(|e| panic!("{e}"));
    let cars = &loaded.tables["cars"];
    assert_eq!(cars.rows, 7, "a lookup keeps every row");
    assert_eq!(texts(cars, "continent"), ["America", "America", "Asia", "Asia", "(missing)", "(missing)", "America"]);
    assert_eq!(loaded.tables["inner"].rows, 5, "an inner join drops the European cars");
    let bad = spec(
        "[data.cars]\npath = \"cars.csv\"\ntransform = [{ join = \"region\", on = \"Origin\" }]\n[data.regions]\npath = \"cars.csv\"",
        "cars",
        "Name",
        "Horsepower",
    );
    let out = load_error(&bad);
    assert!(out.contains("no data source \"region\" to join"), "{out}");
    assert!(out.contains("did you mean `regions`?"), "{out}");
}

#[test]
fn flatten_unnests_lists_from_json() {
    let text = spec(
        "[data.d]\nvalues = [{ k = \"a\", v = [1, 2, 3] }, { k = \"b\", v = [4] }]\ntransform = [{ flatten = \"v\" }]",
        "d",
        "k",
        "v",
    );
    let loaded = Fixture::new(&text, &[]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["d"];
    assert_eq!(texts(t, "k"), ["a", "a", "a", "b"]);
    assert_eq!(numbers(t, "v"), [1.0, 2.0, 3.0, 4.0]);
    let out = Fixture::new(&text.replace("flatten = \"v\"", "flatten = \"k\""), &[]).load().expect_err("not a list");
    assert!(out.contains("column `k` holds single values, not lists"), "{out}");
}

#[test]
fn sql_over_the_rows_so_far_and_other_sources() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [
  { filter = "Horsepower >= 95" },
  { sql = "SELECT Origin, COUNT(*) AS n FROM source GROUP BY Origin ORDER BY n DESC, Origin" },
]"#,
        "cars",
        "Origin",
        "n",
    );
    let t = &load(&text).tables["cars"];
    assert_eq!(texts(t, "Origin"), ["Europe", "USA", "Japan"]);
    assert_eq!(numbers(t, "n"), [2.0, 2.0, 1.0]);
    let bad = spec("[data.cars]\npath = \"cars.csv\"\ntransform = [{ sql = \"SELEC 1\" }]", "cars", "Origin", "n");
    let out = load_error(&bad);
    assert!(out.contains("error: data \"cars\": the SQL query fails"), "{out}");
}

#[test]
fn derived_sources_and_their_cycles() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"

[data.usa]
from = "cars"
transform = [{ filter = "Origin == 'USA'" }]"#,
        "usa",
        "Name",
        "Horsepower",
    );
    let loaded = load(&text);
    assert_eq!(loaded.tables["usa"].rows, 3);
    assert_eq!(loaded.tables["cars"].rows, 7);
    let cycle = spec("[data.a]\nfrom = \"b\"\n[data.b]\nfrom = \"a\"\n", "a", "Name", "Horsepower");
    let out = load_error(&cycle);
    assert!(out.contains("data sources build on each other in a cycle: a → b → a"), "{out}");
    let both =
        spec("[data.a]\npath = \"cars.csv\"\nfrom = \"b\"\n[data.b]\npath = \"cars.csv\"", "a", "Name", "Horsepower");
    let out = load_error(&both);
    assert!(out.contains("`data.a` has both `path` and `from`"), "{out}");
}

#[test]
fn transforms_run_on_parquet_with_the_same_answers() {
    use polars::prelude::*;
    let mut df = df!(
        "Origin" => ["USA", "USA", "Japan", "Europe"],
        "Horsepower" => [130.0, 165.0, 95.0, 110.0],
    )
    .expect("frame");
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes).finish(&mut df).expect("parquet");
    let text = spec(
        r#"[data.cars]
path = "cars.parquet"
transform = [{ filter = "Horsepower > 100" }, { aggregate = { hp = "sum(Horsepower)" }, groupby = "Origin" }]"#,
        "cars",
        "Origin",
        "hp",
    );
    let loaded = Fixture::new(&text, &[("cars.parquet", &bytes)]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["cars"];
    assert_eq!(texts(t, "Origin"), ["USA", "Europe"]);
    assert_eq!(numbers(t, "hp"), [295.0, 110.0]);
}

#[test]
fn dataink_data_prints_the_rows_after_the_transforms() {
    let text = spec(
        r#"[data.cars]
path = "cars.csv"
transform = [{ aggregate = { n = "count()" }, groupby = ["Origin"] }]"#,
        "cars",
        "Origin",
        "nope",
    );
    let fx = Fixture::new(&text, &[("cars.csv", CARS.as_bytes())]);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dataink"))
        .args(["data", fx.spec.to_str().unwrap_or_default(), "cars"])
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.starts_with("data \"cars\": 3 rows, 2 columns\n  Origin: str\n  n: f64\n"), "{stdout}");
    assert!(stdout.contains("Japan"), "{stdout}");
}

/// `n` rows of `day,value`: dates from 2020-01-01 and the row index as the value, except that
/// row `missing_at` holds `NA`.
fn dated_rows(n: usize, missing_at: usize) -> String {
    let mut csv = String::from("day,value\n");
    let start = 18_262; // 2020-01-01 in days since the epoch
    for i in 0..n {
        let (y, m, d) = civil_from_days(start + i as i64);
        let value = if i == missing_at { "NA".to_string() } else { i.to_string() };
        csv.push_str(&format!("{y:04}-{m:02}-{d:02},{value}\n"));
    }
    csv
}

/// The proleptic Gregorian date of a day count since 1970-01-01 (Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

#[test]
fn a_missing_text_below_the_inferred_rows_of_a_lazy_scan_is_missing() {
    // The schema is inferred from the first 10,000 rows (numbers and dates only there), so the
    // scan first skips the missing texts; the `NA` at row 12,000 makes it read the file again
    // comparing cells with the list, instead of failing with "could not parse `NA`".
    let csv = dated_rows(12_500, 12_000);
    let text =
        spec_columns("[data.d]\npath = \"d.csv\"\ntransform = [{ filter = \"value >= 0\" }]", "d", &["day", "value"]);
    let loaded = Fixture::new(&text, &[("d.csv", csv.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["d"];
    // The filter drops the missing row (a comparison with a missing value is not true).
    let values = numbers(t, "value");
    assert_eq!(values.len(), 12_499);
    assert_eq!(values[11_999], 11_999.0);
    assert_eq!(values[12_000], 12_001.0);
    // The dates are still instants after the second read: 2020-01-01 and 12,000 days on.
    let Some(ColumnValues::Time(days)) = t.column("day").map(|c| &c.values) else { panic!("day is not a time") };
    assert_eq!(days[0], 1_577_836_800_000.0);
    assert_eq!(days[12_000], 1_577_836_800_000.0 + 12_001.0 * 86_400_000.0);
}

#[test]
fn a_numbers_only_lazy_scan_keeps_its_dates_and_numbers() {
    // No missing text anywhere: the fast scan reuses the inferred schema without the list.
    let csv = dated_rows(300, usize::MAX);
    let text =
        spec_columns("[data.d]\npath = \"d.csv\"\ntransform = [{ filter = \"value >= 100\" }]", "d", &["day", "value"]);
    let loaded = Fixture::new(&text, &[("d.csv", csv.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let t = &loaded.tables["d"];
    assert_eq!(numbers(t, "value"), (100..300).map(f64::from).collect::<Vec<_>>());
    let Some(ColumnValues::Time(days)) = t.column("day").map(|c| &c.values) else { panic!("day is not a time") };
    assert_eq!(days[0], 1_577_836_800_000.0 + 100.0 * 86_400_000.0);
}

#[test]
fn a_text_that_is_not_missing_below_the_inferred_rows_is_an_error_once() {
    let mut csv = dated_rows(10_500, usize::MAX);
    csv.push_str("2049-01-01,lots\n");
    let text =
        spec_columns("[data.d]\npath = \"d.csv\"\ntransform = [{ filter = \"value >= 0\" }]", "d", &["day", "value"]);
    let out = Fixture::new(&text, &[("d.csv", csv.as_bytes())]).load().expect_err("`lots` is not a number");
    assert_eq!(out.matches("error:").count(), 1, "{out}");
    assert!(out.contains("lots"), "{out}");
}

#[test]
fn a_source_drawn_from_a_scan_with_a_late_missing_text_reads_it_as_missing() {
    // The late `NA` is in `raw`; the chart reads `recent`, which starts from it.
    let csv = dated_rows(12_500, 12_000);
    let text = spec_columns(
        "[data.raw]\npath = \"d.csv\"\n[data.recent]\nfrom = \"raw\"\ntransform = [{ filter = \"value >= 11000\" }]",
        "recent",
        &["day", "value"],
    );
    let loaded = Fixture::new(&text, &[("d.csv", csv.as_bytes())]).load().unwrap_or_else(|e| panic!("{e}"));
    let values = numbers(&loaded.tables["recent"], "value");
    assert_eq!(values.len(), 1_499);
    assert!(!values.contains(&12_000.0) && values.contains(&12_001.0));
}
