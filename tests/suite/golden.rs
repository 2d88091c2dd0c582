//! Golden images: a few gallery charts compared with committed references.
//!
//! PNGs must match within 1/255 per channel with zero pixels beyond that; SVGs must match in every
//! non-numeric token and in every number within 0.01. Regenerate with `UPDATE_GOLDENS=1 cargo test
//! --test suite golden`; on failure the actual output and a diff image go to `target/golden-failures/`.

use std::path::PathBuf;

use dataink::data::PathPolicy;
use dataink::pipeline;
use dataink::render;

const CHARTS: &[&str] = &["iris-scatter", "decay", "stock-prices"];

fn golden_dir() -> PathBuf {
    crate::common::root().join("tests/golden")
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

fn compare_png(name: &str, actual: &[u8]) {
    let path = golden_dir().join(format!("{name}.png"));
    let expected =
        std::fs::read(&path).unwrap_or_else(|_| panic!("missing golden {}; run with UPDATE_GOLDENS=1", path.display()));
    let (ew, eh, e) = decode(&expected);
    let (aw, ah, a) = decode(actual);
    assert_eq!((aw, ah), (ew, eh), "{name}.png size");
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
        panic!("{name}.png: {differing} pixels differ by more than 1/255 (see {})", dir.display());
    }
}

fn compare_svg(name: &str, actual: &str) {
    let path = golden_dir().join(format!("{name}.svg"));
    let expected = std::fs::read_to_string(&path).unwrap_or_else(|_| panic!("missing golden {}", path.display()));
    let (et, en) = tokens(&expected);
    let (at, an) = tokens(actual);
    let fail = |what: String| {
        std::fs::create_dir_all(failure_dir()).expect("failure dir");
        std::fs::write(failure_dir().join(format!("{name}.actual.svg")), actual).expect("write");
        panic!("{name}.svg: {what}");
    };
    if et != at {
        let first = et.iter().zip(&at).position(|(a, b)| a != b).unwrap_or(et.len().min(at.len()));
        fail(format!("text differs at token {first}: expected {:?}, got {:?}", et.get(first), at.get(first)));
    }
    for (i, (e, a)) in en.iter().zip(&an).enumerate() {
        if (e - a).abs() > 0.01 {
            fail(format!("number {i} differs: expected {e}, got {a}"));
        }
    }
}

#[test]
fn gallery_charts_match_their_goldens() {
    let loaded = pipeline::load(&crate::common::root().join("examples/gallery.toml"), PathPolicy::InsideSpecFolder)
        .unwrap_or_else(|f| panic!("{}", f.render()));
    for name in CHARTS {
        let (index, chart) = loaded
            .spec
            .chart
            .iter()
            .enumerate()
            .find(|(_, c)| c.name == *name)
            .unwrap_or_else(|| panic!("gallery has {name}"));
        let out = pipeline::draw_chart(&loaded, index, chart).unwrap_or_else(|e| panic!("{e}"));
        let png = render::png::to_png(&out.scene, 1.0).expect("png");
        let svg = render::svg::to_svg(&out.scene);
        crate::common::assert_svg_parses(&svg);
        if updating() {
            std::fs::create_dir_all(golden_dir()).expect("golden dir");
            std::fs::write(golden_dir().join(format!("{name}.png")), &png).expect("write golden");
            std::fs::write(golden_dir().join(format!("{name}.svg")), &svg).expect("write golden");
            continue;
        }
        compare_png(name, &png);
        compare_svg(name, &svg);
    }
}

#[test]
fn svg_tokenizer_separates_numbers_from_text() {
    let (t, n) = tokens(r##"<circle cx="10.5" cy="-3" fill="#1f77b4"/>"##);
    assert_eq!(n, vec![10.5, -3.0]);
    assert_eq!(t[0], "<circle cx=\"");
    assert!(t.last().is_some_and(|s| s.contains("#1f77b4")));
}
