//! `faces`: Chernoff faces. Up to 15 numeric columns drive facial features (each column scaled
//! from its minimum to its maximum over the drawn rows); one face per row in a grid, labelled by
//! a column, with a key that says which column drives which feature in which direction.

use super::face::{FacePaint, FaceParams, Feature, face_items};
use crate::data::{Column, Table};
use crate::guide::layout::LayoutError;
use crate::guide::legend::{Legend, Symbol, truncate_to_width};
use crate::mark::derived::{Derived, DerivedColumn};
use crate::mark::encode::{self, ColorEncoding};
use crate::mark::frame;
use crate::mark::registry::{ChartContext, KindInfo, Technique};
use crate::mark::warning::Warning;
use crate::mark::{ChartOutput, MarkError, highlight, with_default_size};
use crate::scene::{Anchor, Baseline, Color, Item, Point, Role, Text};
use crate::selection::Highlight;
use crate::spec::{Chart, ColorChannel};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of `kind = "faces"`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct FacesOptions {
    /// Up to 15 numeric columns, assigned to features in the order face width, face height,
    /// face shape, eye size, eye spacing, eye slant, pupil position, brow slant, brow height,
    /// nose length, nose width, mouth curvature, mouth width, mouth openness, ear size
    /// (give this or `features`).
    #[serde(default)]
    #[schemars(example = crate::spec::types::example_columns())]
    pub columns: Option<Vec<String>>,
    /// Columns by feature, e.g. `{ mouth_curvature = "mpg", hair = "hp" }` (up to 15).
    #[serde(default)]
    pub features: Option<FaceFeatures>,
    /// Column whose values label the faces (default: the row number).
    #[serde(default)]
    pub label: Option<String>,
    /// Colour the faces by a column (categories get a legend).
    #[serde(default)]
    pub color: Option<ColorChannel>,
    /// Faces per row of the grid (default: from the canvas' aspect ratio).
    #[serde(default)]
    #[schemars(range(min = 1, max = 100))]
    pub per_row: Option<u32>,
    /// Draw the feature key saying which column drives which feature (default true). Without it
    /// the faces cannot be read; lint rule TQ005 reports that.
    #[serde(default)]
    pub key: Option<bool>,
}

/// Columns driving facial features; a feature without a column stays neutral.
#[derive(Clone, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq)]
pub struct FaceFeatures {
    /// Narrow to wide face.
    #[serde(default)]
    pub face_width: Option<String>,
    /// Short to tall face.
    #[serde(default)]
    pub face_height: Option<String>,
    /// Round to pointed chin.
    #[serde(default)]
    pub face_shape: Option<String>,
    /// Small to large eyes.
    #[serde(default)]
    pub eye_size: Option<String>,
    /// Close-set to wide-set eyes.
    #[serde(default)]
    pub eye_spacing: Option<String>,
    /// Eyes slanting down to up at the outer corners.
    #[serde(default)]
    pub eye_slant: Option<String>,
    /// Pupils looking left to right.
    #[serde(default)]
    pub pupil_position: Option<String>,
    /// Brows slanting down to up at the outer ends.
    #[serde(default)]
    pub brow_slant: Option<String>,
    /// Low to high brows.
    #[serde(default)]
    pub brow_height: Option<String>,
    /// Short to long nose.
    #[serde(default)]
    pub nose_length: Option<String>,
    /// Narrow to wide nose.
    #[serde(default)]
    pub nose_width: Option<String>,
    /// Frown to smile.
    #[serde(default)]
    pub mouth_curvature: Option<String>,
    /// Narrow to wide mouth.
    #[serde(default)]
    pub mouth_width: Option<String>,
    /// Closed to open mouth.
    #[serde(default)]
    pub mouth_openness: Option<String>,
    /// Small to large ears.
    #[serde(default)]
    pub ear_size: Option<String>,
    /// No hair to full hair.
    #[serde(default)]
    pub hair: Option<String>,
}

/// Canvas size when the spec gives none.
pub(super) const DEFAULT_SIZE: [f64; 2] = [900.0, 620.0];
/// Most columns one chart maps to features.
pub const MAX_COLUMNS: usize = 15;
/// Smallest face, in pixels, that still shows its features.
const MIN_FACE: f64 = 28.0;
/// Default skin colour when nothing encodes colour.
const SKIN: Color = Color::rgb(0xf3, 0xdc, 0xc2);
/// Outline colour.
const INK: Color = Color::rgb(0x33, 0x2b, 0x26);
/// Hair colour.
const HAIR: Color = Color::rgb(0x6b, 0x4e, 0x3a);
/// Title of the feature key (lint rule TQ005 looks for it).
pub const KEY_TITLE: &str = "Features";

/// Draw a grid of Chernoff faces.
pub fn draw(
    chart: &Chart,
    options: &FacesOptions,
    table: &Table,
    highlight: Option<&Highlight>,
) -> Result<ChartOutput, MarkError> {
    let chart = &with_default_size(chart);
    let (key, mapping) = feature_columns(options)?;
    let mut numeric: Vec<(&str, &Column)> = Vec::new();
    for (_, field) in &mapping {
        let col = encode::column(chart, key, field, table)?;
        encode::require_numeric(key, col, "a facial feature", "map a numeric column to the feature")?;
        numeric.push((field.as_str(), col));
    }
    let label_col = match &options.label {
        Some(field) => Some(encode::column(chart, "label", field, table)?),
        None => None,
    };
    let (rows, mut warnings) = encode::drawn_rows(chart, table, numeric.clone(), options.color.as_ref())?;

    // Each column scaled over the drawn rows; a constant column leaves its feature neutral.
    let mut params = vec![FaceParams::neutral(); rows.len()];
    let mut key_lines = Vec::new();
    for (&(feature, _), &(field, col)) in mapping.iter().zip(&numeric) {
        let values = encode::values_at(col, &rows);
        let (lo, hi) = encode::finite_extent(values.iter().copied()).unwrap_or((0.0, 0.0));
        if hi <= lo {
            warnings.push(Warning::from(format!("column `{field}` is constant, so {} stays neutral", feature.label())));
        }
        for (p, v) in params.iter_mut().zip(&values) {
            p.set(feature, if hi > lo { (v - lo) / (hi - lo) } else { 0.5 });
        }
        let (low, high) = feature.extremes();
        key_lines.push(format!("{}: {field} ({low} to {high})", feature.label()));
    }

    let (colors, color_legend) =
        encode::color_encoding(chart, options.color.as_ref(), None, table, &rows, Symbol::Circle)?;
    let mut legends: Vec<Legend> = color_legend.into_iter().collect();
    legends.extend(highlight.map(|h| highlight::legend(h, &rows, Symbol::Circle)));
    if options.key.unwrap_or(true) {
        legends.push(Legend::Notes { title: KEY_TITLE.into(), lines: key_lines });
    }
    let canvas = frame::PanelCanvas::new(chart, legends);
    let theme = canvas.theme.clone();
    let grid = FaceGrid::lay_out(&canvas, rows.len(), options.per_row).map_err(|e| match e {
        LayoutError::TooSmall { plot_width, .. } if plot_width > 0.0 => MarkError::at(
            &["size"],
            format!(
                "{} faces would be {plot_width:.0} px each, too small to read (at least {MIN_FACE} px)",
                rows.len()
            ),
            "make `size` larger, or draw fewer rows (faces suit tens of rows, not hundreds)",
        ),
        e => MarkError::layout(e),
    })?;

    let mut items = vec![canvas.background()];
    let label_size = theme.font_size * 0.9;
    let (mut centers_x, mut centers_y, mut labels) = (Vec::new(), Vec::new(), Vec::new());
    for (k, (&row, p)) in rows.iter().zip(&params).enumerate() {
        let (cx, cy) = grid.center(k);
        let selected = highlight.is_none_or(|h| h.contains(row));
        let paint = if selected {
            let skin = match &colors {
                ColorEncoding::Fixed(_) => SKIN,
                c => crate::guide::color::lighten(c.color_of(row), 0.55),
            };
            FacePaint { skin, ink: INK, hair: HAIR }
        } else {
            FacePaint {
                skin: Color::rgb(0xf2, 0xf2, 0xf2),
                ink: highlight::CONTEXT,
                hair: Color::rgb(0xe0, 0xe0, 0xe0),
            }
        };
        let center = Point::new(cx, cy);
        let parts = face_items(p, center, grid.face, paint).into_iter().map(|i| i.with_rows(vec![row])).collect();
        items.push(Item::group(Role::DataMark, parts, None).labelled(format!("face {row}")));
        let label = label_col.map_or_else(|| row.to_string(), |c| encode::cell_text(c, row));
        let label = truncate_to_width(&label, grid.cell_w - 4.0, label_size);
        items.push(Item::text(
            Role::Annotation,
            Text {
                at: Point::new(cx, cy + grid.face / 2.0 + 2.0),
                content: label.clone(),
                size: label_size,
                anchor: Anchor::Middle,
                baseline: Baseline::Top,
                angle: 0.0,
                color: if selected { theme.text } else { theme.muted_text.with_opacity(0.6) },
            },
        ));
        centers_x.push(cx);
        centers_y.push(cy);
        labels.push(label);
    }

    let mut derived = Derived::over(rows.clone());
    derived.push("row", DerivedColumn::RowIndex);
    derived.push("label", DerivedColumn::Text(labels));
    derived.push("x", DerivedColumn::Number(centers_x));
    derived.push("y", DerivedColumn::Number(centers_y));
    for &(feature, _) in &mapping {
        derived.push(feature.key(), DerivedColumn::Number(params.iter().map(|p| p.get(feature)).collect()));
    }
    if let Some(h) = highlight {
        derived.push("selected", DerivedColumn::Selected(h.selected.clone()));
    }
    Ok(ChartOutput {
        scene: canvas.scene(chart, items, None),
        derived,
        warnings,
        meshes: Vec::new(),
        geojson: None,
        volume: None,
        geometry: Default::default(),
    })
}

/// The column driving each mapped feature, in feature order.
type FeatureColumns = Vec<(Feature, String)>;

/// The spec key the mapping comes from (`columns` or `features`) and (feature, column) per
/// mapped feature: from `columns` in feature order, or from `features`.
fn feature_columns(options: &FacesOptions) -> Result<(&'static str, FeatureColumns), MarkError> {
    match (&options.columns, &options.features) {
        (Some(_), Some(_)) => Err(MarkError::at(
            &["features"],
            format!("give `columns` or `features`, not both"),
            "`columns` assigns features in order; `features` names them",
        )),
        (None, None) => Err(MarkError::at(
            &[],
            format!("faces need `columns` or `features`"),
            "e.g. `columns = [\"mpg\", \"hp\", \"weight\"]` or `features = { mouth_curvature = \"mpg\" }`",
        )),
        (Some(columns), None) => {
            if columns.len() > MAX_COLUMNS {
                return Err(MarkError::at(
                    &["columns"],
                    format!("{} columns given; faces show at most {MAX_COLUMNS}", columns.len()),
                    "drop the least important columns, or use parallel coordinates for wide tables",
                ));
            }
            if columns.is_empty() {
                return Err(MarkError::at(
                    &["columns"],
                    format!("`columns` is empty"),
                    "name at least one numeric column",
                ));
            }
            Ok(("columns", Feature::ALL.into_iter().zip(columns.iter().cloned()).collect()))
        }
        (None, Some(features)) => {
            let map = serde_json::to_value(features).unwrap_or_default();
            let mut out: Vec<(Feature, String)> = map
                .as_object()
                .into_iter()
                .flatten()
                .filter_map(|(k, v)| Some((Feature::from_key(k)?, v.as_str()?.to_string())))
                .collect();
            out.sort_by_key(|(f, _)| *f);
            if out.is_empty() {
                return Err(MarkError::at(
                    &["features"],
                    format!("`features` maps no column"),
                    "e.g. `features = { mouth_curvature = \"mpg\" }`",
                ));
            }
            if out.len() > MAX_COLUMNS {
                return Err(MarkError::at(
                    &["features"],
                    format!("{} features mapped; faces show at most {MAX_COLUMNS} columns", out.len()),
                    "leave one feature neutral",
                ));
            }
            Ok(("features", out))
        }
    }
}

/// The grid of faces in the canvas' room, left of the legends.
struct FaceGrid {
    top: f64,
    left: f64,
    per_row: usize,
    cell_w: f64,
    cell_h: f64,
    face: f64,
}

impl FaceGrid {
    /// The arrangement of `n` faces (`per_row` of them per row, or the one giving the largest
    /// faces) that fits the room.
    fn lay_out(canvas: &frame::PanelCanvas, n: usize, per_row: Option<u32>) -> Result<FaceGrid, LayoutError> {
        let theme = &canvas.theme;
        let m = theme.margin;
        let area_w = canvas.width - 2.0 * m - canvas.legend_room();
        let label_h = theme.font_size * 1.3;
        let cell = |cols: usize| {
            let rows = n.div_ceil(cols);
            let (cw, ch) = (area_w / cols as f64, canvas.room / rows as f64);
            (cw, ch, (cw * 0.88).min(ch - label_h - 4.0))
        };
        let per_row = match per_row {
            Some(p) => (p as usize).clamp(1, n),
            None => (1..=n).max_by(|&a, &b| cell(a).2.total_cmp(&cell(b).2)).unwrap_or(1),
        };
        let (cell_w, cell_h, face) = cell(per_row);
        if face < MIN_FACE {
            return Err(LayoutError::TooSmall { plot_width: face.max(0.0), plot_height: face.max(0.0) });
        }
        Ok(FaceGrid { top: canvas.top(), left: m, per_row, cell_w, cell_h, face })
    }

    /// Centre of face `k` (row-major).
    fn center(&self, k: usize) -> (f64, f64) {
        let (r, c) = (k / self.per_row, k % self.per_row);
        (self.left + self.cell_w * (c as f64 + 0.5), self.top + self.cell_h * r as f64 + self.face / 2.0 + 2.0)
    }
}

/// `kind = "faces"`.
pub static KIND: KindInfo = KindInfo::new("faces", &["columns", "features", "label", "color"])
    .sized(DEFAULT_SIZE)
    .drawing_selections()
    .faceted(crate::mark::registry::Faceting::Canvas);

impl Technique for FacesOptions {
    fn info(&self) -> &'static KindInfo {
        &KIND
    }

    fn draw(&self, cx: &ChartContext<'_>) -> Result<ChartOutput, MarkError> {
        draw(&cx.chart, self, cx.table, cx.highlight)
    }

    crate::mark::registry::color_key!();
}
