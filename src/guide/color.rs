//! Colour maps (continuous and categorical) and colour parsing.
//!
//! Continuous maps come from the `colorous` crate (matplotlib's perceptually uniform maps and the
//! ColorBrewer schemes). A `_r` suffix reverses any continuous map. Names are case-insensitive.

use crate::scene::Color;

/// The default palette for categories: Okabe–Ito, safe for colour-blind readers.
pub const DEFAULT_CATEGORICAL: &str = "okabe-ito";
/// The default map for ordered values.
pub const DEFAULT_SEQUENTIAL: &str = "viridis";
/// The default map for values diverging from a midpoint.
pub const DEFAULT_DIVERGING: &str = "rdbu";
/// The colour [`ContinuousMap::at`] returns for a missing (NaN) value: a neutral mid grey.
pub const MISSING: Color = Color::rgb(0xbd, 0xbd, 0xbd);

/// What a continuous map is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Ordered values from low to high: lightness changes monotonically along the map.
    Sequential,
    /// Values on either side of a meaningful centre: two hues meeting at a light midpoint.
    Diverging,
    /// Hue-cycling ("rainbow") maps: lightness rises and falls along the map, so they show
    /// bands that are not in the data and hide order. Kept for cyclic quantities (angles,
    /// phases) and for users who ask; lint rule CL001 warns when they colour ordered data.
    Rainbow,
}

/// Continuous maps: sequential first, then diverging, then rainbow (without the `_r` forms).
const CONTINUOUS: [(&str, colorous::Gradient, MapKind); 21] = [
    ("viridis", colorous::VIRIDIS, MapKind::Sequential),
    ("magma", colorous::MAGMA, MapKind::Sequential),
    ("inferno", colorous::INFERNO, MapKind::Sequential),
    ("plasma", colorous::PLASMA, MapKind::Sequential),
    ("cividis", colorous::CIVIDIS, MapKind::Sequential),
    ("blues", colorous::BLUES, MapKind::Sequential),
    ("greens", colorous::GREENS, MapKind::Sequential),
    ("greys", colorous::GREYS, MapKind::Sequential),
    ("oranges", colorous::ORANGES, MapKind::Sequential),
    ("purples", colorous::PURPLES, MapKind::Sequential),
    ("reds", colorous::REDS, MapKind::Sequential),
    ("rdbu", colorous::RED_BLUE, MapKind::Diverging),
    ("brbg", colorous::BROWN_GREEN, MapKind::Diverging),
    ("puor", colorous::PURPLE_ORANGE, MapKind::Diverging),
    ("piyg", colorous::PINK_GREEN, MapKind::Diverging),
    ("prgn", colorous::PURPLE_GREEN, MapKind::Diverging),
    ("rdylbu", colorous::RED_YELLOW_BLUE, MapKind::Diverging),
    ("spectral", colorous::SPECTRAL, MapKind::Diverging),
    ("rainbow", colorous::RAINBOW, MapKind::Rainbow),
    ("turbo", colorous::TURBO, MapKind::Rainbow),
    ("sinebow", colorous::SINEBOW, MapKind::Rainbow),
];

const CONTINUOUS_NAMES: [&str; 21] = [
    "viridis", "magma", "inferno", "plasma", "cividis", "blues", "greens", "greys", "oranges", "purples", "reds",
    "rdbu", "brbg", "puor", "piyg", "prgn", "rdylbu", "spectral", "rainbow", "turbo", "sinebow",
];

const CATEGORICAL_NAMES: [&str; 7] =
    ["okabe-ito", "okabe-ito-12", "tableau10", "category10", "set2", "dark2", "paired"];

/// Okabe & Ito (2008), in the order used for successive categories.
const OKABE_ITO: [Color; 8] = [
    Color::rgb(0x00, 0x72, 0xb2), // blue
    Color::rgb(0xe6, 0x9f, 0x00), // orange
    Color::rgb(0x00, 0x9e, 0x73), // bluish green
    Color::rgb(0xd5, 0x5e, 0x00), // vermillion
    Color::rgb(0xcc, 0x79, 0xa7), // reddish purple
    Color::rgb(0x56, 0xb4, 0xe9), // sky blue
    Color::rgb(0xf0, 0xe4, 0x42), // yellow
    Color::rgb(0x00, 0x00, 0x00), // black
];

/// Okabe–Ito followed by four colours chosen for dataink (a greedy farthest-point search over
/// the sRGB cube, keeping lightness 25–85 and chroma ≥ 20 so marks stand off a white page): each
/// added colour is at least ΔE00 14.5 from every other colour of the twelve with normal vision,
/// simulated protanopia and simulated deuteranopia, so the palette stays above lint rule CL003's
/// threshold (the closest pair is still Okabe–Ito's orange and yellow, 11.6). The default for
/// more than eight treemap or hyperbolic-tree branches.
const OKABE_ITO_12: [Color; 12] = [
    OKABE_ITO[0],
    OKABE_ITO[1],
    OKABE_ITO[2],
    OKABE_ITO[3],
    OKABE_ITO[4],
    OKABE_ITO[5],
    OKABE_ITO[6],
    OKABE_ITO[7],
    Color::rgb(0x77, 0x22, 0x00), // dark brown
    Color::rgb(0x77, 0x33, 0x55), // plum
    Color::rgb(0x11, 0x00, 0xcc), // ultramarine
    Color::rgb(0xdd, 0xcc, 0x99), // sand
];

/// A continuous colour map from 0..=1 to colours.
#[derive(Clone, Debug)]
pub struct ContinuousMap {
    name: String,
    gradient: colorous::Gradient,
    reversed: bool,
    kind: MapKind,
    /// The part of the gradient used, so that a map can start past its lightest colour.
    start: f64,
}

impl ContinuousMap {
    /// The same map starting at `start` (0 to 1) of the way along it, e.g. so the lowest
    /// values of thin lines are not drawn in near-white.
    pub fn starting_at(mut self, start: f64) -> ContinuousMap {
        self.start = start.clamp(0.0, 0.9);
        self
    }

    /// The colour at `t`, clamped to 0..=1 (±∞ go to the ends); NaN gives [`MISSING`].
    pub fn at(&self, t: f64) -> Color {
        if t.is_nan() {
            return MISSING;
        }
        let t = self.start + (1.0 - self.start) * t.clamp(0.0, 1.0);
        let t = if self.reversed { 1.0 - t } else { t };
        let c = self.gradient.eval_continuous(t);
        Color::rgb(c.r, c.g, c.b)
    }

    /// The canonical name, e.g. `viridis` or `rdbu_r`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether the map diverges from a light midpoint (for values around a centre).
    pub fn is_diverging(&self) -> bool {
        self.kind == MapKind::Diverging
    }

    /// Whether the map cycles through the hues (`rainbow`, `turbo`, `sinebow`): unsuited to
    /// ordered values, because its lightness is not monotonic.
    pub fn is_rainbow(&self) -> bool {
        self.kind == MapKind::Rainbow
    }

    /// What the map is for: sequential, diverging or rainbow.
    pub fn kind(&self) -> MapKind {
        self.kind
    }

    /// Whether this is the `_r` form of a map.
    pub fn is_reversed(&self) -> bool {
        self.reversed
    }
}

/// The continuous map called `name` (case-insensitive; a `_r` suffix reverses it), if known.
pub fn continuous(name: &str) -> Option<ContinuousMap> {
    let lower = name.trim().to_ascii_lowercase();
    let (base, reversed) = match lower.strip_suffix("_r") {
        Some(base) => (base, true),
        None => (lower.as_str(), false),
    };
    let base = if base == "grays" { "greys" } else { base };
    let (canonical, gradient, kind) = CONTINUOUS.iter().find(|(n, _, _)| *n == base)?;
    let name = if reversed { format!("{canonical}_r") } else { canonical.to_string() };
    Some(ContinuousMap { name, gradient: *gradient, reversed, kind: *kind, start: 0.0 })
}

/// The colours of the categorical palette called `name` (case-insensitive), if known.
pub fn categorical(name: &str) -> Option<Vec<Color>> {
    let from = |cs: &[colorous::Color]| cs.iter().map(|c| Color::rgb(c.r, c.g, c.b)).collect();
    match name.trim().to_ascii_lowercase().as_str() {
        "okabe-ito" | "okabe_ito" | "okabeito" => Some(OKABE_ITO.to_vec()),
        "okabe-ito-12" | "okabe_ito_12" => Some(OKABE_ITO_12.to_vec()),
        "tableau10" => Some(from(&colorous::TABLEAU10)),
        "category10" => Some(from(&colorous::CATEGORY10)),
        "set2" => Some(from(&colorous::SET2)),
        "dark2" => Some(from(&colorous::DARK2)),
        "paired" => Some(from(&colorous::PAIRED)),
        _ => None,
    }
}

/// Names accepted by [`continuous`] (each also with `_r`), for "did you mean" hints.
pub fn continuous_names() -> &'static [&'static str] {
    &CONTINUOUS_NAMES
}

/// Names accepted by [`categorical`], for "did you mean" hints.
pub fn categorical_names() -> &'static [&'static str] {
    &CATEGORICAL_NAMES
}

/// Parse `#rgb`, `#rgba`, `#rrggbb`, `#rrggbbaa` or a common CSS colour name (case-insensitive,
/// e.g. `steelblue`, `grey`/`gray`, `transparent`).
pub fn parse_color(s: &str) -> Option<Color> {
    let s = s.trim();
    match s.strip_prefix('#') {
        Some(hex) => parse_hex(hex),
        None => named(&s.to_ascii_lowercase()),
    }
}

fn parse_hex(hex: &str) -> Option<Color> {
    let digits: Vec<u8> = hex.chars().map(|c| c.to_digit(16).map(|d| d as u8)).collect::<Option<_>>()?;
    let pair = |i: usize| Some(digits.get(i)? * 16 + digits.get(i + 1)?);
    let single = |i: usize| Some(digits.get(i)? * 17);
    let (r, g, b, a) = match digits.len() {
        3 => (single(0)?, single(1)?, single(2)?, 255),
        4 => (single(0)?, single(1)?, single(2)?, single(3)?),
        6 => (pair(0)?, pair(2)?, pair(4)?, 255),
        8 => (pair(0)?, pair(2)?, pair(4)?, pair(6)?),
        _ => return None,
    };
    Some(Color { r, g, b, a })
}

/// Common CSS named colours (values from CSS Color Module Level 4).
fn named(name: &str) -> Option<Color> {
    let rgb = match name {
        "black" => 0x000000,
        "white" => 0xffffff,
        "grey" | "gray" => 0x808080,
        "darkgrey" | "darkgray" => 0xa9a9a9,
        "dimgrey" | "dimgray" => 0x696969,
        "lightgrey" | "lightgray" => 0xd3d3d3,
        "silver" => 0xc0c0c0,
        "gainsboro" => 0xdcdcdc,
        "whitesmoke" => 0xf5f5f5,
        "red" => 0xff0000,
        "darkred" => 0x8b0000,
        "crimson" => 0xdc143c,
        "firebrick" => 0xb22222,
        "salmon" => 0xfa8072,
        "tomato" => 0xff6347,
        "coral" => 0xff7f50,
        "orange" => 0xffa500,
        "darkorange" => 0xff8c00,
        "gold" => 0xffd700,
        "yellow" => 0xffff00,
        "khaki" => 0xf0e68c,
        "green" => 0x008000,
        "darkgreen" => 0x006400,
        "lime" => 0x00ff00,
        "limegreen" => 0x32cd32,
        "forestgreen" => 0x228b22,
        "seagreen" => 0x2e8b57,
        "olive" => 0x808000,
        "teal" => 0x008080,
        "cyan" | "aqua" => 0x00ffff,
        "turquoise" => 0x40e0d0,
        "blue" => 0x0000ff,
        "navy" => 0x000080,
        "darkblue" => 0x00008b,
        "royalblue" => 0x4169e1,
        "steelblue" => 0x4682b4,
        "skyblue" => 0x87ceeb,
        "lightblue" => 0xadd8e6,
        "dodgerblue" => 0x1e90ff,
        "slategrey" | "slategray" => 0x708090,
        "purple" => 0x800080,
        "indigo" => 0x4b0082,
        "violet" => 0xee82ee,
        "magenta" | "fuchsia" => 0xff00ff,
        "orchid" => 0xda70d6,
        "pink" => 0xffc0cb,
        "hotpink" => 0xff69b4,
        "brown" => 0xa52a2a,
        "chocolate" => 0xd2691e,
        "tan" => 0xd2b48c,
        "beige" => 0xf5f5dc,
        "maroon" => 0x800000,
        "transparent" => return Some(Color::TRANSPARENT),
        _ => return None,
    };
    let [_, r, g, b] = u32::to_be_bytes(rgb);
    Some(Color::rgb(r, g, b))
}

/// `color` mixed with white: `amount` 0 keeps it, 1 gives white.
pub fn lighten(color: Color, amount: f64) -> Color {
    let mix = |c: u8| (c as f64 + (255.0 - c as f64) * amount).round() as u8;
    Color { r: mix(color.r), g: mix(color.g), b: mix(color.b), a: color.a }
}

/// `color` mixed with black: `amount` 0 keeps it, 1 gives black.
pub fn darken(color: Color, amount: f64) -> Color {
    let mix = |c: u8| (c as f64 * (1.0 - amount)).round() as u8;
    Color { r: mix(color.r), g: mix(color.g), b: mix(color.b), a: color.a }
}

/// WCAG relative luminance of an opaque colour (0 black, 1 white).
pub fn relative_luminance(color: Color) -> f64 {
    let [r, g, b] = crate::guide::colour_science::linear_rgb(color);
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// WCAG contrast ratio of two colours (1 to 21).
pub fn contrast_ratio(a: Color, b: Color) -> f64 {
    let (la, lb) = (relative_luminance(a), relative_luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// Black or white, whichever contrasts more with `background`: text drawn on a filled mark.
pub fn text_color_on(background: Color) -> Color {
    // Pure black and white: one of them contrasts at least 4.58:1 with any colour (WCAG AA).
    let dark = Color::rgb(0, 0, 0);
    if contrast_ratio(dark, background) >= contrast_ratio(Color::rgb(255, 255, 255), background) {
        dark
    } else {
        Color::rgb(255, 255, 255)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_endpoints_and_reversal() {
        let v = continuous("viridis").unwrap();
        assert_eq!(v.at(0.0).hex(), "#440154");
        assert_eq!(v.at(1.0).hex(), "#fde725");
        assert_eq!(v.at(-3.0), v.at(0.0));
        assert_eq!(v.at(f64::INFINITY), v.at(1.0));
        assert_eq!(v.at(f64::NAN), MISSING);
        let r = continuous("Viridis_R").unwrap();
        assert_eq!(r.name(), "viridis_r");
        assert!(r.is_reversed() && !v.is_reversed());
        assert_eq!(r.at(0.0).hex(), "#fde725");
        assert_eq!(r.at(0.3), v.at(0.7));
    }

    #[test]
    fn diverging_maps_are_light_in_the_middle() {
        for name in ["rdbu", "brbg", "puor", "piyg", "prgn", "rdylbu", "spectral"] {
            let m = continuous(name).unwrap();
            assert!(m.is_diverging() && !m.is_rainbow(), "{name}");
            let mid = m.at(0.5);
            let end = m.at(0.0);
            let lightness = |c: Color| c.r as u32 + c.g as u32 + c.b as u32;
            assert!(lightness(mid) > 650, "{name} midpoint {}", mid.hex());
            assert!(lightness(mid) > lightness(end) + 150, "{name}");
        }
        // colorous interpolates RdBu with a B-spline: the midpoint is #f1efed, near white.
        let mid = continuous("rdbu").unwrap().at(0.5);
        assert!(mid.r >= 0xe8 && mid.g >= 0xe8 && mid.b >= 0xe8, "{}", mid.hex());
        assert!(!continuous("blues").unwrap().is_diverging());
    }

    #[test]
    fn rainbow_maps_are_marked_and_their_lightness_is_not_monotonic() {
        use super::super::colour_science::lab;
        // L* along the map, in 64 steps.
        let lightness = |m: &ContinuousMap| (0..=64).map(|i| lab(m.at(i as f64 / 64.0)).l).collect::<Vec<_>>();
        let monotonic = |ls: &[f64]| {
            let up = ls.windows(2).all(|w| w[1] >= w[0] - 0.5);
            let down = ls.windows(2).all(|w| w[1] <= w[0] + 0.5);
            up || down
        };
        for name in continuous_names() {
            let m = continuous(name).unwrap();
            let ls = lightness(&m);
            match m.kind() {
                MapKind::Sequential => assert!(monotonic(&ls), "{name} should be monotonic in L*"),
                MapKind::Rainbow => {
                    assert!(m.is_rainbow() && !m.is_diverging(), "{name}");
                    // Lightness rises and falls: the reason they mislead on ordered values.
                    assert!(!monotonic(&ls), "{name} is monotonic in L*");
                }
                MapKind::Diverging => assert!(!m.is_rainbow(), "{name}"),
            }
        }
        for name in ["rainbow", "Turbo", "sinebow_r"] {
            assert!(continuous(name).is_some_and(|m| m.is_rainbow()), "{name}");
        }
        assert_eq!(continuous("turbo_r").unwrap().name(), "turbo_r");
        assert!(!continuous("viridis").unwrap().is_rainbow());
        let hint = crate::spec::suggest::hint("rainbw", continuous_names(), "continuous schemes", false);
        assert!(hint.starts_with("did you mean `rainbow`?"), "{hint}");
    }

    #[test]
    fn every_listed_name_resolves() {
        for name in continuous_names() {
            assert!(continuous(name).is_some(), "{name}");
            assert!(continuous(&format!("{name}_r")).is_some(), "{name}_r");
        }
        for name in categorical_names() {
            assert!(categorical(name).is_some_and(|p| p.len() >= 8), "{name}");
        }
        assert!(continuous("jet").is_none());
        assert!(continuous("_r").is_none());
        assert!(categorical("rainbow").is_none());
        assert_eq!(continuous(DEFAULT_SEQUENTIAL).unwrap().name(), "viridis");
        assert!(continuous(DEFAULT_DIVERGING).unwrap().is_diverging());
    }

    #[test]
    fn okabe_ito_order() {
        let p = categorical(DEFAULT_CATEGORICAL).unwrap();
        let hex: Vec<String> = p.iter().map(|c| c.hex()).collect();
        assert_eq!(hex, ["#0072b2", "#e69f00", "#009e73", "#d55e00", "#cc79a7", "#56b4e9", "#f0e442", "#000000"]);
        assert_eq!(categorical("tableau10").unwrap()[0].hex(), "#4e79a7");
        assert_eq!(categorical("category10").unwrap()[1].hex(), "#ff7f0e");
    }

    #[test]
    fn parsing_colours() {
        assert_eq!(parse_color("#fff"), Some(Color::WHITE));
        assert_eq!(parse_color("#1A2b3C"), Some(Color::rgb(0x1a, 0x2b, 0x3c)));
        assert_eq!(parse_color("#00000080"), Some(Color { r: 0, g: 0, b: 0, a: 0x80 }));
        assert_eq!(parse_color("#f008"), Some(Color { r: 255, g: 0, b: 0, a: 0x88 }));
        assert_eq!(parse_color(" SteelBlue "), Some(Color::rgb(0x46, 0x82, 0xb4)));
        assert_eq!(parse_color("grey"), parse_color("gray"));
        assert_eq!(parse_color("darkgrey"), Some(Color::rgb(0xa9, 0xa9, 0xa9)));
        assert_eq!(parse_color("transparent"), Some(Color::TRANSPARENT));
        for bad in ["", "#", "#ff", "#fffff", "#ggg", "#ééé", "#123456789", "notacolour", "rgb(1,2,3)"] {
            assert_eq!(parse_color(bad), None, "{bad}");
        }
    }

    #[test]
    fn contrast_follows_wcag() {
        let (black, white) = (Color::rgb(0, 0, 0), Color::rgb(255, 255, 255));
        assert!((contrast_ratio(black, white) - 21.0).abs() < 1e-9);
        // WCAG's worked value: #777777 on white is 4.48:1.
        assert!((contrast_ratio(Color::rgb(0x77, 0x77, 0x77), white) - 4.48).abs() < 0.01);
        assert_eq!(text_color_on(Color::rgb(0, 0x72, 0xb2)), white);
        assert_ne!(text_color_on(Color::rgb(0xf0, 0xe4, 0x42)), white);
        assert_eq!(lighten(black, 1.0), white);
        assert_eq!(darken(white, 1.0), black);
    }
}
