//! Hostile inputs: paths that are not regular files (FIFOs, devices, directories) and oversized
//! specs and templates. Each case runs the command-line tool as a child process with a timeout, so
//! a read that blocks or never ends fails the test instead of hanging it.

use crate::common::{Fixture, run_dataink};
use std::path::Path;

const SCATTER: &str = "[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"x\"\ny = \"y\"\n";

/// A fixture whose data source `d` reads `file` (created by the caller).
fn fixture_reading(file: &str) -> Fixture {
    Fixture::new(&format!("[data.d]\npath = \"{file}\"\n{SCATTER}"), &[])
}

/// Run `dataink ARGS` in `dir`, assert it fails (exit 1 or 2, not a panic) within 30 s, and return its stderr.
fn fails(dir: &Path, args: &[&str]) -> String {
    let out = run_dataink(dir, args, 30).expect("dataink finished within 30 s");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out.status.code();
    assert!(matches!(code, Some(1 | 2)), "exit {code:?}: {stderr}");
    stderr
}

fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo").arg(path).status().expect("run mkfifo");
    assert!(status.success());
}

#[cfg(unix)]
#[test]
fn device_behind_a_data_symlink_is_refused() {
    for (name, device) in [("d.npy", "/dev/zero"), ("d.csv", "/dev/urandom")] {
        let fx = fixture_reading(name);
        std::os::unix::fs::symlink(device, fx.dir.path().join(name)).expect("symlink");
        // Allowed outside, so the file-type check (not the path policy) is what refuses it.
        let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--allow-outside-paths"]);
        assert!(err.contains(&format!("cannot read `{name}`")), "{err}");
        assert!(err.contains("it is a device; only regular files are read"), "{err}");
    }
}

#[cfg(unix)]
#[test]
fn devices_and_hostile_headers_as_volume_sources_are_refused() {
    for (name, device) in [("head.nii", "/dev/zero"), ("head.nii.gz", "/dev/urandom")] {
        let fx = Fixture::new(&format!("[data.head]\npath = \"{name}\"\n"), &[]);
        std::os::unix::fs::symlink(device, fx.dir.path().join(name)).expect("symlink");
        let err = fails(fx.dir.path(), &["data", "spec.toml", "--allow-outside-paths"]);
        assert!(err.contains("it is a device; only regular files are read"), "{err}");
    }
    // A header asking for 32767³ voxels, a gzip stream that inflates past its voxels, and one
    // cut short: refused or read to the header's size, quickly, without a giant allocation.
    let fixture = |name: &str| {
        std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/volume").join(name))
            .expect("fixture")
    };
    let mut huge = fixture("le_sform_i16.nii");
    for n in 1..4 {
        huge[40 + 2 * n..42 + 2 * n].copy_from_slice(&32767i16.to_le_bytes());
    }
    let mut bomb = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    let mut inflated = fixture("le_sform_i16.nii");
    inflated.resize(200_000_000, 0);
    std::io::Write::write_all(&mut bomb, &inflated).expect("gzip");
    let bomb = bomb.finish().expect("gzip");
    let cut = fixture("le_sform_i16.nii.gz");
    let spec =
        "[data.huge]\npath = \"huge.nii\"\n[data.bomb]\npath = \"bomb.nii.gz\"\n[data.cut]\npath = \"cut.nii.gz\"\n";
    let fx = Fixture::new(spec, &[("huge.nii", &huge), ("bomb.nii.gz", &bomb), ("cut.nii.gz", &cut[..cut.len() - 40])]);
    let err = fails(fx.dir.path(), &["data", "spec.toml"]);
    assert!(err.contains("the volume is 32767 × 32767 × 32767 voxels, more than the limit of 268435456"), "{err}");
    assert!(err.contains("cut.nii.gz"), "{err}");
    assert!(!err.contains("bomb"), "the bomb's 48 bytes of voxels are read, the rest never inflated: {err}");
}

#[cfg(unix)]
#[test]
fn device_as_tree_source_is_refused() {
    let fx = Fixture::new(
        "[data.d]\npath = \"t.json\"\nformat = \"tree\"\n[[chart]]\nname = \"c\"\nkind = \"treemap\"\ndata = \"d\"\n",
        &[],
    );
    std::os::unix::fs::symlink("/dev/zero", fx.dir.path().join("t.json")).expect("symlink");
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--allow-outside-paths"]);
    assert!(err.contains("it is a device"), "{err}");
}

#[cfg(unix)]
#[test]
fn fifo_as_data_or_spec_does_not_block() {
    let fx = fixture_reading("d.csv");
    mkfifo(&fx.dir.path().join("d.csv"));
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("it is a FIFO; only regular files are read"), "{err}");

    mkfifo(&fx.dir.path().join("fifo.toml"));
    let err = fails(fx.dir.path(), &["render", "fifo.toml", "--out", "out"]);
    assert!(err.contains("cannot read spec file `fifo.toml`: it is a FIFO"), "{err}");
}

#[cfg(unix)]
#[test]
fn device_or_directory_as_spec_is_refused() {
    let fx = fixture_reading("d.csv");
    std::os::unix::fs::symlink("/dev/zero", fx.dir.path().join("zero.toml")).expect("symlink");
    let err = fails(fx.dir.path(), &["render", "zero.toml", "--out", "out"]);
    assert!(err.contains("cannot read spec file `zero.toml`: it is a device"), "{err}");

    std::fs::create_dir(fx.dir.path().join("folder.toml")).expect("mkdir");
    let err = fails(fx.dir.path(), &["render", "folder.toml", "--out", "out"]);
    assert!(err.contains("it is a directory"), "{err}");
}

#[test]
fn directory_as_data_is_refused() {
    let fx = fixture_reading("d.csv");
    std::fs::create_dir(fx.dir.path().join("d.csv")).expect("mkdir");
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("it is a directory; only regular files are read"), "{err}");
}

#[test]
fn oversized_spec_names_the_cap() {
    let fx = fixture_reading("d.csv");
    let mut text = String::from("# padding\n");
    text.push_str(&"#".repeat(17 * 1024 * 1024));
    std::fs::write(fx.dir.path().join("big.toml"), text).expect("write");
    let err = fails(fx.dir.path(), &["render", "big.toml", "--out", "out"]);
    assert!(err.contains("larger than the spec size limit of 16 MiB"), "{err}");
}

#[cfg(unix)]
#[test]
fn device_or_oversized_template_is_refused() {
    let fx = Fixture::new(&format!("[data.d]\nvalues = [{{ x = 1, y = 2 }}]\n{SCATTER}"), &[]);
    std::os::unix::fs::symlink("/dev/urandom", fx.dir.path().join("t.html")).expect("symlink");
    let err = fails(fx.dir.path(), &["report", "spec.toml", "--out", "out", "--template", "t.html"]);
    assert!(err.contains("cannot read template `t.html`: it is a device"), "{err}");

    std::fs::write(fx.dir.path().join("big.html"), "x".repeat(2 * 1024 * 1024)).expect("write");
    let err = fails(fx.dir.path(), &["report", "spec.toml", "--out", "out", "--template", "big.html"]);
    assert!(err.contains("larger than the template size limit of 1 MiB"), "{err}");
}

#[cfg(unix)]
#[test]
fn symlinks_leading_out_of_the_spec_folder_are_refused() {
    let outside = tempfile::tempdir().expect("tempdir");
    std::fs::write(outside.path().join("d.csv"), "x,y\n1,2\n").expect("write");
    let fx = fixture_reading("d.csv");
    std::os::unix::fs::symlink(outside.path().join("d.csv"), fx.dir.path().join("d.csv")).expect("symlink");
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("data path `d.csv` leaves the spec's folder through a symbolic link"), "{err}");
    let ok = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out", "--allow-outside-paths"], 30)
        .expect("finished");
    assert_eq!(ok.status.code(), Some(0), "{}", String::from_utf8_lossy(&ok.stderr));

    // A folder symlink inside the spec folder that leads out is refused too.
    let fx = fixture_reading("sub/d.csv");
    std::os::unix::fs::symlink(outside.path(), fx.dir.path().join("sub")).expect("symlink");
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("through a symbolic link"), "{err}");

    // A link that stays inside is allowed.
    let fx = Fixture::new(&format!("[data.d]\npath = \"link.csv\"\n{SCATTER}"), &[("real.csv", b"x,y\n1,2\n")]);
    std::os::unix::fs::symlink("real.csv", fx.dir.path().join("link.csv")).expect("symlink");
    let ok = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out"], 30).expect("finished");
    assert_eq!(ok.status.code(), Some(0), "{}", String::from_utf8_lossy(&ok.stderr));
}

/// One flipped byte in the shipped `grid-load.parquet` (offset 190545, 0x16 to 0x36) made
/// polars-parquet panic in its thrift decoder ("thrift bool field"); now the read fails with an
/// error naming the file.
#[test]
fn flipped_byte_in_parquet_metadata_is_an_error_not_a_panic() {
    let mut bytes = std::fs::read(crate::common::root().join("examples/data/grid-load.parquet")).expect("example");
    assert_eq!(bytes[190_545], 0x16, "the example file changed; find another metadata byte");
    bytes[190_545] = 0x36;
    let fixture = Fixture::new(&format!("[data.d]\npath = \"d.parquet\"\n{SCATTER}"), &[("d.parquet", &bytes)]);
    let commands: [&[&str]; 2] = [&["render", "spec.toml", "--out", "out"], &["data", "spec.toml", "d"]];
    for args in commands {
        let stderr = fails(fixture.dir.path(), args);
        assert!(stderr.contains("d.parquet"), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// Control and bidi characters in every user string that reaches a page.
const HIDDEN: [char; 4] = ['\u{0}', '\u{7}', '\u{1b}', '\u{202e}'];

#[test]
fn control_and_bidi_characters_reach_no_output() {
    // TOML escapes in the spec; raw characters in the CSV's header and cells.
    let hostile = r"\u0000\u0007\u001B[31m\u202E";
    let spec = format!(
        "title = \"spec {hostile} title\"\n[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\n\
         data = \"d\"\ntitle = \"chart {hostile} title\"\ncaption = \"caption {hostile}\"\n\
         x = \"x\\u0007\\u202E|col\"\ny = {{ field = \"y\", title = \"y {hostile}\" }}\ncolor = \"who\"\n"
    );
    let raw = "\u{0}\u{7}\u{1b}[31m\u{202e}";
    let csv = format!("\"x\u{7}\u{202e}|col\",y,who\n1,2,a{raw}\n2,3,b{raw}\n3,1,c|d\n");
    let fx = Fixture::new(&spec, &[("d.csv", csv.as_bytes())]);
    let out = run_dataink(fx.dir.path(), &["report", "spec.toml", "--out", "report"], 60).expect("finished");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{stderr}");
    let ok = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out"], 60).expect("finished");
    assert_eq!(ok.status.code(), Some(0), "{}", String::from_utf8_lossy(&ok.stderr));

    let read = |p: &str| std::fs::read_to_string(fx.dir.path().join(p)).expect(p);
    let (html, md, svg) = (read("report/index.html"), read("report/report.md"), read("out/c.svg"));
    for (name, text) in [("index.html", &html), ("report.md", &md), ("c.svg", &svg)] {
        for c in HIDDEN {
            assert!(!text.contains(c), "{name} holds {c:?}");
        }
    }
    // The visible text stays: titles, categories and the column name.
    assert!(html.contains("<title>spec [31m title · dataink report</title>"), "{html}");
    assert!(html.contains("chart [31m title"), "chart title");
    assert!(svg.contains("a[31m") && svg.contains("x|col"), "{svg}");
    // Markdown: every table row keeps its six cells, a `|` in user text is escaped.
    for row in md.lines().filter(|l| l.starts_with('|')) {
        let cells = row.replace("\\|", "").matches('|').count();
        assert_eq!(cells, 7, "{row}");
    }
}

/// The `id` column of a data file read through a spec, as the charts see it.
fn id_column(file: &str, bytes: &[u8]) -> Vec<Option<String>> {
    let fx = Fixture::new(&format!("[data.d]\npath = \"{file}\"\n{SCATTER}"), &[(file, bytes)]);
    let loaded = fx.load().unwrap_or_else(|e| panic!("{file}: {e}"));
    let table = &loaded.tables["d"];
    let id = table.column("id").expect("an id column");
    let categories = id.categories().unwrap_or_else(|| panic!("{file}: id read as {}", id.type_name()));
    (0..id.len()).map(|row| categories.value(row).map(str::to_string)).collect()
}

#[test]
fn integers_above_i64_read_as_exact_text() {
    let expected = [Some("18446744073709551615".to_string()), Some("7".to_string())];
    let array = br#"[{"id": 18446744073709551615, "x": 1, "y": 2}, {"id": 7, "x": 2, "y": 3}]"#;
    assert_eq!(id_column("d.json", array), expected);
    let lines = b"{\"id\": 18446744073709551615, \"x\": 1, \"y\": 2}\n{\"id\": 7, \"x\": 2, \"y\": 3}\n";
    assert_eq!(id_column("d.jsonl", lines), expected);
    // Asked for, the text converts to the nearest float.
    let fx = Fixture::new(
        &format!("[data.d]\npath = \"d.json\"\nparse = {{ id = \"number\" }}\n{SCATTER}"),
        &[("d.json", array)],
    );
    let loaded = fx.load().unwrap_or_else(|e| panic!("{e}"));
    let ids = loaded.tables["d"].column("id").and_then(|c| c.numbers()).expect("numbers").to_vec();
    assert_eq!(ids, [18446744073709551615.0, 7.0]);
}

/// `[{"x":1,"y":1,"z":[[...]]}]` with `depth` levels in all.
fn nested_records(depth: usize, lines: bool) -> Vec<u8> {
    let inner = depth - if lines { 1 } else { 2 };
    let record = format!("{{\"x\":1,\"y\":1,\"z\":{}1{}}}", "[".repeat(inner), "]".repeat(inner));
    if lines { format!("{record}\n").into_bytes() } else { format!("[{record}]").into_bytes() }
}

#[test]
fn nesting_past_the_limit_is_refused_before_parsing() {
    for file in ["d.json", "d.jsonl"] {
        let fx = Fixture::new(
            &format!("[data.d]\npath = \"{file}\"\n{SCATTER}"),
            &[(file, &nested_records(20_000, file.ends_with('l')))],
        );
        let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
        assert!(err.contains(file), "{err}");
        assert!(err.contains("nest 20000 levels deep (level 65 opens at byte"), "{err}");
        assert!(err.contains("more than the limit of 64 levels"), "{err}");
    }
    let tree = format!("{}{}", "{\"name\":\"n\",\"children\":[".repeat(10_000), "]}".repeat(10_000));
    let fx = Fixture::new(
        "[data.d]\npath = \"t.json\"\nformat = \"tree\"\n[[chart]]\nname = \"c\"\nkind = \"treemap\"\ndata = \"d\"\n",
        &[("t.json", tree.as_bytes())],
    );
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("nest 20000 levels deep") && err.contains("limit of 128 levels"), "{err}");
}

#[test]
fn sixty_levels_of_records_still_read() {
    use dataink::data::json_path::{JsonContent, read_json};
    for lines in [false, true] {
        // The reader takes them (a chart still cannot use the nested column itself).
        match read_json(&nested_records(60, lines), None, lines) {
            Ok(JsonContent::Frame(df)) => assert_eq!((df.height(), df.width()), (1, 3), "lines: {lines}"),
            other => panic!("lines: {lines}: {other:?}"),
        }
    }
}

/// A spec drawing `x` and `y` of `d.csv` whose bytes the caller writes.
fn csv_fixture(csv: &[u8]) -> Fixture {
    Fixture::new(&format!("[data.d]\npath = \"d.csv\"\n{SCATTER}"), &[("d.csv", csv)])
}

#[test]
fn a_huge_cell_is_quoted_in_a_few_hundred_characters() {
    // Past the 10,000 rows polars looks at to choose the column types, so `x` is read as numbers.
    let mut csv = String::from("x,y\n");
    for i in 0..10_050 {
        csv.push_str(&format!("{i},{i}\n"));
    }
    csv.push_str(&format!("1{},5\n", "9.5".repeat(5 * 1024 * 1024 / 3)));
    let fx = csv_fixture(csv.as_bytes());
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.len() < 2048, "{} bytes: {}", err.len(), &err[..err.len().min(4096)]);
    assert!(err.contains("d.csv"), "{err}");
}

#[test]
fn a_missing_column_among_100000_lists_twenty() {
    let header: Vec<String> = (0..100_000).map(|i| format!("column_{i}")).collect();
    let mut csv = header.join(",");
    csv.push('\n');
    csv.push_str(&vec!["1"; 100_000].join(","));
    csv.push('\n');
    let spec = "[data.d]\npath = \"d.csv\"\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"d\"\nx = \"column_1\"\ny = \"nope\"\n";
    let fx = Fixture::new(spec, &[("d.csv", csv.as_bytes())]);
    let err = fails(fx.dir.path(), &["render", "spec.toml", "--out", "out"]);
    assert!(err.contains("has no column `nope`"), "{}", &err[..err.len().min(4096)]);
    assert!(err.contains("and 99980 more"), "{}", &err[..err.len().min(4096)]);
    assert!(err.len() < 2048, "{} bytes", err.len());
}
