//! Rules for volume charts, from what the chart reports of its volume
//! ([`VolumeFacts`](crate::mark::volume::VolumeFacts)):
//! - SC006 `volume-without-legend`: a volume rendering whose colours no legend decodes;
//! - DI008 `iso-outside-range`: an iso value outside the volume's values draws no surface;
//! - TQ006 `transfer-function-coverage`: a transfer function that shows almost nothing (under
//!   0.1% of the voxels) or almost everything (over 99%): a blank image or a fog.

use crate::guide::format::format_value;
use crate::lint::{Category, Issue, Rule, Severity, Subject};
use crate::scene::Role;

/// SC006.
pub static WITHOUT_LEGEND: Rule = Rule {
    code: "SC006",
    name: "volume-without-legend",
    category: Category::Scale,
    severity: Severity::Error,
    summary: "A volume rendering is coloured by value or label but no legend decodes the colours.",
    check: without_legend,
};

/// DI008.
pub static ISO_OUTSIDE_RANGE: Rule = Rule {
    code: "DI008",
    name: "iso-outside-range",
    category: Category::Integrity,
    severity: Severity::Error,
    summary: "An iso value lies outside the volume's values, so its surface is missing from the chart.",
    check: iso_outside_range,
};

/// TQ006.
pub static COVERAGE: Rule = Rule {
    code: "TQ006",
    name: "transfer-function-coverage",
    category: Category::Technique,
    severity: Severity::Warning,
    summary: "A transfer function shows under 0.1% of the voxels (a blank image) or over 99% (a fog).",
    check: coverage,
};

/// Shares of the voxels shown below and above which TQ006 speaks.
const TOO_FEW: f64 = 0.001;
const TOO_MANY: f64 = 0.99;

fn without_legend(s: &Subject<'_>) -> Vec<Issue> {
    let Some(facts) = &s.output.volume else { return Vec::new() };
    let mut legend = false;
    s.output.scene.walk(|item| legend |= item.role == Role::Legend);
    if !facts.coloured || legend {
        return Vec::new();
    }
    let what = "the volume is coloured through its transfer function (or labels) but no legend shows which \
                values are which colour and how opaque";
    let fix = "remove `legend = false`: the legend draws the transfer function over the histogram of the values";
    vec![Issue::new("legend", "legend", what, fix)]
}

fn iso_outside_range(s: &Subject<'_>) -> Vec<Issue> {
    let Some(facts) = &s.output.volume else { return Vec::new() };
    let Some((lo, hi)) = facts.range else { return Vec::new() };
    let outside: Vec<String> = facts.levels.iter().filter(|&&v| v < lo || v > hi).map(|&v| format_value(v)).collect();
    if outside.is_empty() {
        return Vec::new();
    }
    vec![Issue::new(
        "iso value",
        "levels",
        format!(
            "{} {} outside the volume's values ({} to {}): no surface is drawn there",
            if outside.len() == 1 { "level" } else { "levels" },
            outside.join(", ") + if outside.len() == 1 { " is" } else { " are" },
            format_value(lo),
            format_value(hi)
        ),
        "choose levels between the volume's smallest and largest values (`dataink data SPEC SOURCE` shows them)",
    )]
}

fn coverage(s: &Subject<'_>) -> Vec<Issue> {
    let Some(shown) = s.output.volume.as_ref().and_then(|f| f.shown) else { return Vec::new() };
    if (TOO_FEW..=TOO_MANY).contains(&shown) {
        return Vec::new();
    }
    let percent = format_value(100.0 * shown);
    let (message, fix) = if shown < TOO_FEW {
        (
            format!(
                "the transfer function shows {percent}% of the voxels (opacity at least 1/255 per voxel): the image is \
                 nearly blank"
            ),
            "raise `opacity` over the values of interest; the legend's histogram shows where the voxels are",
        )
    } else {
        (
            format!("the transfer function shows {percent}% of the voxels: everything is a fog and nothing stands out"),
            "make the background values transparent (opacity 0 at the lowest control points), or use \
             `gradient_opacity = true` to show boundaries only",
        )
    };
    vec![Issue::new("transfer function", "opacity", message, fix)]
}
