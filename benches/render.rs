//! Function benchmarks (criterion): `cargo bench --bench render`.
//!
//! - `scatter_1m/*`: one million points to a 1000×1000 canvas — mapping to a scene, drawing the
//!   pixmap, and drawing plus PNG encoding.
//! - `line_small/*`: a small line chart from spec text to SVG and PNG bytes, in process.
//! - `lines/*`: 20,000 polylines × 8 vertices (parallel coordinates) on an 800×440 canvas — one
//!   line batch drawn to a pixmap and to PNG bytes, against the same polylines as 20,000 stroked
//!   path items through tiny-skia.

mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use dataink::data::{Column, ColumnValues, Table};
use dataink::mark;
use dataink::render;
use dataink::scene::{Color, Item, LineBatch, PathCmd, PerPoint, Point, Role, Scene, Shape, Style};
use dataink::spec::{Channel, Chart, ChartKind, ScatterOptions, SourceFile};

/// One million points in three Gaussian-ish clusters from a fixed-seed generator.
fn points_table(n: usize) -> Table {
    let mut uniform = common::uniform(0x2545_f491_4f6c_dd1d);
    let mut x = Vec::with_capacity(n);
    let mut y = Vec::with_capacity(n);
    let centres = [(-2.0, -1.0, 0.9), (1.5, 2.0, 0.6), (3.0, -2.5, 1.2)];
    for i in 0..n {
        let (cx, cy, s) = centres[i % 3];
        let r = s * (-2.0 * (1.0 - uniform()).ln()).sqrt();
        let a = std::f64::consts::TAU * uniform();
        x.push(cx + r * a.cos());
        y.push(cy + r * a.sin());
    }
    Table {
        columns: vec![
            Column { name: "x".into(), values: ColumnValues::Number(x) },
            Column { name: "y".into(), values: ColumnValues::Number(y) },
        ],
        rows: n,
    }
}

fn scatter_chart() -> Chart {
    Chart {
        name: "scatter-1m".into(),
        data: "points".into(),
        title: Some("One million points".into()),
        caption: None,
        size: Some([1000.0, 1000.0]),
        font_size: None,
        aspect: None,
        highlight: None,
        lint: None,
        tooltip: None,
        annotate: Vec::new(),
        facet: None,
        panel: None,
        kind: ChartKind::Scatter(ScatterOptions {
            x: Channel::Field("x".into()),
            y: Channel::Field("y".into()),
            color: None,
            point_size: None,
            radius: None,
            mark_color: None,
            opacity: None,
            trend: None,
        }),
    }
}

fn scatter_1m(c: &mut Criterion) {
    let table = points_table(1_000_000);
    let chart = scatter_chart();
    let scene = mark::draw(&chart, 0, &table, None).expect("scatter draws").scene;
    let mut group = c.benchmark_group("scatter_1m");
    group.sample_size(20);
    group.bench_function("map_to_scene", |b| b.iter(|| mark::draw(black_box(&chart), 0, black_box(&table), None)));
    group.bench_function("png_render", |b| b.iter(|| render::png::to_pixmap(black_box(&scene), 1.0)));
    group.bench_function("png_render_and_encode", |b| b.iter(|| render::png::to_png(black_box(&scene), 1.0)));
    group.finish();
}

fn line_small(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/line_small.toml");
    let text = std::fs::read_to_string(&path).expect("bench spec");
    let mut group = c.benchmark_group("line_small");
    group.bench_function("spec_to_svg_and_png", |b| {
        b.iter(|| {
            let source = SourceFile::new(path.clone(), text.clone());
            let parsed = dataink::spec::parse_spec(&source).expect("valid spec");
            let table = dataink::data::load_source(
                &parsed.spec.data["series"],
                std::path::Path::new("."),
                dataink::data::PathPolicy::InsideSpecFolder,
                None,
            )
            .expect("inline data");
            let out = mark::draw(&parsed.spec.chart[0], 0, &table, None).expect("line draws");
            let svg = render::svg::to_svg(&out.scene);
            let png = render::png::to_png(&out.scene, 1.0).expect("png");
            black_box((svg, png))
        })
    });
    group.finish();
}

/// Parallel-coordinates-like polylines: `rows` rows across `axes` evenly spaced vertical axes
/// of an 800×440 canvas, each vertex anywhere along its axis.
fn polylines(rows: usize, axes: usize) -> Vec<Point> {
    let mut uniform = common::uniform(0x9e37_79b9_7f4a_7c15);
    let step = 720.0 / (axes - 1) as f64;
    (0..rows * axes).map(|k| Point::new(40.0 + (k % axes) as f64 * step, 20.0 + 400.0 * uniform())).collect()
}

fn lines(c: &mut Criterion) {
    let (rows, axes) = (20_000, 8);
    let points = polylines(rows, axes);
    let color = Color::rgb(30, 90, 200).with_opacity(0.2);
    let scene = |items| Scene { width: 800.0, height: 440.0, background: Color::WHITE, title: None, items };
    let batch = LineBatch { points: points.clone(), stride: axes, color: PerPoint::Uniform(color), width: 1.0 };
    let batch_scene = scene(vec![Item::new(Role::DataMark, Shape::Lines(batch), Style::default())]);
    let path_items = points
        .chunks_exact(axes)
        .map(|line| {
            let cmds = line
                .iter()
                .enumerate()
                .map(|(k, p)| if k == 0 { PathCmd::MoveTo(*p) } else { PathCmd::LineTo(*p) })
                .collect();
            Item::new(Role::DataMark, Shape::Path(cmds), Style::stroke(color, 1.0))
        })
        .collect();
    let paths_scene = scene(path_items);
    let mut group = c.benchmark_group("lines");
    group.sample_size(10);
    group.bench_function("batch_png_render", |b| b.iter(|| render::png::to_pixmap(black_box(&batch_scene), 1.0)));
    group.bench_function("batch_png_render_and_encode", |b| {
        b.iter(|| render::png::to_png(black_box(&batch_scene), 1.0))
    });
    group.bench_function("paths_png_render", |b| b.iter(|| render::png::to_pixmap(black_box(&paths_scene), 1.0)));
    group.finish();
}

criterion_group!(benches, scatter_1m, line_small, lines);
criterion_main!(benches);
