//! The fuzz targets: the spec checker and each reader run in-process (in a worker process, so an
//! abort or stack overflow ends only the worker); `render` runs the real binary on a mutated
//! gallery chart with its data.

use std::path::{Path, PathBuf};

use dataink::data::{PathPolicy, load_source};
use dataink::spec::{SourceFile, check, parse_spec};
use polars::prelude::*;

use crate::mutate::{Rng, mutate_bytes, mutate_csv, mutate_toml};

/// Every target, in the order the short run visits them.
pub const TARGETS: [&str; 10] = ["spec", "csv", "json", "jsonl", "parquet", "arrow", "npy", "nifti", "tree", "render"];

/// The examples folder of the repository.
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples")
}

fn read(name: &str) -> Vec<u8> {
    std::fs::read(examples().join(name)).unwrap_or_else(|e| panic!("read examples/{name}: {e}"))
}

/// A small Arrow IPC file written by polars (the examples hold none).
fn arrow_seed() -> Vec<u8> {
    let n = 40;
    let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.5).collect();
    let y: Vec<i64> = (0..n).map(|i| i * i).collect();
    let k: Vec<String> = (0..n).map(|i| format!("k{}", i % 5)).collect();
    let mut df = df!("x" => x, "y" => y, "k" => k).expect("frame");
    let mut bytes = Vec::new();
    IpcWriter::new(&mut bytes).finish(&mut df).expect("IPC");
    bytes
}

/// A 3-D `.npy` array (a small volume of big-endian u16 in Fortran order).
fn npy_volume_seed() -> Vec<u8> {
    let mut header = "{'descr': '>u2', 'fortran_order': True, 'shape': (3, 4, 5), }".to_string();
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    bytes.extend((0..60u16).flat_map(|v| (v * 97).to_be_bytes()));
    bytes
}

/// `cars.json` as newline-delimited records.
fn jsonl_seed() -> Vec<u8> {
    let rows: Vec<serde_json::Value> = serde_json::from_slice(&read("data/cars.json")).expect("cars.json");
    rows.iter().take(80).map(|r| format!("{r}\n")).collect::<String>().into_bytes()
}

/// The seed inputs of a reader target, and the file extension and `format` it is read with.
pub fn reader_seeds(target: &str) -> (Vec<Vec<u8>>, &'static str, &'static str) {
    match target {
        "csv" => {
            (vec![read("data/iris.csv"), read("data/fritsch-carlson.csv"), read("data/us-airports.csv")], "csv", "csv")
        }
        "json" => (vec![read("data/cars.json")], "json", "json"),
        "jsonl" => (vec![jsonl_seed()], "jsonl", "json"),
        "parquet" => (vec![read("data/stocks.parquet"), read("data/grid-load.parquet")], "parquet", "parquet"),
        "arrow" => (vec![arrow_seed()], "arrow", "arrow"),
        "npy" => (vec![read("data/franke.npy"), npy_volume_seed()], "npy", "npy"),
        "nifti" => {
            let fixture = |name: &str| {
                let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/volume").join(name);
                std::fs::read(&path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()))
            };
            (vec![fixture("le_sform_i16.nii"), fixture("be_qform_f32.nii"), fixture("u8_4d.nii")], "nii", "nifti")
        }
        "tree" => (vec![read("data/flare.json")], "json", "tree"),
        other => panic!("not a reader target: {other}"),
    }
}

/// One generated input: the main file and, for `render`, a mutated data file with its name.
pub struct Input {
    pub main: Vec<u8>,
    pub extension: &'static str,
    pub data: Option<(String, Vec<u8>)>,
}

/// The input of iteration `iteration` of `target` under `seed`.
pub fn generate(target: &str, seed: u64, iteration: u64) -> Input {
    let stream = TARGETS.iter().position(|t| *t == target).expect("known target") as u64;
    let mut rng = Rng::new(seed, stream, iteration);
    match target {
        "spec" => {
            let text = String::from_utf8(read("gallery.toml")).expect("UTF-8");
            Input { main: mutate_toml(&mut rng, &text).into_bytes(), extension: "toml", data: None }
        }
        "render" => render_input(&mut rng),
        _ => {
            let (seeds, extension, _) = reader_seeds(target);
            let seed_input = rng.pick(&seeds).clone();
            Input { main: mutate_bytes(&mut rng, &seed_input), extension, data: None }
        }
    }
}

/// The gallery split into its preamble with every `[data.*]` table and its `[[chart]]` blocks.
fn gallery_parts() -> (String, Vec<String>) {
    let text = String::from_utf8(read("gallery.toml")).expect("UTF-8");
    let mut head = String::new();
    let mut charts: Vec<String> = Vec::new();
    for line in text.lines() {
        if line.starts_with("[[chart]]") {
            charts.push(String::new());
        }
        match charts.last_mut() {
            Some(chart) if !line.starts_with("[data.") => chart.push_str(line),
            _ => head.push_str(line),
        }
        match charts.last_mut() {
            Some(chart) => chart.push('\n'),
            None => head.push('\n'),
        }
    }
    (head, charts)
}

/// One gallery chart with every data source, its TOML mutated; one time in three, one CSV file
/// it may read mutated too (saved as `mutated.csv`, the spec pointing at it).
fn render_input(rng: &mut Rng) -> Input {
    let (head, charts) = gallery_parts();
    let chart = rng.pick(&charts).clone();
    let mut spec = mutate_toml(rng, &format!("{head}{chart}"));
    let csvs: Vec<&str> = ["iris.csv", "seattle-weather.csv", "franke.csv", "fritsch-carlson.csv", "us-flights.csv"]
        .into_iter()
        .filter(|name| spec.contains(&format!("\"data/{name}\"")))
        .collect();
    let data = if !csvs.is_empty() && rng.below(3) == 0 {
        let name = *rng.pick(&csvs);
        let text = String::from_utf8(read(&format!("data/{name}"))).expect("UTF-8");
        spec = spec.replace(&format!("\"data/{name}\""), "\"mutated.csv\"");
        Some(("csv".to_string(), mutate_csv(rng, &text).into_bytes()))
    } else {
        None
    };
    Input { main: spec.into_bytes(), extension: "toml", data }
}

/// Run one in-process target on `input` in `dir` (the reader's file is written there).
pub fn run_in_process(target: &str, input: &[u8], dir: &Path) {
    if target == "spec" {
        let text = String::from_utf8_lossy(input);
        let source = SourceFile::new("spec.toml", text.as_ref());
        let checked = check(&source);
        for d in &checked.diagnostics {
            let _ = source.render(d);
        }
        return;
    }
    let (_, extension, format) = reader_seeds(target);
    let name = format!("d.{extension}");
    std::fs::write(dir.join(&name), input).expect("write the input");
    let source = SourceFile::new(
        "spec.toml",
        format!(
            "[data.d]\npath = \"{name}\"\nformat = \"{format}\"\n\n[[chart]]\nname = \"c\"\ndata = \"d\"\nkind = \"scatter\"\nx = \"a\"\ny = \"b\"\n"
        ),
    );
    let parsed = parse_spec(&source).unwrap_or_else(|d| panic!("the harness spec does not parse: {d:?}"));
    if let Some(read) = dataink::data::volume::source::load(&parsed.spec.data["d"], dir, PathPolicy::InsideSpecFolder) {
        if let Ok(read) = &read {
            let _ = dataink::data::volume::summary::describe(&read.volume);
        }
        if let Err(e) = read {
            let _ = format!("{e} {}", e.hint());
        }
        return;
    }
    if let Err(e) = load_source(&parsed.spec.data["d"], dir, PathPolicy::InsideSpecFolder, None) {
        let _ = format!("{e} {}", e.hint());
    }
}

/// Copy the example data into `dir/data` once, for render runs.
pub fn stage_render_dir(dir: &Path) {
    let data = dir.join("data");
    std::fs::create_dir_all(&data).expect("mkdir data");
    for entry in std::fs::read_dir(examples().join("data")).expect("examples/data") {
        let path = entry.expect("entry").path();
        std::fs::copy(&path, data.join(path.file_name().expect("name"))).expect("copy example data");
    }
}

/// Write a render input into a staged `dir`: `spec.toml` and `mutated.csv`.
pub fn write_render_input(input: &Input, dir: &Path) -> PathBuf {
    let spec = dir.join("spec.toml");
    std::fs::write(&spec, &input.main).expect("write spec");
    if let Some((_, bytes)) = &input.data {
        std::fs::write(dir.join("mutated.csv"), bytes).expect("write mutated.csv");
    }
    let _ = std::fs::remove_dir_all(dir.join("out"));
    spec
}
