//! Real files as people have them: the `vega-datasets` npm package, installed by
//! `scripts/fetch_vega_datasets.sh` into `tests/data/vega/` (ignored by git). Without it these
//! tests print a note and pass, except in CI (`CI` set), where a missing folder fails them.
//!
//! Known answers were counted outside dataink: row counts with Python's json module, the Arrow
//! file's rows and delay sum with the apache-arrow package for JavaScript.

use std::path::PathBuf;

use dataink::data::{ColumnValues, PathPolicy, SourceData, load_source_with_warnings};
use dataink::spec::DataSource;
use serde_json::json;

/// The folder of the installed data files, or `None` (with a note) when it is absent outside CI.
fn data_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("DATAINK_VEGA_DATA").map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/vega/node_modules/vega-datasets/data")
    });
    if dir.join("miserables.json").is_file() {
        return Some(dir);
    }
    crate::common::skip_outside_ci(
        &format!("vega-datasets is missing from {}: CI must run scripts/fetch_vega_datasets.sh first", dir.display()),
        &format!("note: {} is absent; run scripts/fetch_vega_datasets.sh to test real datasets", dir.display()),
    );
    None
}

/// Load one source whose keys are given as JSON (as they would be in the spec).
fn load(dir: &std::path::Path, keys: serde_json::Value) -> Result<SourceData, String> {
    let source: DataSource = serde_json::from_value(keys).expect("a valid data source");
    load_source_with_warnings(&source, dir, PathPolicy::InsideSpecFolder, None)
        .map_err(|e| format!("{e} ({})", e.hint()))
}

fn numbers<'a>(data: &'a SourceData, name: &str) -> &'a [f64] {
    data.table.column(name).and_then(|c| c.numbers()).unwrap_or_else(|| panic!("numeric column {name}"))
}

#[test]
fn miserables_nodes_and_links_by_json_path() {
    let Some(dir) = data_dir() else { return };
    let nodes = load(&dir, json!({"path": "miserables.json", "json_path": "nodes"})).expect("nodes");
    assert_eq!(nodes.table.rows, 77);
    assert_eq!(nodes.table.column_names(), ["name", "group", "index"]);
    let names = nodes.table.column("name").and_then(|c| c.categories()).expect("names");
    assert_eq!(names.value(0), Some("Myriel"));
    let links = load(&dir, json!({"path": "miserables.json", "json_path": "links"})).expect("links");
    assert_eq!(links.table.rows, 254);
    assert_eq!(links.table.column_names(), ["source", "target", "value"]);
    assert_eq!(numbers(&links, "source")[0], 1.0);
    let err = load(&dir, json!({"path": "miserables.json", "json_path": "edges"})).expect_err("no such key");
    assert!(err.contains("the top level has no key `edges`"), "{err}");
    assert!(err.contains("keys: `nodes`, `links`"), "{err}");
    let err = load(&dir, json!({"path": "miserables.json"})).expect_err("an object without a path");
    assert!(err.contains("name its array of records with json_path = \"nodes\""), "{err}");
}

#[test]
fn volcano_is_a_grid() {
    let Some(dir) = data_dir() else { return };
    let grid = load(&dir, json!({"path": "volcano.json"})).expect("volcano");
    assert_eq!(grid.table.rows, 87 * 61);
    assert_eq!(grid.table.column_names(), ["x", "y", "value"]);
    let (x, y, v) = (numbers(&grid, "x"), numbers(&grid, "y"), numbers(&grid, "value"));
    assert_eq!((x[86], y[86], x[87], y[87]), (86.0, 0.0, 0.0, 1.0), "87 columns along x, rows along y");
    assert_eq!(&v[..5], [103.0, 104.0, 104.0, 105.0, 105.0]);
    let extent = load(&dir, json!({"path": "volcano.json", "extent": [0.0, 870.0, 0.0, 600.0]})).expect("extent");
    assert_eq!(numbers(&extent, "x")[86], 870.0);
}

#[test]
fn flights_arrow_file() {
    let Some(dir) = data_dir() else { return };
    let flights = load(&dir, json!({"path": "flights-200k.arrow"})).expect("arrow");
    assert_eq!(flights.table.rows, 200_000);
    assert_eq!(flights.table.column_names(), ["delay", "distance", "time"]);
    assert_eq!(numbers(&flights, "delay").iter().sum::<f64>(), 1_500_159.0);
    assert_eq!(numbers(&flights, "distance")[199_999], 1452.0);
    let only = load_source_with_warnings(
        &serde_json::from_value(json!({"path": "flights-200k.arrow"})).expect("source"),
        &dir,
        PathPolicy::InsideSpecFolder,
        Some(&["time".to_string()]),
    )
    .expect("one column");
    assert_eq!(only.table.column_names(), ["time"]);
}

#[test]
fn earthquakes_geojson_points() {
    let Some(dir) = data_dir() else { return };
    // The file ends in .json, so the format is named.
    let quakes = load(&dir, json!({"path": "earthquakes.json", "format": "geojson"})).expect("geojson");
    assert_eq!(quakes.table.rows, 1707);
    let names = quakes.table.column_names();
    assert!(names.contains(&"mag") && names.contains(&"place"), "{names:?}");
    assert!(!names.contains(&"geometry"), "points only: no geometry text column");
    assert_eq!((numbers(&quakes, "lon")[0], numbers(&quakes, "lat")[0]), (-118.6671667, 34.4945));
    assert!(numbers(&quakes, "lat").iter().all(|v| (-90.0..=90.0).contains(v)));
}

#[test]
fn movies_release_dates_warn_then_parse() {
    let Some(dir) = data_dir() else { return };
    let movies = load(&dir, json!({"path": "movies.json"})).expect("movies");
    assert_eq!(movies.table.rows, 3201);
    let release = movies.table.column("Release Date").expect("column");
    assert!(matches!(release.values, ColumnValues::Text(_)));
    assert_eq!(movies.warnings.len(), 1, "{:?}", movies.warnings);
    assert!(movies.warnings[0].contains("parse = { \"Release Date\" = \"date:%b %d %Y\" }"), "{}", movies.warnings[0]);
    // 1,600 distinct release dates among the 3,201 films (counted in Python from the shipped file).
    assert!(movies.warnings[0].contains("read as text (1600 categories)"), "{}", movies.warnings[0]);
    let parsed = load(&dir, json!({"path": "movies.json", "parse": {"Release Date": "date:%b %d %Y"}})).expect("parse");
    assert!(parsed.warnings.is_empty(), "{:?}", parsed.warnings);
    let ColumnValues::Time(ms) = &parsed.table.column("Release Date").expect("column").values else {
        panic!("a time column")
    };
    // "Jun 12 1998" is the first film's release date: 1998-06-12 at midnight UTC.
    assert_eq!(ms[0], 897_609_600_000.0);
    assert!(ms.iter().all(|v| v.is_finite()), "every date reads");
}

// Small self-made files through the whole pipeline, so the readers are tested without the npm data.

mod self_made {
    use std::io::Write;

    use polars::prelude::*;

    use crate::common::Fixture;

    fn gzip(bytes: &[u8]) -> Vec<u8> {
        let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        encoder.write_all(bytes).expect("gzip in memory");
        encoder.finish().expect("gzip in memory")
    }

    fn spec(data: &str) -> String {
        format!("{data}\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\n")
    }

    fn numbers(loaded: &dataink::pipeline::Loaded, column: &str) -> Vec<f64> {
        loaded.tables["d"].column(column).and_then(|c| c.numbers()).map(<[f64]>::to_vec).expect("numbers")
    }

    #[test]
    fn gzip_and_zstd_files_read_like_the_plain_ones() {
        let csv = b"x,y\n1,2\n3,4\n5,6\n";
        let json = br#"[{"x": 1, "y": 2}, {"x": 3, "y": 4}]"#;
        let lines = b"{\"x\": 7, \"y\": 8}\n{\"x\": 9, \"y\": 10}\n";
        let zst = zstd::encode_all(&csv[..], 3).expect("zstd");
        for (name, bytes, xs) in [
            ("d.csv.gz", gzip(csv), vec![1.0, 3.0, 5.0]),
            ("d.csv.zst", zst, vec![1.0, 3.0, 5.0]),
            ("d.json.gz", gzip(json), vec![1.0, 3.0]),
            ("d.jsonl.gz", gzip(lines), vec![7.0, 9.0]),
        ] {
            let f = Fixture::new(&spec(&format!("[data.d]\npath = \"{name}\"")), &[(name, &bytes)]);
            let loaded = f.load().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(numbers(&loaded, "x"), xs, "{name}");
        }
    }

    #[test]
    fn a_corrupt_gzip_is_a_positioned_error() {
        let full = gzip(&b"x,y\n1,2\n".repeat(500));
        let f = Fixture::new(&spec("[data.d]\npath = \"d.csv.gz\""), &[("d.csv.gz", &full[..full.len() / 2])]);
        let err = f.load().expect_err("truncated gzip");
        assert!(err.contains("data \"d\": cannot decompress"), "{err}");
        assert!(err.contains("as gzip"), "{err}");
        assert!(err.contains("the file is not valid gzip or is cut short"), "{err}");
    }

    #[test]
    fn an_arrow_file_written_by_polars() {
        let mut df = df!("x" => [1.0f64, 2.0, 4.0], "y" => [10i64, 20, 40], "k" => ["a", "b", "c"]).expect("frame");
        let mut bytes = Vec::new();
        IpcWriter::new(&mut bytes).finish(&mut df).expect("IPC");
        for name in ["d.arrow", "d.feather", "d.ipc", "d.arrow.gz"] {
            let data = if name.ends_with(".gz") { gzip(&bytes) } else { bytes.clone() };
            let f = Fixture::new(&spec(&format!("[data.d]\npath = \"{name}\"")), &[(name, &data)]);
            let loaded = f.load().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(numbers(&loaded, "x"), [1.0, 2.0, 4.0], "{name}");
            // Only the charted columns are read.
            assert_eq!(loaded.tables["d"].column_names(), ["x", "y"], "{name}");
        }
        let f = Fixture::new(&spec("[data.d]\npath = \"d.arrow\""), &[("d.arrow", &bytes[..bytes.len() - 20])]);
        let err = f.load().expect_err("truncated");
        assert!(err.contains("cannot read") && err.contains("as Arrow IPC"), "{err}");
    }

    #[test]
    fn an_unknown_extension_lists_every_format() {
        let f = Fixture::new(&spec("[data.d]\npath = \"d.dat\""), &[("d.dat", b"x,y\n1,2\n")]);
        let err = f.load().expect_err("unknown");
        assert!(err.contains("cannot tell the format of"), "{err}");
        assert!(err.contains("parquet, json, arrow, geojson, npy, matrix, tree"), "{err}");
    }

    #[test]
    fn geojson_and_json_path_through_the_pipeline() {
        let geo = br#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"y": 5}, "geometry": {"type": "Point", "coordinates": [2.5, 48.75]}},
            {"type": "Feature", "properties": {"y": 6}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}}]}"#;
        let text = "[data.d]\npath = \"d.geojson\"\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"lon\"\ny = \"lat\"\n";
        let loaded = Fixture::new(text, &[("d.geojson", geo)]).load().expect("geojson");
        let t = &loaded.tables["d"];
        assert_eq!(t.column_names(), ["y", "lon", "lat", "geometry", "geometry_type"]);
        let lat = t.column("lat").and_then(|c| c.numbers()).expect("lat");
        assert_eq!(lat[0], 48.75);
        assert!(lat[1].is_nan());
        let kinds = t.column("geometry_type").and_then(|c| c.categories()).expect("types");
        assert_eq!((kinds.value(0), kinds.value(1)), (Some("Point"), Some("LineString")));

        let nested = br#"{"meta": {"n": 2}, "data": {"rows": [{"x": 1, "y": 2}, {"x": 3, "y": 4}]}}"#;
        let ok = Fixture::new(&spec("[data.d]\npath = \"d.json\"\njson_path = \"data.rows\""), &[("d.json", nested)]);
        assert_eq!(numbers(&ok.load().expect("dotted path"), "y"), [2.0, 4.0]);
        let bad = Fixture::new(&spec("[data.d]\npath = \"d.json\"\njson_path = \"data.row\""), &[("d.json", nested)]);
        let err = bad.load().expect_err("wrong key");
        assert!(err.contains("`data` has no key `row`"), "{err}");
        assert!(err.contains("did you mean `rows`? keys: `rows`"), "{err}");
        let csv = Fixture::new(&spec("[data.d]\npath = \"d.csv\"\njson_path = \"a\""), &[("d.csv", b"x,y\n1,2\n")]);
        let err = csv.load().expect_err("json_path on CSV");
        assert!(err.contains("`json_path` does not apply to CSV files"), "{err}");
    }

    /// A spec charting `when` and `id` (only charted columns are read from a CSV file).
    fn dated(data: &str) -> String {
        format!(
            "{data}\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"when\"\ny = \"y\"\ncolor = \"id\"\n"
        )
    }

    #[test]
    fn parse_rules_and_the_date_warning() {
        let csv = b"x,y,when,id\n1,2,12/26/1998,007\n2,3,01/02/1999,010\n";
        let f = Fixture::new(&dated("[data.d]\npath = \"d.csv\""), &[("d.csv", csv)]);
        let loaded = f.load().expect("loads with a warning");
        let warnings: Vec<&str> = loaded.warnings.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(
            warnings,
            [
                "data \"d\": column `when` holds dates written like `12/26/1998`, which are read as text (2 categories); \
              read them as times with parse = { when = \"date:%m/%d/%Y\" }"
            ]
        );
        let parsed = "[data.d]\npath = \"d.csv\"\nparse = { when = \"date:%m/%d/%Y\", id = \"text\" }";
        let loaded = Fixture::new(&dated(parsed), &[("d.csv", csv)]).load().expect("parsed");
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        let t = &loaded.tables["d"];
        let ids = t.column("id").and_then(|c| c.categories()).expect("text ids");
        assert_eq!((ids.value(0), ids.value(1)), (Some("007"), Some("010")));
        let when = t.column("when").expect("when");
        assert!(matches!(&when.values, dataink::data::ColumnValues::Time(ms) if ms[0] == 914_630_400_000.0));

        let bad = "[data.d]\npath = \"d.csv\"\nparse = { when = \"date:%d/%m/%Y\" }";
        let err = Fixture::new(&dated(bad), &[("d.csv", csv)]).load().expect_err("26 is no month");
        assert!(
            err.contains("column `when` of") && err.contains("cannot be read with parse rule \"date:%d/%m/%Y\": 1 of 2 values do not read as `date:%d/%m/%Y`, e.g. `12/26/1998` in row 1"),
            "{err}"
        );
        let typo = "[data.d]\npath = \"d.csv\"\nparse = { wehn = \"date\" }";
        let err = Fixture::new(&dated(typo), &[("d.csv", csv)]).load().expect_err("no such column");
        assert!(err.contains("did you mean `when`?"), "{err}");
    }
}
