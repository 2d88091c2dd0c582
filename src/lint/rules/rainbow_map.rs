//! CL001 `rainbow-map`: a hue-cycling ("rainbow") colour map on ordered values.
//!
//! Rainbow maps (`rainbow`, `turbo`, `sinebow`) run through the hues with a lightness that rises
//! and falls, so the eye sees bands where the hue changes fastest (yellow, cyan) that are not in
//! the data, cannot tell which end is high, and, with a red–green deficiency, sees several
//! values as one (Borland & Taylor 2007, "Rainbow color map (still) considered harmful"). The
//! message quotes the map's lightness L\* at its low end, at its lightness extreme and at its
//! high end, and whether both ends are the same colour (a cyclic map).

use crate::guide::color::{self, ContinuousMap};
use crate::guide::colour_science::{ciede2000, lab};
use crate::lint::chart_info::{colour_encodings, scheme_of};
use crate::lint::{Category, Issue, Rule, Severity, Subject};

/// The rule.
pub static RULE: Rule = Rule {
    code: "CL001",
    name: "rainbow-map",
    category: Category::Colour,
    severity: Severity::Warning,
    summary: "A rainbow (hue-cycling) colour map colours ordered values: it shows false bands and hides order.",
    check,
};

fn check(s: &Subject<'_>) -> Vec<Issue> {
    let encodings = colour_encodings(s.chart);
    let mut found: Vec<(String, String, String)> = encodings
        .iter()
        .filter_map(|e| {
            let name = e.options.scheme.as_deref()?;
            Some((format!("{}.scheme", e.key), name.to_string(), format!("`{}`", e.options.field)))
        })
        .collect();
    // A chart-level `scheme` applies when no column is colour-encoded (treemaps and hyperbolic
    // trees ignore it under `color`).
    if encodings.is_empty()
        && let Some((key, name)) = scheme_of(s.chart)
    {
        found.push((key.to_string(), name.to_string(), "the chart's values".to_string()));
    }
    found
        .into_iter()
        .filter_map(|(key, name, what)| {
            let map = color::continuous(&name).filter(ContinuousMap::is_rainbow)?;
            Some(Issue::new(
                "colour map",
                key,
                format!("`{}` is a rainbow colour map colouring {what}: {}", map.name(), lightness_story(&map)),
                "for ordered values use a sequential map such as `scheme = \"viridis\"` or `\"cividis\"`; for \
                 values either side of a meaningful centre, a diverging map such as `\"rdbu\"` with `midpoint`; \
                 a hue cycle suits only cyclic quantities (angles, phases): then allow `rainbow-map` for this chart",
            ))
        })
        .collect()
}

/// "its lightness runs L* 23 → 95 → 18 along the map, ..." with the numbers of `map`.
fn lightness_story(map: &ContinuousMap) -> String {
    const STEPS: usize = 64;
    let ls: Vec<f64> = (0..=STEPS).map(|i| lab(map.at(i as f64 / STEPS as f64)).l).collect();
    let (first, last) = (ls.first().copied().unwrap_or(0.0), ls.last().copied().unwrap_or(0.0));
    let (lo, hi) = ls.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &l| (lo.min(l), hi.max(l)));
    // The interior extreme farthest from the ends' lightness.
    let turn = if hi - first.max(last) >= first.min(last) - lo { hi } else { lo };
    let mut story = format!(
        "its lightness runs L* {first:.0} → {turn:.0} → {last:.0} along the map, so it draws bands that are \
         not in the data and does not show which values are higher"
    );
    let ends = ciede2000(lab(map.at(0.0)), lab(map.at(1.0)));
    if ends < 5.0 {
        story.push_str(&format!(
            "; its two ends are nearly the same colour (ΔE00 {ends:.1}), so the lowest and highest values look alike"
        ));
    }
    story
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_story_has_the_maps_numbers() {
        let turbo = lightness_story(&color::continuous("turbo").unwrap());
        assert!(turbo.starts_with("its lightness runs L* "), "{turbo}");
        // Turbo starts and ends dark and is light in the middle.
        let nums: Vec<f64> = turbo
            .trim_start_matches("its lightness runs L* ")
            .split(" along")
            .next()
            .unwrap()
            .split(" → ")
            .map(|n| n.parse().unwrap())
            .collect();
        assert_eq!(nums.len(), 3);
        assert!(nums[1] > nums[0] + 40.0 && nums[1] > nums[2] + 40.0, "{nums:?}");
        assert!(!turbo.contains("same colour"), "{turbo}");
        // Sinebow and the cyclic rainbow come back to where they started.
        for name in ["sinebow", "rainbow"] {
            let s = lightness_story(&color::continuous(name).unwrap());
            assert!(s.contains("nearly the same colour (ΔE00 0.0)"), "{name}: {s}");
        }
    }
}
