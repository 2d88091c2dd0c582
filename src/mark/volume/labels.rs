//! Label volumes (segmentations) in `kind = "volume"`: each listed whole-number voxel value gets
//! a name, a colour and an opacity; other values are transparent. The legend is one swatch per
//! label; the derived table lists the labels as drawn.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::data::volume::Volume;
use crate::enrich::volume::raycast::TransferFunction;
use crate::guide::color;
use crate::guide::legend::{Legend, Symbol};
use crate::mark::MarkError;
use crate::mark::derived::{Derived, DerivedColumn};
use crate::scene::Color;

/// One label of a label volume: `{ value, name, color, opacity }`.
#[derive(Clone, Debug, Deserialize, Serialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct VolumeLabel {
    /// The whole-number voxel value.
    pub value: i64,
    /// Name in the legend (default: the value).
    #[serde(default)]
    pub name: Option<String>,
    /// CSS colour name or `#rrggbb` (default: the next colour of `okabe-ito`).
    #[serde(default)]
    pub color: Option<String>,
    /// Opacity per voxel length of ray, 0 to 1 (default 1).
    #[serde(default)]
    pub opacity: Option<f64>,
}

/// Labels resolved: name, colour and opacity of each, in the spec's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Labels {
    entries: Vec<(i64, String, Color, f64)>,
}

/// Voxels checked for whole numbers before a label volume is drawn (evenly strided).
const CHECKED_VOXELS: usize = 1_000_000;

impl Labels {
    /// The labels of `given`, or why they cannot be drawn on `volume`: none given, one given
    /// twice, a bad colour or opacity, or a volume whose values are not whole numbers.
    pub fn resolve(given: &[VolumeLabel], volume: &Volume) -> Result<Labels, MarkError> {
        if given.is_empty() {
            return Err(MarkError::at(&["labels"], "no labels", "give labels = [{ value = 1, name = \"...\" }, ...]"));
        }
        let palette = color::categorical(color::DEFAULT_CATEGORICAL).unwrap_or_default();
        let mut entries = Vec::with_capacity(given.len());
        for (k, label) in given.iter().enumerate() {
            if given[..k].iter().any(|l| l.value == label.value) {
                return Err(MarkError::at(
                    &["labels"],
                    format!("label {} is listed twice", label.value),
                    "list each label value once",
                ));
            }
            let colour = match &label.color {
                Some(s) => color::parse_color(s).ok_or_else(|| {
                    MarkError::at(&["labels"], format!("`{s}` is not a colour"), "use a CSS colour name or #rrggbb")
                })?,
                None => palette.get(k % palette.len().max(1)).copied().unwrap_or(Color::BLACK),
            };
            let opacity = label.opacity.unwrap_or(1.0);
            if !(0.0..=1.0).contains(&opacity) {
                return Err(MarkError::at(
                    &["labels"],
                    format!("label {} has opacity {opacity}", label.value),
                    "give an opacity from 0 to 1",
                ));
            }
            let name = label.name.clone().unwrap_or_else(|| label.value.to_string());
            entries.push((label.value, name, colour, opacity));
        }
        let stride = (volume.len() / CHECKED_VOXELS).max(1);
        if let Some(v) = volume.values().step_by(stride).find(|v| v.is_finite() && v.fract() != 0.0) {
            return Err(MarkError::at(
                &["labels"],
                format!("the volume holds {v}, not a whole number: labels need a segmentation"),
                "draw a label volume (whole-number voxels), or leave out `labels` for a transfer function",
            ));
        }
        Ok(Labels { entries })
    }

    /// The transfer function: each label its colour and opacity, other values transparent.
    pub fn transfer_function(&self) -> Result<TransferFunction, MarkError> {
        let rows: Vec<(i64, [f64; 3], f64)> =
            self.entries.iter().map(|(v, _, c, a)| (*v, [c.r, c.g, c.b].map(|x| f64::from(x) / 255.0), *a)).collect();
        TransferFunction::labels(&rows).map_err(|e| MarkError::at(&["labels"], e, "give labels closer together"))
    }

    /// One swatch per label.
    pub fn legend(&self, title: String) -> Legend {
        Legend::Categorical {
            title,
            entries: self.entries.iter().map(|(_, name, c, _)| (name.clone(), *c)).collect(),
            symbol: Symbol::Square,
        }
    }

    /// One row per label: value, name, colour and opacity.
    pub fn derived(&self) -> Derived {
        let mut d = Derived::default();
        d.push("value", DerivedColumn::Number(self.entries.iter().map(|e| e.0 as f64).collect()));
        d.push("name", DerivedColumn::Text(self.entries.iter().map(|e| e.1.clone()).collect()));
        d.push("color", DerivedColumn::Text(self.entries.iter().map(|e| e.2.hex()).collect()));
        d.push("opacity", DerivedColumn::Number(self.entries.iter().map(|e| e.3).collect()));
        d
    }
}
