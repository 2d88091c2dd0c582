//! Keys and values people bring from other plotting tools (matplotlib, seaborn, ggplot,
//! Vega-Lite), and how dataink says the same thing, for the hints of unknown keys and values.

/// How dataink says what a key from another tool meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Translation {
    /// The dataink key that does the job; the translation applies only where it is allowed.
    pub key: &'static str,
    /// What the foreign key is, as a label on it.
    pub label: &'static str,
    /// The dataink spelling, as a hint.
    pub hint: &'static str,
}

impl Translation {
    /// The hint with the chart's own column for `COLUMN` when the chart names one (a column whose
    /// name needs escaping in TOML is left as the placeholder).
    pub fn hint_for(&self, column: Option<&str>) -> String {
        match column.filter(|c| !c.contains(['"', '\\']) && !c.chars().any(char::is_control)) {
            Some(column) => self.hint.replace("\"COLUMN\"", &format!("\"{column}\"")),
            None => self.hint.to_owned(),
        }
    }
}

const fn t(key: &'static str, label: &'static str, hint: &'static str) -> Translation {
    Translation { key, label, hint }
}

const COLOR_MAP: Translation = t(
    "color",
    "a colour map is the `scheme` of a colour encoding",
    "write `color = { field = \"COLUMN\", scheme = \"viridis\" }` (continuous schemes: viridis, magma, cividis, rdbu, …; categorical: okabe-ito, tableau10, …)",
);
const HUE: Translation = t(
    "color",
    "a colour grouping is `color`",
    "write `color = \"COLUMN\"` (or `color = { field = \"COLUMN\", title = \"...\" }`)",
);
const X_SCALE: Translation =
    t("x", "an axis scale belongs to its channel", "write `x = { field = \"COLUMN\", scale = \"log\" }`");
const Y_SCALE: Translation =
    t("y", "an axis scale belongs to its channel", "write `y = { field = \"COLUMN\", scale = \"log\" }`");
const X_LABEL: Translation = t(
    "x",
    "an axis title belongs to its channel",
    "write `x = { field = \"COLUMN\", title = \"...\", unit = \"...\" }`",
);
const Y_LABEL: Translation = t(
    "y",
    "an axis title belongs to its channel",
    "write `y = { field = \"COLUMN\", title = \"...\", unit = \"...\" }`",
);
const X_LIMITS: Translation =
    t("x", "axis limits are the channel's `domain`", "write `x = { field = \"COLUMN\", domain = [LOW, HIGH] }`");
const Y_LIMITS: Translation =
    t("y", "axis limits are the channel's `domain`", "write `y = { field = \"COLUMN\", domain = [LOW, HIGH] }`");
const FIGURE_SIZE: Translation = t(
    "size",
    "the canvas size is `size`",
    "write `size = [WIDTH, HEIGHT]` in pixels; `--scale 2` on the command line doubles a PNG's resolution",
);
const ALPHA: Translation =
    t("opacity", "transparency is `opacity`", "write `opacity = 0.5` (0 transparent to 1 opaque)");

/// The translation of a key from another tool, when one exists (case, `_` and `-` ignored).
pub fn key(name: &str) -> Option<Translation> {
    let normal: String = name.chars().filter(|c| !matches!(c, '_' | '-')).collect::<String>().to_ascii_lowercase();
    Some(match normal.as_str() {
        "colormap" | "colourmap" | "cmap" | "colorscale" | "colorscheme" | "palette" => COLOR_MAP,
        "hue" | "colorby" => HUE,
        "xscale" | "logx" | "xlog" | "semilogx" => X_SCALE,
        "yscale" | "logy" | "ylog" | "semilogy" | "logscale" => Y_SCALE,
        "xlabel" | "xtitle" | "xaxislabel" | "xaxistitle" => X_LABEL,
        "ylabel" | "ytitle" | "yaxislabel" | "yaxistitle" => Y_LABEL,
        "xlim" | "xlimits" | "xrange" | "xdomain" => X_LIMITS,
        "ylim" | "ylimits" | "yrange" | "ydomain" => Y_LIMITS,
        "figsize" | "figuresize" | "width" | "height" => FIGURE_SIZE,
        "alpha" | "transparency" => ALPHA,
        _ => return None,
    })
}

/// A note on a value from another tool that dataink names differently or leaves out on purpose
/// (colour maps, interpolation methods), naming what to use instead.
pub fn value(text: &str) -> Option<&'static str> {
    Some(match text.to_ascii_lowercase().as_str() {
        "jet" | "hsv" | "gist_rainbow" | "nipy_spectral" => {
            "`jet`, `hsv` and their kin are rainbow maps: their bright bands (cyan, yellow) show edges the data does not have, and they do not read in grey; use `viridis`, `cividis` or `magma` for ordered values and `rdbu` for values around a midpoint (`rainbow` and `turbo` exist for cyclic or legacy needs)"
        }
        "coolwarm" | "bwr" | "seismic" | "rdbu_r" => {
            "a diverging map around a midpoint is `rdbu` (also `brbg`, `puor`, `piyg`, `prgn`, `rdylbu`)"
        }
        "gray" | "grey" | "binary" | "gist_gray" => "the grey map is `greys`",
        "harmonic" | "fritsch-carlson" | "fritsch_carlson" | "monotone" | "monotonecubic" => {
            "monotone cubic interpolation with weighted harmonic-mean slopes (Fritsch–Carlson) is `pchip`"
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_from_other_tools_translate_ignoring_case_and_separators() {
        assert_eq!(key("cmap").map(|t| t.key), Some("color"));
        assert_eq!(key("colorMap").map(|t| t.key), Some("color"));
        assert_eq!(key("y_scale"), Some(Y_SCALE));
        assert_eq!(key("logy"), Some(Y_SCALE));
        assert_eq!(key("xlabel"), Some(X_LABEL));
        assert_eq!(key("x-lim"), Some(X_LIMITS));
        assert_eq!(key("hue"), Some(HUE));
        assert_eq!(key("radius"), None);
    }

    #[test]
    fn every_hint_names_its_dataink_key() {
        for name in ["cmap", "hue", "xscale", "yscale", "xlabel", "ylabel", "xlim", "ylim", "figsize", "alpha"] {
            let translation = key(name).expect(name);
            assert!(translation.hint.starts_with(&format!("write `{}", translation.key)), "{name}: {translation:?}");
        }
    }

    #[test]
    fn the_hint_names_the_charts_own_column() {
        assert_eq!(Y_SCALE.hint_for(Some("CO2")), "write `y = { field = \"CO2\", scale = \"log\" }`");
        assert_eq!(Y_SCALE.hint_for(None), Y_SCALE.hint);
        assert_eq!(Y_SCALE.hint_for(Some("a\"b")), Y_SCALE.hint);
    }

    #[test]
    fn foreign_values_point_to_names_that_exist() {
        let jet = value("jet").expect("jet");
        for scheme in ["viridis", "cividis", "magma", "rdbu"] {
            assert!(crate::guide::color::continuous_names().contains(&scheme) && jet.contains(scheme));
        }
        assert!(value("coolwarm").is_some_and(|v| v.contains("`rdbu`")));
        assert!(value("harmonic").is_some_and(|v| v.ends_with("`pchip`")));
        assert_eq!(value("viridis"), None);
    }
}
