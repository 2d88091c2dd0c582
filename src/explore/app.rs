//! The explorer window (feature `explore`): a thin egui shell over [`Session`]. It lays the
//! charts out (one tab per data source, its charts side by side), turns pointer and keyboard
//! input into session actions in canvas coordinates, and paints the session's tiles with
//! [`crate::render::egui`].
//!
//! Keys: drag in a scatter plot or splom cell brushes a rectangle, drag along a
//! parallel-coordinates axis brushes a range; with shift the brush adds rows, with alt it
//! removes them; a click or Escape clears. Scroll zooms, right- or middle-drag pans, a
//! double-click resets the view. In a hyperbolic tree, drag moves the focus and a click brings
//! a node to the centre. A 3-D chart (isosurface, volume rendering) turns with a drag (a volume
//! rendering is drawn with fewer rays until the button is released), an isosurface's slider
//! moves its first surface's value, a one-plane slice's slider moves its plane along its axis,
//! and a double-click brings back the spec's view.

use std::path::PathBuf;

use eframe::egui::{self, Color32, Key, PointerButton, Pos2, Sense, Stroke, StrokeKind, Vec2};

use super::brush::Mode;
use super::session::{Session, Target};
use crate::render::egui::{TextureCache, shapes};
use crate::scene::Point;

/// Colour of brushed ranges that add rows.
const BRUSH: Color32 = Color32::from_rgb(0x33, 0x66, 0x99);
/// Colour of brushed ranges that remove rows.
const SUBTRACT: Color32 = Color32::from_rgb(0xb0, 0x3a, 0x2e);

/// A drag in progress.
#[derive(Clone, Copy, Debug)]
struct Drag {
    chart: usize,
    target: Option<Target>,
    start: Point,
    last: Point,
    mode: Mode,
    pan: bool,
}

/// The window's state around the session.
pub struct ExploreApp {
    /// The charts, selections and views.
    pub session: Session,
    /// Where Save writes.
    pub out_dir: PathBuf,
    /// The open tab (index into [`ExploreApp::tabs`]).
    pub tab: usize,
    tabs: Vec<(String, Vec<usize>)>,
    caches: Vec<TextureCache>,
    rects: Vec<Option<egui::Rect>>,
    drag: Option<Drag>,
    hover: Option<String>,
    message: Option<String>,
}

impl std::fmt::Debug for ExploreApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ExploreApp").field("tab", &self.tab).field("out_dir", &self.out_dir).finish_non_exhaustive()
    }
}

impl ExploreApp {
    /// A window over `session`, saving into `out_dir`.
    pub fn new(session: Session, out_dir: PathBuf) -> ExploreApp {
        let mut tabs: Vec<(String, Vec<usize>)> = Vec::new();
        for (i, v) in session.charts.iter().enumerate() {
            match tabs.iter_mut().find(|(d, _)| *d == v.data) {
                Some((_, charts)) => charts.push(i),
                None => tabs.push((v.data.clone(), vec![i])),
            }
        }
        let n = session.charts.len();
        ExploreApp {
            session,
            out_dir,
            tab: 0,
            tabs,
            caches: (0..n).map(|_| TextureCache::default()).collect(),
            rects: vec![None; n],
            drag: None,
            hover: None,
            message: None,
        }
    }

    /// The tabs: a data source and its charts.
    pub fn tabs(&self) -> &[(String, Vec<usize>)] {
        &self.tabs
    }

    /// Open the tab of data source `data`; returns whether there is one.
    pub fn open_tab(&mut self, data: &str) -> bool {
        match self.tabs.iter().position(|(d, _)| d == data) {
            Some(t) => {
                self.tab = t;
                true
            }
            None => false,
        }
    }

    /// Where chart `chart`'s canvas was painted in the last frame (screen points).
    pub fn chart_rect(&self, chart: usize) -> Option<egui::Rect> {
        self.rects.get(chart).copied().flatten()
    }

    /// The data source of the open tab.
    fn tab_data(&self) -> Option<&str> {
        self.tabs.get(self.tab).map(|(d, _)| d.as_str())
    }

    /// Draw the whole window into `ui`.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let ppp = f64::from(ui.ctx().pixels_per_point());
        if (ppp - self.session.scale).abs() > 1e-6 && ppp.is_finite() && ppp > 0.0 {
            self.session.scale = ppp;
            let all: Vec<usize> = (0..self.session.charts.len()).collect();
            self.session.draw(&all);
        }
        let dt = f64::from(ui.input(|i| i.stable_dt)).min(0.1);
        if self.session.advance(dt) {
            ui.ctx().request_repaint();
        }
        if ui.input(|i| i.key_pressed(Key::Escape))
            && let Some(data) = self.tab_data().map(str::to_string)
        {
            self.session.clear(&data);
        }
        egui::Panel::top("tabs").show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status(ui));
        egui::CentralPanel::default().show(ui, |ui| {
            // Charts wrap at the window's width; scroll down for more.
            let scroll = egui::ScrollArea::vertical().id_salt(("charts", self.tab)).auto_shrink([false, false]);
            scroll.show(ui, |ui| self.charts(ui));
        });
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            for t in 0..self.tabs.len() {
                let (data, charts) = &self.tabs[t];
                let label = format!("{data} ({})", charts.len());
                if ui.selectable_label(self.tab == t, label).clicked() {
                    self.tab = t;
                }
            }
            ui.separator();
            if ui
                .button("Save")
                .on_hover_text(format!("selection.toml, SVG and PNG into {}", self.out_dir.display()))
                .clicked()
            {
                self.save();
            }
            if ui.button("Clear selection").clicked()
                && let Some(data) = self.tab_data().map(str::to_string)
            {
                self.session.clear(&data);
            }
        });
    }

    /// Write the selection and the open tab's charts.
    pub fn save(&mut self) {
        let charts = self.tabs.get(self.tab).map(|(_, c)| c.clone()).unwrap_or_default();
        self.message = Some(match self.session.save(&self.out_dir, &charts) {
            Ok(files) => format!("saved {} files into {}", files.len(), self.out_dir.display()),
            Err(e) => format!("save failed: {e}"),
        });
    }

    fn status(&mut self, ui: &mut egui::Ui) {
        let data = self.tab_data().unwrap_or("").to_string();
        let line = match self.session.sets.get(&data) {
            Some(set) if set.is_active() => format!("{data}: {} of {} rows selected", set.count(), set.rows()),
            Some(set) => format!("{data}: no selection, all {} rows lit", set.rows()),
            None if self.session.loaded.volumes.contains_key(&data) => {
                format!("{data}: a volume; drag turns a 3-D chart, the sliders move a value or a plane")
            }
            None => format!("{data}: nothing to brush here"),
        };
        ui.horizontal(|ui| {
            ui.strong(line);
            if let Some(h) = &self.hover {
                ui.separator();
                ui.label(h);
            }
            if let Some(m) = &self.message {
                ui.separator();
                ui.label(m);
            }
        });
        ui.weak(
            "drag: brush · shift+drag: add · alt+drag: remove · Esc or click: clear · scroll: zoom · \
             right-drag: pan · double-click: reset · tree: drag moves the focus, click centres a node · \
             3-D: drag turns",
        );
    }

    fn charts(&mut self, ui: &mut egui::Ui) {
        let charts = self.tabs.get(self.tab).map(|(_, c)| c.clone()).unwrap_or_default();
        self.hover = None;
        // Rows of charts as wide as the window allows.
        let gap = 16.0;
        let room = ui.available_width();
        let mut rows: Vec<Vec<usize>> = Vec::new();
        let mut used = 0.0;
        for i in charts {
            let w = self.session.charts.get(i).map_or(0.0, |v| v.size[0] as f32) + gap;
            match rows.last_mut() {
                Some(row) if used + w <= room || row.is_empty() => row.push(i),
                _ => {
                    rows.push(vec![i]);
                    used = 0.0;
                }
            }
            used += w;
        }
        for row in rows {
            ui.horizontal_top(|ui| {
                ui.spacing_mut().item_spacing = Vec2::new(gap, 4.0);
                for i in row {
                    ui.vertical(|ui| self.chart(ui, i));
                }
            });
            ui.add_space(gap);
        }
    }

    fn chart(&mut self, ui: &mut egui::Ui, i: usize) {
        let Some(v) = self.session.charts.get(i) else { return };
        let header = if self.session.loaded.spec.chart.get(v.index).is_some_and(super::session::draws_selection) {
            format!("{} — {} of {} rows lit", v.name, v.lit.0, v.lit.1)
        } else {
            v.name.clone()
        };
        ui.label(header);
        if let Some((level, [lo, hi])) = self.session.level(i) {
            let mut value = level;
            let slider =
                egui::Slider::new(&mut value, lo..=hi).text("iso value").clamping(egui::SliderClamping::Always);
            if ui.add(slider).changed() {
                self.session.set_level(i, value);
            }
        }
        if let Some((at, [lo, hi], axis)) = self.session.plane(i) {
            let mut value = at;
            let text = format!("plane {}", ["x", "y", "z"][axis % 3]);
            let slider = egui::Slider::new(&mut value, lo..=hi).text(text).clamping(egui::SliderClamping::Always);
            if ui.add(slider).changed() {
                self.session.set_plane(i, value);
            }
        }
        let Some(v) = self.session.charts.get(i) else { return };
        if let Some(e) = &v.error {
            ui.colored_label(SUBTRACT, e);
            return;
        }
        let size = Vec2::new(v.size[0] as f32, v.size[1] as f32);
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        if let (Some(tiles), Some(cache)) = (&v.tiles, self.caches.get_mut(i)) {
            let painted = shapes(ui.ctx(), tiles, rect.min, cache);
            ui.painter_at(rect).extend(painted);
        }
        if let Some(r) = self.rects.get_mut(i) {
            *r = Some(rect);
        }
        let to_canvas = |p: Pos2| Point::new(f64::from(p.x - rect.min.x), f64::from(p.y - rect.min.y));
        self.input(ui, i, &response, to_canvas);
        // Brushed ranges.
        let painter = ui.painter_at(rect);
        for (mode, r) in self.session.brush_rects(i) {
            let color = if mode == Mode::Subtract { SUBTRACT } else { BRUSH };
            let screen = egui::Rect::from_min_size(
                Pos2::new(rect.min.x + r.x as f32, rect.min.y + r.y as f32),
                Vec2::new(r.w as f32, r.h as f32),
            );
            painter.rect_filled(screen, 0.0, color.gamma_multiply(0.08));
            painter.rect_stroke(screen, 0.0, Stroke::new(1.0, color), StrokeKind::Middle);
        }
    }

    /// Pointer input on chart `i`.
    fn input(&mut self, ui: &egui::Ui, i: usize, response: &egui::Response, to_canvas: impl Fn(Pos2) -> Point) {
        let pointer = response.hover_pos().or(response.interact_pointer_pos());
        if response.double_clicked() {
            self.session.reset_view(i);
            return;
        }
        if let Some(p) = response.hover_pos() {
            let scroll = ui.input(|inp| inp.smooth_scroll_delta.y);
            // Over a plot or axis the wheel zooms; elsewhere it scrolls the page.
            if scroll != 0.0 && self.session.zoomable_at(i, to_canvas(p)) {
                ui.ctx().input_mut(|inp| inp.smooth_scroll_delta = Vec2::ZERO);
                let factor = (-f64::from(scroll) / 240.0).exp();
                self.session.zoom(i, to_canvas(p), factor);
            }
            // Not while dragging: the brush is what matters then.
            if !response.dragged() {
                self.hover = self.session.hover(i, to_canvas(p));
            }
        }
        let mods = ui.input(|inp| inp.modifiers);
        let pan = response.dragged_by(PointerButton::Secondary) || response.dragged_by(PointerButton::Middle);
        if response.drag_started() {
            let origin = ui.input(|inp| inp.pointer.press_origin()).or(pointer);
            if let Some(o) = origin {
                let start = to_canvas(o);
                let mode = if mods.shift {
                    Mode::Add
                } else if mods.alt {
                    Mode::Subtract
                } else {
                    Mode::Replace
                };
                let target = self.session.target_at(i, start);
                self.drag = Some(Drag { chart: i, target, start, last: start, mode, pan });
            }
        }
        if let (Some(mut d), Some(p)) = (self.drag.filter(|d| d.chart == i), pointer)
            && response.dragged()
        {
            let now = to_canvas(p);
            match d.target {
                Some(Target::Scene) => self.session.turn(i, d.last, now),
                Some(Target::Disk) if !d.pan => self.session.hyper_drag(i, d.last, now),
                Some(_) if d.pan => self.session.pan(i, d.last, now),
                Some(t) => self.session.brush(i, t, d.start, now, d.mode),
                None => {}
            }
            d.last = now;
            self.drag = Some(d);
        }
        if response.drag_stopped()
            && let Some(d) = self.drag.take()
        {
            match d.target {
                Some(Target::Scene) => self.session.end_turn(i),
                Some(Target::Plot(_) | Target::Axis(_)) if !d.pan => self.session.end_brush(i),
                _ => {}
            }
        }
        if response.clicked()
            && let Some(p) = pointer
        {
            let at = to_canvas(p);
            match self.session.target_at(i, at) {
                Some(Target::Disk) => {
                    self.session.hyper_focus(i, at, None);
                    ui.ctx().request_repaint();
                }
                Some(Target::Scene) => {}
                Some(_) if !mods.shift && !mods.alt => {
                    if let Some(data) = self.session.charts.get(i).map(|v| v.data.clone()) {
                        self.session.clear(&data);
                    }
                }
                _ => {}
            }
        }
    }
}

impl eframe::App for ExploreApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        ExploreApp::ui(self, ui);
    }
}

/// Open the window over `session` (blocks until it is closed).
pub fn run(session: Session, out_dir: PathBuf, title: &str) -> Result<(), String> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1560.0, 980.0]).with_title(title),
        ..Default::default()
    };
    let app = ExploreApp::new(session, out_dir);
    eframe::run_native("dataink explore", options, Box::new(move |_cc| Ok(Box::new(app)))).map_err(|e| e.to_string())
}
