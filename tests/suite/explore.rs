//! The explorer window driven headless with egui_kittest (no display, no GPU): pointer drags,
//! clicks and keys go through egui as a user's would, and the tests read the window's labels and
//! the session's state.

use eframe::egui::{self, Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, HarnessBuilder};

use dataink::explore::app::ExploreApp;
use dataink::explore::brush::Mode;
use dataink::explore::{Session, Target};

use crate::common::Fixture;

/// 120 rows of three loosely related columns and a class.
fn table_csv() -> String {
    let mut out = String::from("a,b,c,k\n");
    for i in 0..120 {
        let a = (i * 37 % 120) as f64 / 10.0;
        let b = (i * 53 % 120) as f64 / 4.0 + a;
        let c = (i * 11 % 120) as f64 - a;
        out.push_str(&format!("{a},{b},{c},{}\n", if i % 3 == 0 { "x" } else { "y" }));
    }
    out
}

const LINKED: &str = r#"
[data.t]
path = "t.csv"

[[chart]]
name = "m"
kind = "splom"
data = "t"
size = [520, 500]
columns = ["a", "b", "c"]
color = "k"

[[chart]]
name = "p"
kind = "parallel"
data = "t"
size = [560, 360]
columns = ["a", "b", "c"]
"#;

/// A harness over the app, after the first frames.
fn harness(app: ExploreApp) -> Harness<'static, ExploreApp> {
    let mut h = HarnessBuilder::default()
        .with_size(egui::Vec2::new(1400.0, 1000.0))
        .with_max_steps(400)
        .with_step_dt(1.0 / 30.0)
        .build_ui_state(|ui, app: &mut ExploreApp| app.ui(ui), app);
    h.run();
    h
}

/// Press at `from`, move in steps to `to`, release there (with `modifiers` held).
fn drag(h: &mut Harness<'static, ExploreApp>, from: Pos2, to: Pos2, modifiers: Modifiers) {
    h.event(Event::ModifiersChanged(modifiers));
    h.event(Event::PointerMoved(from));
    h.event(Event::PointerButton { pos: from, button: PointerButton::Primary, pressed: true, modifiers });
    for k in 1..=8 {
        let t = k as f32 / 8.0;
        h.event(Event::PointerMoved(from + (to - from) * t));
    }
    h.event(Event::PointerButton { pos: to, button: PointerButton::Primary, pressed: false, modifiers });
    h.event(Event::ModifiersChanged(Modifiers::NONE));
    h.step();
    h.run();
}

/// Click at `at`.
fn click(h: &mut Harness<'static, ExploreApp>, at: Pos2) {
    h.event(Event::PointerMoved(at));
    h.event(Event::PointerButton {
        pos: at,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    h.event(Event::PointerButton {
        pos: at,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    h.step();
    h.run();
}

/// Screen position of canvas point `(x, y)` of chart `chart`.
fn screen(h: &Harness<'static, ExploreApp>, chart: usize, x: f64, y: f64) -> Pos2 {
    let r = h.state().chart_rect(chart).expect("the chart is on screen");
    Pos2::new(r.min.x + x as f32, r.min.y + y as f32)
}

#[test]
fn a_drag_in_a_splom_cell_selects_the_rows_in_its_ranges_and_the_parallel_view_agrees() {
    let fx = Fixture::new(LINKED, &[("t.csv", table_csv().as_bytes())]);
    let session = Session::new(fx.load().expect("the spec loads"), 1.0);
    let mut h = harness(ExploreApp::new(session, fx.dir.path().join("saved")));
    h.get_by_label_contains("p — 120 of 120 rows lit");

    // Cell (row b, column a): drag over its middle.
    let plot = h.state().session.charts[0]
        .geometry
        .plots
        .iter()
        .find(|p| p.x.as_ref().is_some_and(|x| x.field == "a") && p.y.as_ref().is_some_and(|y| y.field == "b"))
        .expect("a cell plotting b against a")
        .clone();
    let (x_scale, y_scale) = (&plot.x.as_ref().unwrap().scale, &plot.y.as_ref().unwrap().scale);
    let r = plot.rect;
    let (a, b) = ((r.x + r.w * 0.25, r.y + r.h * 0.2), (r.x + r.w * 0.7, r.y + r.h * 0.75));
    let (from, to) = (screen(&h, 0, a.0, a.1), screen(&h, 0, b.0, b.1));
    drag(&mut h, from, to, Modifiers::NONE);

    let session = &h.state().session;
    let set = &session.sets["t"];
    let brushes = set.brushes();
    assert_eq!(brushes.len(), 1);
    let (mode, brush) = brushes[0];
    assert_eq!(mode, Mode::Replace);
    // The ranges are the pixel rectangle read through the cell's scales (to within a pixel).
    let (ra, rb) = (brush.ranges["a"], brush.ranges["b"]);
    let px_a = (x_scale.invert(1.0).unwrap() - x_scale.invert(0.0).unwrap()).abs();
    let px_b = (y_scale.invert(1.0).unwrap() - y_scale.invert(0.0).unwrap()).abs();
    let want_a = [x_scale.invert(a.0).unwrap(), x_scale.invert(b.0).unwrap()];
    let want_b = [y_scale.invert(b.1).unwrap(), y_scale.invert(a.1).unwrap()];
    for (got, want, px) in [(ra, want_a, px_a), (rb, want_b, px_b)] {
        assert!((got[0] - want[0]).abs() <= px && (got[1] - want[1]).abs() <= px, "{got:?} vs {want:?}");
    }
    // Exactly the rows inside both ranges are selected.
    let table = session.table("t");
    let col = |name: &str| table.column(name).and_then(|c| c.numbers()).expect("numbers").to_vec();
    let (va, vb) = (col("a"), col("b"));
    let expected: Vec<bool> =
        (0..120).map(|i| va[i] >= ra[0] && va[i] <= ra[1] && vb[i] >= rb[0] && vb[i] <= rb[1]).collect();
    let count = expected.iter().filter(|&&e| e).count();
    assert!(count > 5 && count < 100, "a real brush: {count}");
    assert_eq!(set.mask(), Some(expected));
    // The linked parallel-coordinates view and the splom show the same count, as does the status line.
    h.get_by_label_contains(&format!("p — {count} of 120 rows lit"));
    h.get_by_label_contains(&format!("m — {count} of 120 rows lit"));
    h.get_by_label_contains(&format!("t: {count} of 120 rows selected"));
    assert_eq!(h.state().session.charts[1].lit, (count, 120));

    // Alt-drag along the parallel axis of `a` removes rows; the count drops in both views.
    let axis = h.state().session.charts[1].geometry.axes[0].clone();
    let (top, bottom) = (axis.top, axis.bottom);
    let (from, to) = (screen(&h, 1, axis.x, top - 4.0), screen(&h, 1, axis.x, (top + bottom) / 2.0));
    drag(&mut h, from, to, Modifiers::ALT);
    let fewer = h.state().session.sets["t"].count();
    assert!(fewer < count, "{fewer} < {count}");
    h.get_by_label_contains(&format!("m — {fewer} of 120 rows lit"));

    // Save writes a selection that selects the same rows, and the charts.
    h.state_mut().save();
    let saved = std::fs::read_to_string(fx.dir.path().join("saved/selection.toml")).expect("selection.toml");
    assert!(saved.contains("[selection.t-brush-1]") && saved.contains("t-brush-1 - t-brush-2"), "{saved}");
    assert!(fx.dir.path().join("saved/m.png").exists() && fx.dir.path().join("saved/p.svg").exists());

    // Escape clears: every row lit again.
    h.key_press(Key::Escape);
    h.run();
    assert_eq!(h.state().session.sets["t"].mask(), None);
    h.get_by_label_contains("p — 120 of 120 rows lit");
    h.get_by_label_contains("t: no selection");
}

#[test]
fn a_saved_single_brush_renders_the_same_rows_from_the_spec() {
    let fx = Fixture::new(LINKED, &[("t.csv", table_csv().as_bytes())]);
    let mut session = Session::new(fx.load().expect("the spec loads"), 1.0);
    let axis = session.charts[1].geometry.axes[1].clone();
    let (y0, y1) = (axis.top + 30.0, axis.top + 150.0);
    session.brush(
        1,
        Target::Axis(1),
        dataink::scene::Point::new(axis.x, y0),
        dataink::scene::Point::new(axis.x, y1),
        Mode::Replace,
    );
    session.end_brush(1);
    let lit = session.mask("t").expect("a selection");
    let out = fx.dir.path().join("saved");
    session.save(&out, &[0, 1]).expect("saved");
    let snippet = std::fs::read_to_string(out.join("selection.toml")).expect("snippet");
    // The snippet, pasted into the spec with a highlight, selects the same rows when rendered.
    let spec = format!("{LINKED}highlight = \"t-brush\"\n\n{snippet}");
    let fx2 = Fixture::new(&spec, &[("t.csv", table_csv().as_bytes())]);
    let loaded = fx2.load().unwrap_or_else(|e| panic!("{e}\n{spec}"));
    assert_eq!(loaded.highlights["t-brush"].selected, lit);
}

#[test]
fn clicking_a_hyperbolic_tree_node_brings_it_to_the_centre() {
    let mut tree = String::from("id,parent,name\nroot,,root\n");
    for i in 0..6 {
        tree.push_str(&format!("n{i},root,node {i}\n"));
        for j in 0..4 {
            tree.push_str(&format!("n{i}-{j},n{i},leaf {i}.{j}\n"));
        }
    }
    let spec = "[data.tree]\npath = \"tree.csv\"\n\n[[chart]]\nname = \"h\"\nkind = \"hypertree\"\ndata = \"tree\"\nsize = [600, 560]\ntree = { id = \"id\", parent = \"parent\" }\nlabel = \"name\"\n";
    let fx = Fixture::new(spec, &[("tree.csv", tree.as_bytes())]);
    let session = Session::new(fx.load().expect("the spec loads"), 1.0);
    let mut h = harness(ExploreApp::new(session, fx.dir.path().join("saved")));
    let disk = h.state().session.charts[0].geometry.disk.clone().expect("a disk");
    let target = disk.nodes.iter().position(|n| n.label == "node 2").expect("node 2");
    let at = disk.to_canvas(disk.nodes[target].position);
    assert!(disk.nodes[target].position[0].hypot(disk.nodes[target].position[1]) > 0.2, "off centre at first");
    let at = screen(&h, 0, at.x, at.y);
    click(&mut h, at);
    let moved = h.state().session.charts[0].geometry.disk.clone().expect("a disk");
    let z = moved.nodes[target].position;
    assert!(z[0].hypot(z[1]) < 1e-6, "node 2 is at the centre: {z:?}");
    assert!(!h.state().session.charts[0].focus.is_animating());
    // Double-click puts the spec's focus (the root) back in the centre.
    let c = moved.center;
    h.event(Event::PointerMoved(screen(&h, 0, c.x + 40.0, c.y)));
    for _ in 0..2 {
        h.event(Event::PointerButton {
            pos: screen(&h, 0, c.x + 40.0, c.y),
            button: PointerButton::Primary,
            pressed: true,
            modifiers: Modifiers::NONE,
        });
        h.event(Event::PointerButton {
            pos: screen(&h, 0, c.x + 40.0, c.y),
            button: PointerButton::Primary,
            pressed: false,
            modifiers: Modifiers::NONE,
        });
    }
    h.step();
    h.run();
    let back = h.state().session.charts[0].geometry.disk.clone().expect("a disk");
    let root = back.nodes.iter().position(|n| n.label == "root").expect("root");
    assert!(back.nodes[root].position[0].hypot(back.nodes[root].position[1]) < 1e-9);
}

/// The distance from the centre of a 24³ lattice of unit voxels: its isosurface at `r` is a
/// sphere of radius `r` (area 4πr²).
fn ball_npy() -> Vec<u8> {
    let n = 24;
    let c = (n as f64 - 1.0) / 2.0;
    let mut data = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let d = ((i as f64 - c).powi(2) + (j as f64 - c).powi(2) + (k as f64 - c).powi(2)).sqrt();
                data.extend_from_slice(&d.to_le_bytes());
            }
        }
    }
    crate::common::npy("<f8", "(24, 24, 24)", &data)
}

const TURNING: &str = r#"
[data.ball]
path = "ball.npy"

[[chart]]
name = "surface"
kind = "isosurface"
data = "ball"
size = [420, 380]
levels = [6]

[[chart]]
name = "rendering"
kind = "volume"
data = "ball"
size = [420, 380]
opacity = [[0, 0.4], [8, 0.1], [9, 0]]

[[chart]]
name = "plane"
kind = "slice"
data = "ball"
axis = "y"
"#;

/// [`TURNING`] with the isosurface at 9.
fn at_nine_spec() -> String {
    TURNING.replace("levels = [6]", "levels = [9]")
}

/// The surface's area as drawn (the chart's derived table).
fn area(session: &Session) -> f64 {
    crate::common::numbers(session.charts[0].output.as_ref().expect("drawn"), "area")[0]
}

#[test]
fn a_3d_chart_turns_and_its_iso_value_moves() {
    let fx = Fixture::new(TURNING, &[("ball.npy", &ball_npy())]);
    let mut s = Session::new(fx.load().expect("the spec loads"), 1.0);
    assert!(s.charts.iter().all(|v| v.error.is_none()), "{:?}", s.charts.iter().map(|v| &v.error).collect::<Vec<_>>());
    let middle = dataink::scene::Point::new(210.0, 190.0);
    assert_eq!(s.target_at(0, middle), Some(Target::Scene));
    assert_eq!(s.target_at(1, middle), Some(Target::Scene));

    // The slider's range is the volume's, the surface a sphere of radius 6, then 9.
    let (level, [lo, hi]) = s.level(0).expect("an isosurface has a level");
    assert_eq!(level, 6.0);
    assert!(lo.abs() < 1.0 && (hi - 11.5 * 3f64.sqrt()).abs() < 1e-9, "[{lo}, {hi}]");
    assert!(s.level(1).is_none(), "a volume rendering has no iso value");
    let sphere = |r: f64| 4.0 * std::f64::consts::PI * r * r;
    assert!((area(&s) / sphere(6.0) - 1.0).abs() < 0.02, "area {} at 6", area(&s));
    s.set_level(0, 9.0);
    assert_eq!(s.level(0).map(|l| l.0), Some(9.0));
    assert!((area(&s) / sphere(9.0) - 1.0).abs() < 0.02, "area {} at 9", area(&s));
    // Found through the span-space index the move built: the very surface the spec draws at 9.
    let at_nine = Fixture::new(&at_nine_spec(), &[("ball.npy", &ball_npy())]);
    let spec_drawn = Session::new(at_nine.load().expect("the spec loads"), 1.0);
    assert_eq!(area(&s).to_bits(), area(&spec_drawn).to_bits());

    // A turn of the isosurface draws the surface kept from the last draw (the one at 9; the one
    // at 6 is kept too), and the picture is the chart drawn at 9 with that camera.
    assert_eq!(s.charts[0].surfaces.len(), 2, "the surfaces at 6 and 9 are kept");
    s.turn(0, middle, dataink::scene::Point::new(250.0, 170.0));
    s.end_turn(0);
    assert_eq!(s.charts[0].surfaces.len(), 2, "a turn extracts no surface");
    let turned = at_nine_spec().replace("levels = [9]\n", "levels = [9]\nazimuth = -80\nelevation = 15\n");
    let direct = Fixture::new(&turned, &[("ball.npy", &ball_npy())]);
    let fresh = Session::new(direct.load().expect("the turned spec loads"), 1.0);
    let picture = |s: &Session| s.charts[0].tiles.as_ref().expect("tiles").composite().2;
    assert!(picture(&s) == picture(&fresh), "the turned surface is the chart drawn with that camera");

    // A drag turns the camera (half a degree per unit) and draws the rendering with fewer rays
    // until it ends; the full drawing then equals the chart drawn with that camera.
    let (_, _, before) = s.charts[1].tiles.as_ref().expect("tiles").composite();
    s.turn(1, middle, dataink::scene::Point::new(250.0, 170.0));
    let spec = s.loaded.spec.chart[1].clone();
    assert_eq!(s.charts[1].orbit.camera(&spec), [-80.0, 15.0]);
    assert!(s.charts[1].orbit.preview);
    let (_, _, preview) = s.charts[1].tiles.as_ref().expect("tiles").composite();
    s.end_turn(1);
    assert!(!s.charts[1].orbit.preview);
    let (_, _, after) = s.charts[1].tiles.as_ref().expect("tiles").composite();
    assert!(after != before, "the turned rendering differs");
    assert!(preview != after, "the preview is coarser than the full rendering");
    let turned = TURNING.replace("name = \"rendering\"\n", "name = \"rendering\"\nazimuth = -80\nelevation = 15\n");
    let direct = Fixture::new(&turned, &[("ball.npy", &ball_npy())]);
    let fresh = Session::new(direct.load().expect("the turned spec loads"), 1.0);
    let (_, _, want) = fresh.charts[1].tiles.as_ref().expect("tiles").composite();
    assert!(after == want, "the turned view is the chart drawn with that camera");

    // A double-click's reset brings back the spec's view and value.
    s.reset_view(0);
    assert_eq!(s.level(0).map(|l| l.0), Some(6.0));

    // The slice's plane slides along y over the volume (0 to 23), from the voxel plane
    // nearest the middle; at y = 5 the nearest value is the distance from the centre's row.
    assert!(s.level(2).is_none() && s.plane(0).is_none());
    assert_eq!(s.plane(2), Some((12.0, [0.0, 23.0], 1)));
    s.set_plane(2, 5.0);
    assert_eq!(s.plane(2).map(|p| p.0), Some(5.0));
    let out = s.charts[2].output.as_ref().expect("drawn");
    assert_eq!(crate::common::numbers(out, "point_y"), vec![5.0]);
    let nearest = (6.5f64 * 6.5 + 2.0 * 0.25).sqrt();
    assert!((crate::common::numbers(out, "min")[0] - nearest).abs() < 1e-9);
}

#[test]
fn in_the_window_a_drag_turns_an_isosurface() {
    let fx = Fixture::new(TURNING, &[("ball.npy", &ball_npy())]);
    let session = Session::new(fx.load().expect("the spec loads"), 1.0);
    let mut h = harness(ExploreApp::new(session, fx.dir.path().join("saved")));
    assert!(h.query_all_by_label_contains("iso value").next().is_some(), "the iso value slider is shown");
    h.get_by_label_contains("ball: a volume; drag turns a 3-D chart");
    let (from, to) = (screen(&h, 0, 200.0, 190.0), screen(&h, 0, 260.0, 190.0));
    drag(&mut h, from, to, Modifiers::NONE);
    let v = &h.state().session.charts[0];
    let [azimuth, elevation] = v.orbit.camera(&h.state().session.loaded.spec.chart[0]);
    assert!((azimuth + 90.0).abs() < 3.0, "dragged 60 units right: azimuth {azimuth}, not −90");
    assert_eq!(elevation, 25.0);
    assert!(!v.orbit.preview, "released: drawn in full");
}
