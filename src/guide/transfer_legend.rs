//! The legend of a volume's transfer function: along one value axis, the colour ramp, the
//! histogram of the volume's values (grey bars, length by log count, so the sparse values a
//! transfer function usually picks out stay visible beside the mass of background voxels) and
//! the opacity curve over it with its control points, opacity 0 at the panel's left edge and
//! 1 at its right. How CT and MRI users choose opacities: by the peaks of the histogram.

use std::sync::Arc;

use super::Theme;
use super::color::ContinuousMap;
use super::legend::{bar_tick, value_scale};
use super::scale::Scale;
use crate::scene::{Anchor, Baseline, Color, Item, PathCmd, Point, Raster, Rect, Role, Shape, Style, Text};
use crate::text::measure;

/// A transfer function and the histogram it is read against.
#[derive(Clone, Debug)]
pub struct TransferLegend {
    /// The colour map of the transfer function.
    pub map: ContinuousMap,
    /// The values at the map's two ends (colours hold beyond them).
    pub colour_domain: (f64, f64),
    /// The value axis, bottom to top; it holds every control point.
    pub domain: (f64, f64),
    /// Opacity control points `[value, opacity]`, rising in value (end opacities hold beyond).
    pub opacity: Vec<[f64; 2]>,
    /// Voxels per bin, in equal bins over `domain`, bottom to top.
    pub counts: Vec<u64>,
}

/// Width of the colour ramp and of the histogram panel beside it.
const RAMP_WIDTH: f64 = 12.0;
const PANEL_WIDTH: f64 = 64.0;

impl TransferLegend {
    /// The ramp and the panel for a legend whose column starts at `x`, `length` tall from `top`.
    fn boxes(x: f64, top: f64, length: f64) -> (Rect, Rect) {
        let ramp = Rect::new(x, top, RAMP_WIDTH, length);
        (ramp, Rect::new(ramp.right() + 2.0, top, PANEL_WIDTH, length))
    }

    /// The value scale along a panel `length` tall.
    pub fn scale(&self, theme: &Theme, length: f64) -> Option<Scale> {
        value_scale(self.domain, length, theme)
    }

    /// Width and height of the drawing under the title, for a panel `length` tall.
    pub fn extent(&self, theme: &Theme, length: f64) -> (f64, f64) {
        let label_w = self
            .scale(theme, length)
            .map(|s| s.ticks().iter().map(|t| measure(&t.label, theme.font_size).width).fold(0.0, f64::max))
            .unwrap_or(0.0);
        let w = RAMP_WIDTH + 2.0 + PANEL_WIDTH + theme.tick_length + 3.0 + label_w;
        (w, theme.font_size * 0.5 + length + opacity_axis_height(theme))
    }

    /// The items of the drawing under the title, its top-left corner at `at`.
    pub fn draw(&self, at: Point, theme: &Theme, length: f64) -> Vec<Item> {
        let (ramp, panel) = TransferLegend::boxes(at.x, at.y + theme.font_size * 0.5, length);
        let (d0, d1) = self.domain;
        let y_of = |v: f64| panel.bottom() - (v - d0) / (d1 - d0) * length;
        let mut items = vec![Item::new(Role::Legend, Shape::Image(self.ramp(ramp)), Style::default())];
        items.push(Item::new(Role::Legend, Shape::Rect(ramp), Style::stroke(theme.axis, 0.5)));
        items.extend(self.histogram(panel));
        items.push(Item::new(Role::Legend, Shape::Rect(panel), Style::stroke(theme.axis, 0.5)));

        // The opacity curve through the control points, held flat beyond the end ones.
        let x_of = |a: f64| panel.x + a.clamp(0.0, 1.0) * panel.w;
        let (Some(first), Some(last)) = (self.opacity.first(), self.opacity.last()) else { return items };
        let mut curve = vec![[d0, first[1]]];
        curve.extend(self.opacity.iter().copied());
        curve.push([d1, last[1]]);
        let path: Vec<PathCmd> = curve
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let pt = Point::new(x_of(p[1]), y_of(p[0]));
                if k == 0 { PathCmd::MoveTo(pt) } else { PathCmd::LineTo(pt) }
            })
            .collect();
        items.push(Item::new(Role::Legend, Shape::Path(path), Style::stroke(theme.text, 1.5)));
        for p in &self.opacity {
            items.push(Item::new(
                Role::Legend,
                Shape::Circle { center: Point::new(x_of(p[1]), y_of(p[0])), radius: 2.5 },
                Style::fill(theme.text),
            ));
        }

        // Value ticks right of the panel.
        if let Some(scale) = self.scale(theme, length) {
            let mut ticks = Vec::new();
            for t in scale.ticks() {
                bar_tick(&mut ticks, &mut items, panel, panel.y + t.position, &t.label, theme);
            }
            items.push(Item::new(Role::Legend, Shape::Path(ticks), Style::stroke(theme.axis, 1.0)));
        }
        // The opacity axis under the panel: 0 at the left, 1 at the right.
        let y = panel.bottom() + 3.0;
        let under = |x: f64, text: &str, anchor| {
            let mut item = label(Point::new(x, y), text, anchor, theme);
            if let Shape::Text(t) = &mut item.shape {
                t.baseline = Baseline::Top;
            }
            item
        };
        items.push(under(panel.x, "0", Anchor::Start));
        items.push(under(panel.x + panel.w / 2.0, "opacity", Anchor::Middle));
        items.push(under(panel.right(), "1", Anchor::End));
        items
    }

    /// The colour ramp over the value axis, top = high values.
    fn ramp(&self, dest: Rect) -> Raster {
        const STEPS: u32 = 256;
        let ((d0, d1), (c0, c1)) = (self.domain, self.colour_domain);
        let mut rgba = Vec::with_capacity(STEPS as usize * 4);
        for i in 0..STEPS {
            let v = d1 - (d1 - d0) * (i as f64 + 0.5) / STEPS as f64;
            let c = self.map.at(((v - c0) / (c1 - c0)).clamp(0.0, 1.0));
            rgba.extend_from_slice(&[c.r, c.g, c.b, c.a]);
        }
        Raster { dest, width: 1, height: STEPS, rgba: Arc::new(rgba), smooth: true }
    }

    /// Grey bars, one per histogram bin, from the panel's left edge, length by log count.
    fn histogram(&self, panel: Rect) -> Vec<Item> {
        let most = self.counts.iter().copied().max().unwrap_or(0);
        if most == 0 {
            return Vec::new();
        }
        let bins = self.counts.len() as f64;
        let h = panel.h / bins;
        let full = (most as f64).ln_1p();
        let grey = Color::rgb(0xbb, 0xbb, 0xbb);
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .map(|(i, &c)| {
                let w = panel.w * (c as f64).ln_1p() / full;
                let y = panel.bottom() - h * (i as f64 + 1.0);
                Item::new(Role::Legend, Shape::Rect(Rect::new(panel.x, y, w, h)), Style::fill(grey))
            })
            .collect()
    }
}

/// Height of the opacity axis labels under the panel.
fn opacity_axis_height(theme: &Theme) -> f64 {
    theme.font_size * 1.4 + 3.0
}

fn label(at: Point, content: &str, anchor: Anchor, theme: &Theme) -> Item {
    Item::text(
        Role::Legend,
        Text {
            at,
            content: content.to_string(),
            size: theme.font_size,
            anchor,
            baseline: Baseline::Middle,
            angle: 0.0,
            color: theme.muted_text,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guide::color::continuous;

    fn legend() -> TransferLegend {
        TransferLegend {
            map: continuous("magma").unwrap(),
            colour_domain: (0.0, 100.0),
            domain: (0.0, 200.0),
            opacity: vec![[50.0, 0.0], [100.0, 0.5], [150.0, 1.0]],
            counts: vec![1000, 10, 0, 1],
        }
    }

    #[test]
    fn the_opacity_curve_passes_through_the_control_points() {
        let theme = Theme::default();
        let items = legend().draw(Point::new(0.0, 0.0), &theme, 200.0);
        let curve = items
            .iter()
            .find_map(|i| match &i.shape {
                Shape::Path(p) if i.style.stroke.as_ref().is_some_and(|s| s.width == 1.5) => Some(p.clone()),
                _ => None,
            })
            .unwrap();
        let pts: Vec<(f64, f64)> = curve
            .iter()
            .map(|c| match c {
                PathCmd::MoveTo(p) | PathCmd::LineTo(p) => (p.x, p.y),
                _ => unreachable!(),
            })
            .collect();
        // Panel from x = 14 (64 wide), from y = 6 (200 tall): value v at y = 206 − v, opacity a
        // at x = 14 + 64a; ends held: 0 at the bottom, 1 at the top.
        let top = theme.font_size * 0.5;
        let want = [(0.0, 0.0), (50.0, 0.0), (100.0, 0.5), (150.0, 1.0), (200.0, 1.0)]
            .map(|(v, a)| (14.0 + 64.0 * a, top + 200.0 - v));
        assert_eq!(pts.len(), want.len());
        for (p, w) in pts.iter().zip(want) {
            assert!((p.0 - w.0).abs() < 1e-9 && (p.1 - w.1).abs() < 1e-9, "{pts:?}");
        }
    }

    #[test]
    fn histogram_bars_grow_with_log_count_and_skip_empty_bins() {
        let panel = Rect::new(0.0, 0.0, 64.0, 100.0);
        let bars: Vec<Rect> = legend()
            .histogram(panel)
            .iter()
            .map(|i| match i.shape {
                Shape::Rect(r) => r,
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(bars.len(), 3, "the empty bin draws nothing");
        assert!((bars[0].w - 64.0).abs() < 1e-9);
        assert!((bars[1].w - 64.0 * 11f64.ln() / 1001f64.ln()).abs() < 1e-9);
        // Bottom bin at the bottom.
        assert!((bars[0].bottom() - 100.0).abs() < 1e-9 && (bars[2].y - 0.0).abs() < 1e-9);
    }
}
