//! Explorer benchmarks (criterion): `cargo bench --bench explore`.
//!
//! 100,000 rows × 8 columns, drawn as a 6 × 6 splom (800 × 800) and 8-axis parallel
//! coordinates (820 × 440) on one data source, as `dataink explore` shows them.
//!
//! - `explore/brush_frame`: one frame of a brush drag in a splom cell — the brush's rows found
//!   through the cell's scales, both linked charts relit (their 30 + 1 mark tiles split into
//!   grey context and lit rows and rasterized again, in parallel) and the count legends
//!   rewritten. This is all the work a frame does before egui uploads the changed tiles.
//! - `explore/mask_only`: the brush's rows alone (no drawing).
//! - `explore/relight_splom`, `explore/relight_parallel`: the same relight done exactly, every
//!   mark tile rasterized again (what the counting in `explore::counts` avoids).
//! - `explore/draw_both`: drawing both charts from scratch (what zoom and pan cost).
//! - `explore/window_frame`: a whole window frame during a drag, headless (egui_kittest): input,
//!   layout, the brush, both charts relit, the changed tiles handed to egui as textures.
//!
//! The 256³ field of four Gaussian blobs (`common::blobs`) as an isosurface (640 × 560) and a
//! volume rendering (640 × 560, 512 rays across):
//!
//! - `explore_volume/level_frame`: the iso value slider moved (0.5 and 0.45 in turn): the
//!   active cells from the span-space index, marching cubes, shading and the chart's tiles.
//! - `explore_volume/level_frame_scan`: the same surfaces found by scanning every cell (what
//!   the index avoids).
//! - `explore_volume/turn_surface`, `explore_volume/turn_volume_preview`: a drag turning the
//!   camera by a degree: the isosurface drawn again, and the volume rendering cast with 128
//!   rays across; `explore_volume/volume_full`: such a preview and then the rendering at full
//!   resolution (a drag of one frame and its release).

mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::io::Write as _;

use dataink::data::PathPolicy;
use dataink::explore::app::ExploreApp;
use dataink::explore::brush::Mode;
use dataink::explore::{Session, Target};
use dataink::scene::Point;
use eframe::egui;

const ROWS: usize = 100_000;

/// Write the table and spec into a temporary folder and open a session over them.
fn session(dir: &std::path::Path) -> Session {
    let mut uniform = common::uniform(0x9e37_79b9_7f4a_7c15);
    let mut csv = std::io::BufWriter::new(std::fs::File::create(dir.join("table.csv")).expect("csv"));
    writeln!(csv, "c0,c1,c2,c3,c4,c5,c6,c7,group").expect("write");
    for i in 0..ROWS {
        let g = i % 3;
        let base = (uniform() - 0.5) * 3.0 + g as f64 * 1.5;
        let row: Vec<String> = (0..8)
            .map(|j| format!("{:.4}", base * (0.4 + 0.15 * j as f64) + (uniform() - 0.5) * (1.0 + 0.2 * j as f64)))
            .collect();
        writeln!(csv, "{},g{g}", row.join(",")).expect("write");
    }
    drop(csv);
    let spec = r#"
[data.table]
path = "table.csv"

[[chart]]
name = "splom"
kind = "splom"
data = "table"
size = [800, 800]
columns = ["c0", "c1", "c2", "c3", "c4", "c5"]
color = "group"

[[chart]]
name = "parallel"
kind = "parallel"
data = "table"
columns = ["c0", "c1", "c2", "c3", "c4", "c5", "c6", "c7"]
color = "group"
"#;
    std::fs::write(dir.join("spec.toml"), spec).expect("spec");
    let loaded = dataink::pipeline::load(&dir.join("spec.toml"), PathPolicy::InsideSpecFolder).expect("spec loads");
    Session::new(loaded, 1.0)
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path());
    let plot = s.charts[0].geometry.plots[0].clone();
    let r = plot.rect;
    let start = Point::new(r.x + r.w * 0.3, r.y + r.h * 0.3);
    let mut group = c.benchmark_group("explore");
    group.sample_size(20);
    // The brush grows and shrinks as a drag would, about a pixel per frame, back and forth.
    let mut frame = 0usize;
    group.bench_function("brush_frame", |b| {
        b.iter(|| {
            frame += 1;
            let t = 0.45 + 0.4 * triangle(frame, 40);
            let end = Point::new(r.x + r.w * t, r.y + r.h * t);
            s.brush(0, Target::Plot(0), start, end, Mode::Replace);
            black_box(s.charts[1].lit)
        })
    });
    let brush = s.brush_for(0, Target::Plot(0), start, Point::new(r.x + r.w * 0.6, r.y + r.h * 0.6)).expect("a brush");
    let mask = s.mask("table");
    for (chart, name) in [(0, "relight_splom"), (1, "relight_parallel")] {
        let tiles = s.charts[chart].tiles.as_mut().expect("tiles");
        group.bench_function(name, |b| {
            b.iter(|| tiles.redraw_dynamic(|item| dataink::explore::light::split(item, mask.as_deref())))
        });
    }
    let table = s.table("table").clone();
    group.bench_function("mask_only", |b| b.iter(|| black_box(brush.mask("table", &table).map(|m| m.len()))));
    println!(
        "lit after the last brush frame: splom {:?}, parallel {:?} (of {ROWS} rows)",
        s.charts[0].lit, s.charts[1].lit
    );
    group.sample_size(10);
    group.bench_function("draw_both", |b| b.iter(|| s.draw(&[0, 1])));

    // The whole window frame, headless: egui input, layout and painting, the brush and both
    // charts relit, and the changed tiles handed to egui as texture updates (no GPU).
    s.clear("table");
    let mut app = ExploreApp::new(s, dir.path().join("saved"));
    app.open_tab("table");
    let mut h = egui_kittest::HarnessBuilder::default()
        .with_size(egui::Vec2::new(1700.0, 900.0))
        .with_max_steps(10_000)
        .build_ui_state(|ui, app: &mut ExploreApp| app.ui(ui), app);
    h.run();
    let origin = h.state().chart_rect(0).expect("the splom is on screen").min;
    let at = |p: Point| egui::Pos2::new(origin.x + p.x as f32, origin.y + p.y as f32);
    h.event(egui::Event::PointerMoved(at(start)));
    h.event(egui::Event::PointerButton {
        pos: at(start),
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.step();
    let mut frame = 0usize;
    group.sample_size(30);
    group.bench_function("window_frame", |b| {
        b.iter(|| {
            frame += 1;
            // A drag moving about 1.5 pixels a frame, back and forth across the cell.
            let t = 0.45 + 0.4 * triangle(frame, 30);
            h.event(egui::Event::PointerMoved(at(Point::new(r.x + r.w * t, r.y + r.h * t))));
            h.step();
        })
    });
    group.finish();
    let s = &h.state().session;
    println!(
        "lit during the window drag: splom {:?}, parallel {:?} (of {ROWS} rows)",
        s.charts[0].lit, s.charts[1].lit
    );
}

/// A triangle wave over `period` frames: 0 up to 1 and back down to 0.
fn triangle(frame: usize, period: usize) -> f64 {
    let p = (frame % (2 * period)) as f64 / period as f64;
    if p <= 1.0 { p } else { 2.0 - p }
}

/// A session over the 256³ blobs: an isosurface at 0.5 and a volume rendering. The spec names
/// a one-voxel-thick raw file, replaced by the field before the charts are drawn.
fn volume_session(dir: &std::path::Path) -> Session {
    std::fs::write(dir.join("stub.raw"), [0u8; 32]).expect("raw");
    let spec = r#"
[data.blobs]
path = "stub.raw"
format = "raw"
dims = [2, 2, 2]
dtype = "f32"

[[chart]]
name = "surface"
kind = "isosurface"
data = "blobs"
size = [640, 560]
levels = [0.5]

[[chart]]
name = "rendering"
kind = "volume"
data = "blobs"
size = [640, 560]
opacity = [[0.2, 0], [0.5, 0.3], [1, 0.8]]
resolution = 512
"#;
    std::fs::write(dir.join("spec.toml"), spec).expect("spec");
    let mut loaded = dataink::pipeline::load(&dir.join("spec.toml"), PathPolicy::InsideSpecFolder).expect("spec loads");
    loaded.volumes.insert("blobs".into(), common::blobs(256));
    Session::new(loaded, 1.0)
}

fn bench_volume(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = volume_session(dir.path());
    assert!(s.charts.iter().all(|v| v.error.is_none()), "the charts draw");
    let mut group = c.benchmark_group("explore_volume");
    group.sample_size(10);
    let mut frame = 0usize;
    group.bench_function("level_frame_scan", |b| {
        b.iter(|| {
            frame += 1;
            // The spec's value changes, so the chart is drawn from a full scan each time.
            let level = if frame % 2 == 0 { 0.5 } else { 0.45 };
            s.loaded.spec.chart[0] = {
                let mut chart = s.loaded.spec.chart[0].clone();
                let mut value = serde_json::to_value(&chart).expect("json");
                value["levels"] = serde_json::json!([level]);
                chart = serde_json::from_value(value).expect("chart");
                chart
            };
            s.draw(&[0]);
            black_box(s.charts[0].generation)
        })
    });
    s.set_level(0, 0.45);
    group.bench_function("level_frame", |b| {
        b.iter(|| {
            frame += 1;
            s.set_level(0, if frame % 2 == 0 { 0.5 } else { 0.45 });
            black_box(s.charts[0].generation)
        })
    });
    let (a, b) = (Point::new(300.0, 280.0), Point::new(302.0, 280.0));
    group.bench_function("turn_surface", |bench| bench.iter(|| s.turn(0, a, b)));
    group.bench_function("turn_volume_preview", |bench| bench.iter(|| s.turn(1, a, b)));
    group.bench_function("volume_full", |bench| {
        bench.iter(|| {
            s.turn(1, a, b);
            s.end_turn(1)
        })
    });
    group.finish();
}

criterion_group!(benches, bench, bench_volume);
criterion_main!(benches);
