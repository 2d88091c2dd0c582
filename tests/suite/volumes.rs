//! Volume sources through the spec: NIfTI files, 3-D `.npy` arrays and raw files load as volumes
//! that charts reach through their context, `dataink data` describes them, and keys that do not
//! fit the source are errors that say so.

use std::path::Path;

use crate::common::{Fixture, run_dataink};
use dataink::data::Table;
use dataink::mark::ChartContext;

fn fixture_file(name: &str) -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/volume").join(name)).expect("fixture")
}

const SCATTER: &str = "[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"t\"\nx = \"x\"\ny = \"y\"\n";

#[test]
fn a_nifti_source_is_a_volume_that_charts_reach() {
    let gz = fixture_file("le_sform_i16.nii.gz");
    let spec = format!(
        "[data.head]\npath = \"head.nii.gz\"  # voxel spacing and orientation from the header\n\n[data.t]\npath = \"t.csv\"\n{SCATTER}"
    );
    let csv = "x,y,z,value\n0,0,0,1\n1,0,0,2\n0,1,0,3\n0,0,1,4\n1,1,1,5\n";
    let fx = Fixture::new(&spec, &[("head.nii.gz", &gz), ("t.csv", csv.as_bytes())]);
    let loaded = fx.load().expect("loads");
    let head = &loaded.volumes["head"];
    assert!(!loaded.tables.contains_key("head"), "a volume is not a table");
    assert_eq!(head.dims(), [4, 3, 2]);
    assert_eq!(head.spacing(), [2.0, 2.0, 2.0]);
    assert_eq!(head.value(3, 2, 1), 123.0 * 0.5 - 3.0);
    let chart = &loaded.spec.chart[0];
    let empty = Table::default();
    let cx = ChartContext::new(chart, 0, &empty).with_volume(Some(head));
    assert!(matches!(cx.volume(), Ok(std::borrow::Cow::Borrowed(_))));
    // A long table on a lattice is a volume too, its missing points NaN (the whole table: the
    // scatter chart alone loads only x and y).
    let whole =
        dataink::data::load_source(&loaded.spec.data["t"], fx.dir.path(), Default::default(), None).expect("table");
    let table = ChartContext::new(chart, 0, &whole).volume().expect("lattice");
    assert_eq!(table.dims(), [2, 2, 2]);
    assert_eq!(table.value(1, 1, 1), 5.0);
    assert!(table.value(1, 1, 0).is_nan());
    let err = ChartContext::new(chart, 0, &empty).volume().expect_err("no columns");
    assert!(err.message.starts_with("data \"t\" is not a volume: the table has no column `x`"), "{}", err.message);
}

#[test]
fn dataink_data_describes_a_volume() {
    let spec = format!("[data.head]\npath = \"head.nii\"\n[data.t]\npath = \"t.csv\"\n{SCATTER}");
    let fx = Fixture::new(&spec, &[("head.nii", &fixture_file("be_qform_f32.nii")), ("t.csv", b"x,y\n1,2\n")]);
    let out = run_dataink(fx.dir.path(), &["data", "spec.toml", "head"], 60).expect("finished");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for line in [
        "data \"head\": volume of 4 × 3 × 2 voxels",
        "  dims: 4 × 3 × 2 (24 voxels), stored as f32",
        "  spacing: 1.5 × 0.5 × 2 µm",
        "  values: 0 to 123, 1 missing",
        "  orientation: PRI",
        "  affine x: [         0        0.5          0          5]",
        "  affine y: [      -1.5          0          0         -7]",
        "  affine z: [         0          0         -2         11]",
        "  memory: 96 bytes",
    ] {
        assert!(text.contains(line), "{line:?} in\n{text}");
    }
}

#[test]
fn raw_big_endian_and_3d_npy_sources() {
    let values: Vec<u16> = (0..24).map(|n| n * 1000).collect();
    let mut raw = vec![0xAB; 16];
    raw.extend(values.iter().flat_map(|v| v.to_be_bytes()));
    let data: Vec<u8> = (0..24i16).flat_map(|v| (-v).to_le_bytes()).collect();
    let npy_3d = crate::common::npy("<i2", "(2, 3, 4)", &data);
    let spec = "[data.t]\npath = \"t.csv\"\n[data.ct]\npath = \"ct.raw\"\nformat = \"raw\"\ndims = [4, 3, 2]\ndtype = \"u16\"\nbyte_order = \"big\"\nspacing = [0.5, 0.5, 1.5]\nheader_bytes = 16\n\n[data.field]\npath = \"field.npy\"\nspacing = [1, 2, 3]\norigin = [-1.5, 0, 10]\n\n[data.grid]\npath = \"grid.npy\"\n";
    let grid = crate::common::npy_f8(2, 2, &[1.0, 2.0, 3.0, 4.0]);
    let spec = format!("{spec}{SCATTER}");
    let files: &[(&str, &[u8])] =
        &[("ct.raw", &raw), ("field.npy", &npy_3d), ("grid.npy", &grid), ("t.csv", b"x,y\n1,2\n")];
    let fx = Fixture::new(&spec, files);
    let loaded = fx.load().expect("loads");
    let ct = &loaded.volumes["ct"];
    assert_eq!(ct.values().collect::<Vec<_>>(), values.iter().map(|&v| f64::from(v)).collect::<Vec<_>>());
    assert_eq!(ct.spacing(), [0.5, 0.5, 1.5]);
    let field = &loaded.volumes["field"];
    assert_eq!((field.dims(), field.value(3, 2, 1), field.spacing()), ([4, 3, 2], -23.0, [1.0, 2.0, 3.0]));
    // `origin` places voxel (0, 0, 0); the spacing still steps from it.
    assert_eq!(field.affine(), [[1.0, 0.0, 0.0, -1.5], [0.0, 2.0, 0.0, 0.0], [0.0, 0.0, 3.0, 10.0]]);
    assert_eq!(ct.affine()[0][3], 0.0, "the default origin is 0");
    assert!(loaded.tables.contains_key("grid") && !loaded.volumes.contains_key("grid"), "a 2-D array stays a grid");
}

/// The diagnostics of loading `spec` with `files`.
fn load_error(spec: &str, files: &[(&str, &[u8])]) -> String {
    Fixture::new(&format!("{spec}{SCATTER}"), files).load().expect_err("an error")
}

#[test]
fn keys_that_do_not_fit_the_source_are_errors() {
    let nii = fixture_file("u8_4d.nii");
    let files: &[(&str, &[u8])] = &[("v.nii", &nii), ("t.csv", b"x,y\n1,2\n")];
    let cases = [
        ("[data.v]\npath = \"v.nii\"\nspacing = [1, 1, 1]\n", "data \"v\": `spacing` does not apply to NIfTI-1 files"),
        ("[data.v]\npath = \"v.nii\"\norigin = [1, 2, 3]\n", "data \"v\": `origin` does not apply to NIfTI-1 files"),
        ("[data.v]\npath = \"v.nii\"\nframe = 7\n", "`frame = 7` asks for volume 7, but the file holds 3 (0 to 2)"),
        (
            "[data.v]\npath = \"v.nii\"\ntransform = [{ filter = \"x > 1\" }]\n",
            "`transform` does not apply to NIfTI-1 files",
        ),
        (
            "[data.v]\npath = \"v.nii\"\nformat = \"raw\"\ndtype = \"u8\"\n",
            "data \"v\": reading a raw volume needs `dims`",
        ),
        ("[data.t]\npath = \"t.csv\"\ndims = [1, 2, 3]\n", "data \"t\": `dims` does not apply to CSV files"),
        (
            "[data.v]\npath = \"v.nii\"\n[data.w]\nfrom = \"v\"\n",
            "data \"w\": data \"v\" is a volume; `from`, `join` and `lookup` read tables",
        ),
        ("[data.v]\npath = \"gone.nii.gz\"\n", "data file `"),
    ];
    for (spec, message) in cases {
        let err = load_error(spec, files);
        assert!(err.contains(message), "{spec}\nwants {message:?}\n{err}");
    }
    // A 4-D file read without `frame` loads its first volume, with a warning.
    let loaded = Fixture::new(&format!("[data.v]\npath = \"v.nii\"\n[data.t]\npath = \"t.csv\"\n{SCATTER}"), files)
        .load()
        .expect("loads");
    assert!(loaded.warnings.iter().any(|w| w.message.contains("the file holds 3 volumes")), "{:?}", loaded.warnings);
}

#[test]
fn the_readme_volume_example_loads() {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).expect("README");
    let start = readme.find("[data.head]\npath = \"head.nii.gz\"").expect("the README's volume example");
    let block = &readme[start..start + readme[start..].find("```").expect("end of block")];
    let data: Vec<u8> = (0..8).flat_map(|v| (v as f32).to_le_bytes()).collect();
    let npy = crate::common::npy("<f4", "(2, 2, 2)", &data);
    let spec = format!("{block}\n[data.t]\npath = \"t.csv\"\n{SCATTER}");
    let fx = Fixture::new(
        &spec,
        &[("head.nii.gz", &fixture_file("le_sform_i16.nii.gz")), ("field.npy", &npy), ("t.csv", b"x,y\n1,2\n")],
    );
    // The raw file as a sparse file of the size the example describes.
    let raw = std::fs::File::create(fx.dir.path().join("ct.raw")).expect("create");
    raw.set_len(256 * 256 * 150 * 2).expect("size");
    let loaded = fx.load().expect("the README example loads");
    assert_eq!(loaded.volumes["ct"].dims(), [256, 256, 150]);
    assert_eq!(loaded.volumes["field"].spacing(), [0.5, 0.5, 2.0]);
    assert_eq!(loaded.volumes["head"].orientation(), "RAS");
}

#[test]
fn a_table_kind_pointed_at_a_volume_says_so_at_its_data_key() {
    let spec = "[data.head]\npath = \"head.nii\"\n\n[[chart]]\nname = \"c\"\nkind = \"scatter\"\ndata = \"head\"\nx = \"x\"\ny = \"y\"\n";
    let fx = Fixture::new(spec, &[("head.nii", &fixture_file("be_qform_f32.nii"))]);
    let out = run_dataink(fx.dir.path(), &["render", "spec.toml", "--out", "out"], 60).expect("finished");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("data \"head\" is a volume (4 × 3 × 2 voxels), and kind \"scatter\" draws the rows of a table"),
        "{stderr}"
    );
    // The caret is under the chart's `data` value, not under a column name.
    assert!(stderr.contains("data = \"head\"\n  |        ^^^^^^"), "{stderr}");
}
