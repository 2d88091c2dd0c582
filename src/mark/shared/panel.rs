//! What a facet panel is told and what it reports back. The facet layout draws each panel with
//! the chart's own kind, handing it a [`Panel`] through the chart ([`crate::spec::Chart::panel`]):
//! the frame ([`super::frame::cartesian`]) and the panel canvas of the other kinds read the
//! scales and plot it fixes and record the axes and legends the panel would have drawn, so the
//! layout can share them across panels and draw the legends once.

use std::fmt;
use std::sync::{Arc, Mutex};

use crate::guide::layout::{Domain, PositionAxis};
use crate::guide::legend::Legend;
use crate::scene::Rect;

/// The instructions for drawing one facet panel, and what it saw.
#[derive(Debug, Default)]
pub struct Panel {
    /// The x domain every panel uses (`None`: the panel's own).
    pub x: Option<Domain>,
    /// The y domain every panel uses (`None`: the panel's own).
    pub y: Option<Domain>,
    /// The range a continuous colour map spans in every panel (`None`: the panel's own).
    pub color: Option<(f64, f64)>,
    /// The domain every panel uses on each column's axis (parallel coordinates, daisy, splom),
    /// by column; empty: the panel's own.
    pub columns: Vec<(String, Domain)>,
    /// Where the plot area lies on the canvas (`None` while measuring).
    pub plot: Option<Rect>,
    /// Whether the x axis carries tick labels (bottom panels, or every panel of an unshared x).
    pub x_labels: bool,
    /// Whether the y axis carries tick labels (left panels, or every panel of an unshared y).
    pub y_labels: bool,
    /// How far tick labels may reach past the plot's ends without running into a neighbour.
    pub overhang: (f64, f64),
    /// The value every panel maps to its largest marker (`None`: the panel's own largest), so a
    /// marker's size means the same in every panel.
    pub size_max: Option<f64>,
    /// Whether this is the measuring pass of a cartesian panel: its frame records the axes and
    /// legends and stops the kind there ([`crate::mark::MarkError::measured`]), so no mark is
    /// built only to be thrown away.
    pub measuring: bool,
    /// What the panel drew, recorded as it drew it.
    pub(crate) seen: Mutex<Seen>,
}

/// What a panel would have drawn around its data.
#[derive(Clone, Debug, Default)]
pub struct Seen {
    /// Its x axis, if it drew one cartesian frame.
    pub x: Option<PositionAxis>,
    /// Its y axis, if it drew one cartesian frame.
    pub y: Option<PositionAxis>,
    /// Its legends (drawn once beside the panels instead).
    pub legends: Vec<Legend>,
    /// Its column axes, by column (kinds with one axis per column).
    pub columns: Vec<(String, PositionAxis)>,
    /// The largest value of its size encoding, if it has one.
    pub size_max: Option<f64>,
}

impl Panel {
    /// Record the axes of the panel's cartesian frame.
    pub fn saw_axes(&self, x: &PositionAxis, y: &PositionAxis) {
        let mut seen = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        seen.x = Some(x.clone());
        seen.y = Some(y.clone());
    }

    /// Record the axes of the panel's columns and give them the shared domains, if set.
    pub fn share_columns(&self, fields: &[&str], axes: &mut [PositionAxis]) {
        let mut seen = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        for (field, axis) in fields.iter().zip(axes.iter_mut()) {
            seen.columns.push((field.to_string(), axis.clone()));
            if let Some((_, domain)) = self.columns.iter().find(|(f, _)| f == field) {
                axis.domain = domain.clone();
            }
        }
    }

    /// Record the largest value of the panel's size encoding, and give the value every panel
    /// maps to its largest marker, if set.
    pub fn share_size_max(&self, own: f64) -> f64 {
        self.seen.lock().unwrap_or_else(|e| e.into_inner()).size_max = Some(own);
        self.size_max.unwrap_or(own)
    }

    /// Record the panel's legends.
    pub fn saw_legends(&self, legends: &[Legend]) {
        self.seen.lock().unwrap_or_else(|e| e.into_inner()).legends.extend(legends.iter().cloned());
    }

    /// What the panel recorded.
    pub fn seen(&self) -> Seen {
        self.seen.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
}

/// A shared [`Panel`], as a chart carries it. Two handles are equal when they are the same panel.
#[derive(Clone, Default)]
pub struct PanelHandle(pub Arc<Panel>);

impl PartialEq for PanelHandle {
    fn eq(&self, other: &PanelHandle) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl fmt::Debug for PanelHandle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl std::ops::Deref for PanelHandle {
    type Target = Panel;
    fn deref(&self) -> &Panel {
        &self.0
    }
}
