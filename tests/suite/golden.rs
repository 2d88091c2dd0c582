//! Reference images: every chart of every spec in `examples/` compared with its committed
//! reference in `tests/golden/SPEC/` (the SVG kept gzipped).
//!
//! PNGs must match within 1/255 per channel with zero pixels beyond that; SVGs must match in every
//! non-numeric token and in every number within 0.01. Regenerate with `UPDATE_GOLDENS=1 cargo test
//! --test suite golden`; on failure the actual output and a diff image go to `target/golden-failures/`.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use dataink::data::PathPolicy;
use dataink::pipeline;
use dataink::render;

fn golden_root() -> PathBuf {
    crate::common::root().join("tests/golden")
}

/// The example specs, by file stem.
fn example_specs() -> Vec<(String, PathBuf)> {
    let dir = crate::common::root().join("examples");
    let mut specs: Vec<(String, PathBuf)> = std::fs::read_dir(&dir)
        .expect("examples folder")
        .map(|entry| entry.expect("entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .map(|path| (path.file_stem().expect("stem").to_string_lossy().into_owned(), path))
        .collect();
    specs.sort();
    specs
}

/// A gzip stream with no timestamp, so an unchanged reference rewrites to the same bytes.
fn gzip(text: &str) -> Vec<u8> {
    let mut encoder = flate2::GzBuilder::new().mtime(0).write(Vec::new(), flate2::Compression::best());
    encoder.write_all(text.as_bytes()).expect("gzip");
    encoder.finish().expect("gzip")
}

fn gunzip(bytes: &[u8]) -> String {
    let mut text = String::new();
    flate2::read::GzDecoder::new(bytes).read_to_string(&mut text).expect("gzipped SVG reference");
    text
}

fn failure_dir() -> PathBuf {
    crate::common::root().join("target/golden-failures")
}

fn updating() -> bool {
    std::env::var_os("UPDATE_GOLDENS").is_some_and(|v| v == "1")
}

fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("buffer size")];
    let info = reader.next_frame(&mut buf).expect("png frame");
    assert_eq!(info.color_type, png::ColorType::Rgba, "RGBA PNG");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Numbers and the text between them.
fn tokens(svg: &str) -> (Vec<String>, Vec<f64>) {
    let mut texts = Vec::new();
    let mut numbers = Vec::new();
    let mut current = String::new();
    let mut chars = svg.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let starts_number = c.is_ascii_digit()
            || ((c == '-' || c == '.') && svg[i + c.len_utf8()..].starts_with(|d: char| d.is_ascii_digit()));
        let prev_is_word = current.chars().last().is_some_and(|p| p.is_ascii_alphanumeric() || p == '#' || p == '_');
        if starts_number && !prev_is_word {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if d.is_ascii_digit() || d == '.' || d == 'e' {
                    end = j + d.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            match svg[i..end].parse::<f64>() {
                Ok(v) => {
                    texts.push(std::mem::take(&mut current));
                    numbers.push(v);
                }
                Err(_) => current.push_str(&svg[i..end]),
            }
        } else {
            current.push(c);
        }
    }
    texts.push(current);
    (texts, numbers)
}

fn compare_png(dir: &Path, name: &str, actual: &[u8]) -> Result<(), String> {
    let path = dir.join(format!("{name}.png"));
    let expected =
        std::fs::read(&path).unwrap_or_else(|_| panic!("missing golden {}; run with UPDATE_GOLDENS=1", path.display()));
    let (ew, eh, e) = decode(&expected);
    let (aw, ah, a) = decode(actual);
    if (aw, ah) != (ew, eh) {
        return Err(format!("{name}.png is {aw}×{ah}, its reference {ew}×{eh}"));
    }
    let mut differing = 0usize;
    let mut diff = vec![0u8; a.len()];
    for (i, (pa, pe)) in a.chunks_exact(4).zip(e.chunks_exact(4)).enumerate() {
        let worst = pa.iter().zip(pe).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
        if worst > 1 {
            differing += 1;
            diff[i * 4..i * 4 + 4].copy_from_slice(&[255, 0, 0, 255]);
        }
    }
    if differing > 0 {
        let dir = failure_dir();
        std::fs::create_dir_all(&dir).expect("failure dir");
        std::fs::write(dir.join(format!("{name}.actual.png")), actual).expect("write actual");
        let file = std::fs::File::create(dir.join(format!("{name}.diff.png"))).expect("diff file");
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), aw, ah);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header().and_then(|mut w| w.write_image_data(&diff)).expect("write diff");
        return Err(format!("{name}.png: {differing} pixels differ by more than 1/255 (see {})", dir.display()));
    }
    Ok(())
}

fn compare_svg(dir: &Path, name: &str, actual: &str) -> Result<(), String> {
    let path = dir.join(format!("{name}.svg.gz"));
    let expected = gunzip(
        &std::fs::read(&path)
            .unwrap_or_else(|_| panic!("missing golden {}; run with UPDATE_GOLDENS=1", path.display())),
    );
    let (et, en) = tokens(&expected);
    let (at, an) = tokens(actual);
    let fail = |what: String| {
        std::fs::create_dir_all(failure_dir()).expect("failure dir");
        std::fs::write(failure_dir().join(format!("{name}.actual.svg")), actual).expect("write");
        Err(format!("{name}.svg: {what}"))
    };
    if et != at {
        let first = et.iter().zip(&at).position(|(a, b)| a != b).unwrap_or(et.len().min(at.len()));
        return fail(format!("text differs at token {first}: expected {:?}, got {:?}", et.get(first), at.get(first)));
    }
    match en.iter().zip(&an).enumerate().find(|(_, (e, a))| (*e - *a).abs() > 0.01) {
        Some((i, (e, a))) => fail(format!("number {i} differs: expected {e}, got {a}")),
        None => Ok(()),
    }
}

#[test]
fn every_example_chart_matches_its_reference() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for (stem, path) in example_specs() {
        let dir = golden_root().join(&stem);
        let loaded = pipeline::load(&path, PathPolicy::InsideSpecFolder).unwrap_or_else(|f| panic!("{}", f.render()));
        for (index, chart) in loaded.spec.chart.iter().enumerate() {
            let name = &chart.name;
            let out = pipeline::draw_chart(&loaded, index, chart).unwrap_or_else(|e| panic!("{stem}/{name}: {e}"));
            let png = render::png::to_png(&out.scene, 1.0).expect("png");
            let svg = render::svg::to_svg(&out.scene);
            crate::common::assert_svg_parses(&svg);
            checked += 1;
            if updating() {
                std::fs::create_dir_all(&dir).expect("golden dir");
                std::fs::write(dir.join(format!("{name}.png")), &png).expect("write golden");
                std::fs::write(dir.join(format!("{name}.svg.gz")), gzip(&svg)).expect("write golden");
                continue;
            }
            failures.extend(compare_png(&dir, name, &png).err().map(|e| format!("{stem}/{e}")));
            failures.extend(compare_svg(&dir, name, &svg).err().map(|e| format!("{stem}/{e}")));
        }
    }
    // The gallery alone has 35 charts: an empty walk is a broken test, not a pass.
    assert!(checked >= 35, "only {checked} example charts found");
    assert!(
        failures.is_empty(),
        "{} of {checked} charts differ from their references:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn a_reference_differs_when_one_pixel_does() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut pixels = vec![255u8; 4 * 4 * 4];
    let encode = |data: &[u8]| {
        let mut bytes = Vec::new();
        let mut enc = png::Encoder::new(&mut bytes, 4, 4);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header().and_then(|mut w| w.write_image_data(data)).expect("encode");
        bytes
    };
    std::fs::write(dir.path().join("t.png"), encode(&pixels)).expect("write");
    // One channel off by 1/255 is within tolerance; by 2/255 it is a differing pixel.
    pixels[5] = 254;
    assert_eq!(compare_png(dir.path(), "t", &encode(&pixels)), Ok(()));
    pixels[5] = 253;
    let error = compare_png(dir.path(), "t", &encode(&pixels)).expect_err("one pixel differs");
    assert!(error.starts_with("t.png: 1 pixels differ"), "{error}");
    std::fs::write(dir.path().join("t.svg.gz"), gzip(r#"<rect x="1.5" fill="red"/>"#)).expect("write");
    assert_eq!(compare_svg(dir.path(), "t", r#"<rect x="1.505" fill="red"/>"#), Ok(()));
    assert!(compare_svg(dir.path(), "t", r#"<rect x="1.52" fill="red"/>"#).is_err());
    assert!(compare_svg(dir.path(), "t", r#"<rect x="1.5" fill="blue"/>"#).is_err());
}

#[test]
fn svg_tokenizer_separates_numbers_from_text() {
    let (t, n) = tokens(r##"<circle cx="10.5" cy="-3" fill="#1f77b4"/>"##);
    assert_eq!(n, vec![10.5, -3.0]);
    assert_eq!(t[0], "<circle cx=\"");
    assert!(t.last().is_some_and(|s| s.contains("#1f77b4")));
}
