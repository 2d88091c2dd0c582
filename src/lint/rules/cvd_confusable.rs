//! CL003 `cvd-confusable`: two categories whose colours a reader with a red–green colour-vision
//! deficiency cannot tell apart.
//!
//! The rule reads the categorical legends from the scene (every kind's legends, so it judges the
//! colours the reader sees), simulates protanopia and deuteranopia on each swatch (Machado,
//! Oliveira & Fernandes 2009, severity 1.0, in linear sRGB; see
//! [`crate::guide::colour_science`]) and measures every pair with CIEDE2000. A pair closer than
//! [`THRESHOLD`] with either deficiency is reported (the closest pair per legend, with a count
//! of the others). A pair that is that close with normal vision too is reported as such.
//!
//! # The threshold: ΔE00 10
//!
//! Measured with this code (and colorspacious, which agrees to 0.01) on the palettes dataink
//! ships, taking each palette's first n colours; the number is the smallest ΔE00 of any pair
//! under either simulated deficiency:
//!
//! | palette | n | min ΔE00 | closest pair |
//! |---|---|---|---|
//! | okabe-ito | 8 (all) | 11.6 | orange `#e69f00` / yellow `#f0e442`, deuteranopia |
//! | okabe-ito | 5–6 | 12.2 | blue `#0072b2` / reddish purple `#cc79a7`, protanopia |
//! | category10 | 3 | 1.3 | orange `#ff7f0e` / green `#2ca02c`, protanopia |
//! | tableau10 | 2–4 | 13.9 | orange `#f28e2b` / red `#e15759`, deuteranopia |
//! | tableau10 | 5 | 0.7 | red `#e15759` / green `#59a14f`, deuteranopia |
//! | paired | 4 | 19.4 | light green `#b2df8a` / green `#33a02c`, protanopia |
//! | paired | 5 | 8.4 | light green `#b2df8a` / pink `#fb9a99`, deuteranopia |
//! | paired | 6 | 4.7 | green `#33a02c` / red `#e31a1c`, deuteranopia |
//! | set2 | 4 | 1.6 | `#8da0cb` / `#e78ac3`, protanopia |
//! | dark2 | 4 | 4.9 | `#1b9e77` / `#e7298a`, deuteranopia |
//!
//! Any threshold in (8.4, 11.6] passes the whole Okabe–Ito palette and fails every palette that
//! puts a red next to a green (category10 from 3 categories, tableau10 from 5, paired from 5);
//! 10 sits in the middle of that gap. For scale: ΔE00 1 is a just-noticeable difference between
//! large patches, and small chart marks need several times that. Tableau10's first four colours
//! (blue, orange, red, teal) pass: its red and green are the 3rd and 5th colours.

use super::colour_keys::{ColourKey, colour_keys, palette_keys};
use crate::guide::colour_science::{Deficiency, difference};
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::Color;

/// Pairs closer than this (CIEDE2000) under simulated protanopia or deuteranopia are reported.
pub const THRESHOLD: f64 = 10.0;

/// Colours in the Okabe–Ito palette, the most that stay apart with either deficiency.
const OKABE_ITO_COLOURS: usize = 8;

/// The rule.
pub static RULE: Rule = Rule {
    code: "CL003",
    name: "cvd-confusable",
    category: Category::Colour,
    severity: Severity::Warning,
    summary: "Two categories' colours look alike with protanopia or deuteranopia (CIEDE2000 below 10).",
    check,
};

/// The closest pair of a legend and how many pairs fall below the threshold.
#[derive(Clone, Debug, PartialEq)]
struct Closest {
    /// Indices into the legend's entries.
    pair: (usize, usize),
    /// The vision under which they are closest (`None`: normal vision).
    vision: Option<Deficiency>,
    /// ΔE00 under that vision.
    delta: f64,
    /// ΔE00 with normal vision.
    normal: f64,
    /// The smallest ΔE00 of the pair under any of the three visions (ranks the pairs).
    worst: f64,
    /// Pairs below the threshold, this one included.
    count: usize,
}

/// The closest pair of `colors` under normal, protan and deutan vision, if any pair is closer
/// than [`THRESHOLD`].
fn closest(colors: &[Color]) -> Option<Closest> {
    let mut best: Option<Closest> = None;
    let mut count = 0;
    for i in 0..colors.len() {
        for j in i + 1..colors.len() {
            let (Some(&a), Some(&b)) = (colors.get(i), colors.get(j)) else { continue };
            let normal = difference(a, b, None);
            let (deficiency, deficient) = Deficiency::ALL
                .iter()
                .map(|&d| (d, difference(a, b, Some(d))))
                .fold((Deficiency::Protanopia, f64::INFINITY), |acc, x| if x.1 < acc.1 { x } else { acc });
            let worst = normal.min(deficient);
            if worst >= THRESHOLD {
                continue;
            }
            count += 1;
            // Too close for everyone is said as such; otherwise name the deficiency.
            let (vision, delta) = if normal < THRESHOLD { (None, normal) } else { (Some(deficiency), deficient) };
            if best.as_ref().is_none_or(|b| worst < b.worst) {
                best = Some(Closest { pair: (i, j), vision, delta, normal, worst, count: 0 });
            }
        }
    }
    best.map(|b| Closest { count, ..b })
}

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let (_, key) = palette_keys(s.chart);
    colour_keys(&s.output.scene).iter().filter_map(|legend| issue(legend, &key)).collect()
}

fn issue(legend: &ColourKey, key: &str) -> Option<Issue> {
    let colors: Vec<Color> = legend.entries.iter().map(|e| e.1).collect();
    let c = closest(&colors)?;
    let (Some((la, ca)), Some((lb, cb))) = (legend.entries.get(c.pair.0), legend.entries.get(c.pair.1)) else {
        return None;
    };
    let (la, lb) = (crate::spec::validate::shorten(la), crate::spec::validate::shorten(lb));
    let others = match c.count.saturating_sub(1) {
        0 => String::new(),
        1 => format!("; 1 more pair is below {THRESHOLD}"),
        n => format!("; {n} more pairs are below {THRESHOLD}"),
    };
    let (message, hint) = match c.vision {
        Some(d) => (
            format!(
                "\"{la}\" ({}) and \"{lb}\" ({}) look alike with {}: ΔE00 {:.1}, below {THRESHOLD} ({:.1} with \
                 normal vision){others}",
                ca.hex(),
                cb.hex(),
                d.name(),
                c.delta,
                c.normal
            ),
            if legend.categories() > OKABE_ITO_COLOURS {
                format!(
                    "no palette keeps {} hues apart for every reader (Okabe–Ito, the default, keeps its 8 apart \
                     with protanopia and deuteranopia): group the smallest categories into \"other\", or tell \
                     them apart by lightness, shape or direct labels as well as hue",
                    legend.categories()
                )
            } else {
                "use `scheme = \"okabe-ito\"` (the default; its 8 colours stay apart with protanopia and \
                 deuteranopia), or tell the categories apart by lightness, shape or direct labels as well as hue"
                    .to_string()
            },
        ),
        None => (
            format!(
                "\"{la}\" ({}) and \"{lb}\" ({}) have nearly the same colour: ΔE00 {:.1} even with normal \
                 vision, below {THRESHOLD}{others}",
                ca.hex(),
                cb.hex(),
                c.delta
            ),
            "give each category its own colour: if the palette has fewer colours than there are categories, \
             group the smallest into \"other\" or label the marks directly; if the two are coloured alike on \
             purpose, tell them apart by shape in the marks and in the legend"
                .to_string(),
        ),
    };
    Some(Issue::new(legend.element(), key, message, hint))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guide::color::categorical;

    fn min_delta(colors: &[Color]) -> (f64, Option<Deficiency>) {
        let mut best = (f64::INFINITY, None);
        for (i, &a) in colors.iter().enumerate() {
            for &b in &colors[i + 1..] {
                for d in Deficiency::ALL {
                    let delta = difference(a, b, Some(d));
                    if delta < best.0 {
                        best = (delta, Some(d));
                    }
                }
            }
        }
        best
    }

    /// The measurements in the module documentation, to the decimal shown there.
    #[test]
    fn documented_measurements_hold() {
        let table: [(&str, usize, f64, Deficiency); 10] = [
            ("okabe-ito", 8, 11.6, Deficiency::Deuteranopia),
            ("okabe-ito", 6, 12.2, Deficiency::Protanopia),
            ("category10", 3, 1.3, Deficiency::Protanopia),
            ("tableau10", 4, 13.9, Deficiency::Deuteranopia),
            ("tableau10", 5, 0.7, Deficiency::Deuteranopia),
            ("paired", 4, 19.4, Deficiency::Protanopia),
            ("paired", 5, 8.4, Deficiency::Deuteranopia),
            ("paired", 6, 4.7, Deficiency::Deuteranopia),
            ("set2", 4, 1.6, Deficiency::Protanopia),
            ("dark2", 4, 4.9, Deficiency::Deuteranopia),
        ];
        for (name, n, want, deficiency) in table {
            let p = categorical(name).unwrap();
            let (got, d) = min_delta(&p[..n]);
            assert!((got - want).abs() < 0.05, "{name} ×{n}: {got:.3}, documented {want}");
            assert_eq!(d, Some(deficiency), "{name} ×{n}");
        }
    }

    #[test]
    fn threshold_passes_okabe_ito_and_fails_red_green_palettes() {
        let okabe = categorical("okabe-ito").unwrap();
        assert_eq!(okabe.len(), 8);
        assert_eq!(closest(&okabe), None);
        // The 12-colour extension (the branch default above eight branches) passes at every
        // length, and its closest pair is still Okabe–Ito's orange and yellow.
        let twelve = categorical("okabe-ito-12").unwrap();
        assert_eq!((twelve.len(), &twelve[..8]), (12, &okabe[..]));
        for n in 9..=12 {
            assert_eq!(closest(&twelve[..n]), None, "okabe-ito-12 ×{n}");
            assert!((min_delta(&twelve[..n]).0 - 11.6).abs() < 0.05);
        }
        let added = min_delta(&twelve[8..]).0;
        assert!(added >= 14.5, "the four added colours are {added:.2} apart");
        for (name, n) in [("category10", 3), ("tableau10", 5), ("paired", 5), ("set2", 4), ("dark2", 4)] {
            let p = categorical(name).unwrap();
            assert!(closest(&p[..n]).is_some(), "{name} ×{n} passes");
            assert!(closest(&p[..n - 1]).is_none(), "{name} ×{} fails", n - 1);
        }
        // Red and green side by side: protan and deutan both confuse them; the closer one wins.
        let c = closest(&[Color::rgb(0xe1, 0x57, 0x59), Color::rgb(0x59, 0xa1, 0x4f)]).unwrap();
        assert_eq!((c.pair, c.vision, c.count), ((0, 1), Some(Deficiency::Deuteranopia), 1));
        assert!(c.delta < 1.0 && c.normal > 20.0, "{c:?}");
        // A repeated colour is confusable for everyone.
        let blue = Color::rgb(0, 0x72, 0xb2);
        let c = closest(&[blue, Color::rgb(0xe6, 0x9f, 0), blue]).unwrap();
        assert_eq!((c.pair, c.vision, c.delta, c.count), ((0, 2), None, 0.0, 1));
    }
}
