//! Tick labels of a category (band) axis. Unlike numbers, categories cannot be read off a
//! neighbouring label, so every category keeps its label: labels too wide to sit side by side
//! are wrapped onto two or three lines, else turned (−45°, then −90°); labels longer than the
//! room the axis may take are cut with an ellipsis (the full name stays as the label's hover
//! text). Only when even upright labels are taller than the bands are wide are some left out,
//! and then they are counted so the chart can say so.

use super::Theme;
use super::legend::truncate_to_width;
use super::scale::Tick;
use crate::text::measure;

/// The label of one category as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct CategoryLabel {
    /// The category's tick (its position and full name).
    pub tick: Tick,
    /// The lines drawn, first on top (one line unless wrapped).
    pub lines: Vec<String>,
}

impl CategoryLabel {
    fn single(tick: Tick) -> CategoryLabel {
        CategoryLabel { lines: vec![tick.label.clone()], tick }
    }

    /// Whether the lines drawn differ from the full name (wrapped or cut), so the full name
    /// should be kept as hover text.
    pub fn shortened(&self) -> bool {
        self.lines.len() != 1 || self.lines.first() != Some(&self.tick.label)
    }
}

/// How the labels of a category axis are set.
#[derive(Clone, Debug, PartialEq)]
pub struct CategoryFit {
    /// The labels drawn, in tick order.
    pub labels: Vec<CategoryLabel>,
    /// Rotation of every label in degrees, clockwise (0, −45 or −90).
    pub angle: f64,
    /// Categories whose labels had to be left out (the bands are narrower than a line of text).
    pub left_out: usize,
}

/// The most lines a bottom-axis label is wrapped onto.
pub const MAX_LINES: usize = 3;
/// The most lines a left-axis label is wrapped onto.
pub const MAX_LEFT_LINES: usize = 2;

/// Height of one line of tick-label text (ascent to descent): the distance between wrapped lines.
pub fn line_height(theme: &Theme) -> f64 {
    let m = measure("Ag", theme.font_size);
    m.ascent + m.descent
}

/// Smallest gap between the labels of neighbouring categories set side by side.
fn side_gap(theme: &Theme) -> f64 {
    theme.font_size * 0.6
}

/// Width of the widest of `lines`.
fn widest(lines: &[String], size: f64) -> f64 {
    lines.iter().map(|l| measure(l, size).width).fold(0.0, f64::max)
}

/// Where `label` may be broken: `(end of the line, start of the next)` in characters. A space
/// is dropped at the break; a hyphen, underscore or slash stays at the end of the first line.
fn breaks(chars: &[char]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for (i, c) in chars.iter().enumerate() {
        let inside = i > 0 && i + 1 < chars.len();
        match c {
            ' ' if inside && chars[i - 1] != ' ' => out.push((i, i + 1)),
            '-' | '_' | '/' if inside && chars[i + 1] != ' ' => out.push((i + 1, i + 1)),
            _ => {}
        }
    }
    out
}

/// Break candidates looked at per label: a label with more is wrapped only at its first ones.
const MAX_BREAKS: usize = 40;

/// `label` on at most `max_lines` lines, broken where [`breaks`] allows so that the widest line
/// is as narrow as it can be (fewer lines when that is as narrow). A label without a place to
/// break stays one line.
pub fn wrap(label: &str, max_lines: usize, size: f64) -> Vec<String> {
    let chars: Vec<char> = label.chars().collect();
    let cuts: Vec<(usize, usize)> = breaks(&chars).into_iter().take(MAX_BREAKS).collect();
    let piece = |from: usize, to: usize| chars[from..to].iter().collect::<String>().trim().to_string();
    let lines_of = |picked: &[(usize, usize)]| {
        let mut lines = Vec::with_capacity(picked.len() + 1);
        let mut start = 0;
        for &(end, next) in picked {
            lines.push(piece(start, end));
            start = next;
        }
        lines.push(piece(start, chars.len()));
        lines
    };
    let mut best = vec![label.trim().to_string()];
    let mut best_width = widest(&best, size);
    let mut consider = |lines: Vec<String>| {
        let w = widest(&lines, size);
        if w < best_width - 1e-9 && lines.iter().all(|l| !l.is_empty()) {
            best_width = w;
            best = lines;
        }
    };
    if max_lines >= 2 {
        for &a in &cuts {
            consider(lines_of(&[a]));
        }
    }
    if max_lines >= 3 {
        for (i, &a) in cuts.iter().enumerate() {
            for &b in &cuts[i + 1..] {
                consider(lines_of(&[a, b]));
            }
        }
    }
    best
}

/// Whether labels `widths` wide, centred on `ticks`, sit side by side with a gap between
/// neighbours and inside `span`.
fn side_by_side(ticks: &[Tick], widths: &[f64], gap: f64, span: (f64, f64)) -> bool {
    let inside = ticks
        .iter()
        .zip(widths)
        .all(|(t, w)| t.position - w / 2.0 >= span.0 - 0.5 && t.position + w / 2.0 <= span.1 + 0.5);
    let apart = ticks.windows(2).zip(widths.windows(2)).all(|(t, w)| {
        let distance = (t[1].position - t[0].position).abs();
        distance >= (w[0] + w[1]) / 2.0 + gap
    });
    inside && apart
}

/// The distance between neighbouring ticks (infinite for one tick).
fn spacing(ticks: &[Tick]) -> f64 {
    ticks.windows(2).map(|t| (t[1].position - t[0].position).abs()).fold(f64::INFINITY, f64::min)
}

/// Every `k`-th label, the smallest `k` that leaves `need` pixels between kept ticks, with the
/// count of the labels left out.
fn every_kth(labels: Vec<CategoryLabel>, step: f64, need: f64) -> (Vec<CategoryLabel>, usize) {
    let n = labels.len();
    let k = if step > 0.0 && step.is_finite() { (need / step).ceil().max(1.0) as usize } else { n.max(1) };
    let kept: Vec<CategoryLabel> = labels.into_iter().step_by(k.max(1)).collect();
    let left_out = n - kept.len();
    (kept, left_out)
}

/// The labels of a category axis along the bottom of a plot. `span` is the stretch along x that
/// unturned labels must stay inside; `reach` the longest a turned label may be.
pub fn fit_bottom(ticks: Vec<Tick>, theme: &Theme, span: (f64, f64), reach: f64) -> CategoryFit {
    let size = theme.font_size;
    let gap = side_gap(theme);
    let step = spacing(&ticks);
    let flat: Vec<f64> = ticks.iter().map(|t| measure(&t.label, size).width).collect();
    if side_by_side(&ticks, &flat, gap, span) {
        let labels = ticks.into_iter().map(CategoryLabel::single).collect();
        return CategoryFit { labels, angle: 0.0, left_out: 0 };
    }
    // Wrap only the labels wider than their band's share of the axis.
    let room = step - gap;
    for max_lines in 2..=MAX_LINES {
        let labels: Vec<CategoryLabel> = ticks
            .iter()
            .zip(&flat)
            .map(|(t, &w)| match w > room {
                true => CategoryLabel { tick: t.clone(), lines: wrap(&t.label, max_lines, size) },
                false => CategoryLabel::single(t.clone()),
            })
            .collect();
        let widths: Vec<f64> = labels.iter().map(|l| widest(&l.lines, size)).collect();
        if labels.iter().any(|l| l.lines.len() > 1) && side_by_side(&ticks, &widths, gap, span) {
            return CategoryFit { labels, angle: 0.0, left_out: 0 };
        }
    }
    let reach = reach.max(size * 3.0);
    let labels: Vec<CategoryLabel> = ticks
        .into_iter()
        .map(|tick| CategoryLabel { lines: vec![truncate_to_width(&tick.label, reach, size)], tick })
        .collect();
    // Turned labels need a line's height across them; the font's ascent leaves room above
    // capitals, so lines one height apart do not touch.
    let need = line_height(theme);
    let diagonal = std::f64::consts::FRAC_1_SQRT_2;
    if step * diagonal >= need {
        return CategoryFit { labels, angle: -45.0, left_out: 0 };
    }
    let (labels, left_out) = every_kth(labels, step, need);
    CategoryFit { labels, angle: -90.0, left_out }
}

/// The labels of a category axis left of a plot. A label wider than `reach` is wrapped onto
/// two lines when its band is tall enough for them, and cut with an ellipsis at `reach`
/// otherwise. Labels are left out only when the bands are not as tall as one line.
pub fn fit_left(ticks: Vec<Tick>, theme: &Theme, reach: f64) -> CategoryFit {
    let size = theme.font_size;
    let reach = reach.max(size * 3.0);
    let step = spacing(&ticks);
    let line = line_height(theme);
    let two_lines = step >= MAX_LEFT_LINES as f64 * line;
    let labels: Vec<CategoryLabel> = ticks
        .into_iter()
        .map(|tick| {
            let lines = match measure(&tick.label, size).width <= reach {
                true => vec![tick.label.clone()],
                false if two_lines => wrap(&tick.label, MAX_LEFT_LINES, size),
                false => vec![tick.label.clone()],
            };
            let lines = lines.into_iter().map(|l| truncate_to_width(&l, reach, size)).collect();
            CategoryLabel { tick, lines }
        })
        .collect();
    if step >= line {
        return CategoryFit { labels, angle: 0.0, left_out: 0 };
    }
    let (labels, left_out) = every_kth(labels, step, line);
    CategoryFit { labels, angle: 0.0, left_out }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ticks(labels: &[&str], step: f64) -> Vec<Tick> {
        labels
            .iter()
            .enumerate()
            .map(|(i, l)| Tick { value: i as f64, position: step * (i as f64 + 0.5), label: l.to_string() })
            .collect()
    }

    const ALL: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);

    #[test]
    fn wraps_at_spaces_hyphens_and_underscores() {
        assert_eq!(wrap("Grand Theft Auto", 2, 12.0), vec!["Grand", "Theft Auto"]);
        assert_eq!(wrap("north-east_region", 2, 12.0), vec!["north-east_", "region"]);
        assert_eq!(wrap("one two three four five six", 3, 12.0), vec!["one two", "three four", "five six"]);
        assert_eq!(wrap("Unbreakable", 3, 12.0), vec!["Unbreakable"]);
        // Leading, trailing and doubled spaces never make empty lines.
        assert_eq!(wrap("  a  b ", 3, 12.0), vec!["a", "b"]);
        assert_eq!(wrap("x-", 2, 12.0), vec!["x-"]);
        // One line when breaking would not make it narrower.
        assert_eq!(wrap("a b", 1, 12.0), vec!["a b"]);
    }

    #[test]
    fn short_labels_stay_flat() {
        let fit = fit_bottom(ticks(&["a", "b", "c"], 40.0), &Theme::default(), ALL, 100.0);
        assert_eq!(fit.angle, 0.0);
        assert_eq!(fit.left_out, 0);
        assert!(fit.labels.iter().all(|l| !l.shortened()));
    }

    #[test]
    fn long_labels_wrap_when_that_fits() {
        let fit = fit_bottom(ticks(&["North America", "South America", "Europe"], 70.0), &Theme::default(), ALL, 100.0);
        assert_eq!(fit.angle, 0.0);
        assert_eq!(fit.labels[0].lines, vec!["North", "America"]);
        assert_eq!(fit.labels[2].lines, vec!["Europe"]);
        assert!(fit.labels[0].shortened() && !fit.labels[2].shortened());
    }

    #[test]
    fn labels_turn_when_wrapping_is_not_enough() {
        let names = ["Supercalifragilistic", "Antidisestablishment", "Floccinaucinihilipil"];
        let fit = fit_bottom(ticks(&names, 30.0), &Theme::default(), ALL, 300.0);
        assert_eq!((fit.angle, fit.left_out, fit.labels.len()), (-45.0, 0, 3));
        let fit = fit_bottom(ticks(&names, 16.0), &Theme::default(), ALL, 300.0);
        assert_eq!((fit.angle, fit.left_out, fit.labels.len()), (-90.0, 0, 3));
        // Long names are cut at the reach and keep the ellipsis.
        let fit = fit_bottom(ticks(&names, 30.0), &Theme::default(), ALL, 60.0);
        assert!(fit.labels.iter().all(|l| l.lines[0].ends_with('…') && measure(&l.lines[0], 12.0).width <= 60.0));
    }

    #[test]
    fn too_narrow_bands_leave_labels_out_and_count_them() {
        let names: Vec<String> = (0..100).map(|i| format!("category {i}")).collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let fit = fit_bottom(ticks(&names, 5.0), &Theme::default(), ALL, 300.0);
        assert_eq!(fit.angle, -90.0);
        // 12 px text needs 13.5 px: every third band at 5 px apart.
        assert_eq!(fit.labels.len(), 34);
        assert_eq!(fit.left_out, 66);
    }

    #[test]
    fn left_labels_wrap_or_cut_and_never_thin_when_a_line_fits() {
        let theme = Theme::default();
        let long = "An exceedingly long category name indeed";
        let fit = fit_left(ticks(&[long, "short"], 40.0), &theme, 150.0);
        assert_eq!(fit.labels[0].lines.len(), 2);
        assert!(fit.labels[0].lines.iter().all(|l| measure(l, 12.0).width <= 150.0));
        assert_eq!(fit.labels[1].lines, vec!["short"]);
        // Bands one line tall: cut, not wrapped, and all kept.
        let names: Vec<String> = (0..40).map(|i| format!("{long} {i}")).collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let fit = fit_left(ticks(&names, 16.0), &theme, 150.0);
        assert_eq!((fit.labels.len(), fit.left_out), (40, 0));
        assert!(fit.labels.iter().all(|l| l.lines.len() == 1 && l.lines[0].ends_with('…')));
        let fit = fit_left(ticks(&names, 5.0), &theme, 150.0);
        assert_eq!(fit.left_out, 40 - fit.labels.len());
        assert!(fit.left_out > 0);
    }
}
