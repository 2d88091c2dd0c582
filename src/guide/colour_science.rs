//! Colour science for the colour lint rules: sRGB to CIELAB, the CIEDE2000 colour difference,
//! and simulated dichromatic vision. Pure functions on `f64`s, each checked against published
//! reference values in the tests below.
//!
//! - **sRGB → linear → XYZ → CIELAB.** The sRGB transfer function of IEC 61966-2-1; the
//!   linear-sRGB to XYZ matrix and the D65 white (0.95047, 1, 1.08883) as Lindbloom tabulates
//!   them, the pair most published CIELAB values of sRGB colours are computed with (sRGB red is
//!   L\* 53.2408, a\* 80.0925, b\* 67.2032); the CIE 1976 L\*a\*b\* formulas with the CIE's exact
//!   constants (ε = 216/24389, κ = 24389/27).
//! - **CIEDE2000** (CIE 142-2001) with k_L = k_C = k_H = 1, following the implementation notes
//!   of Sharma, Wu & Dalal (2005), whose test pairs it reproduces to 1e-4.
//! - **Colour-vision deficiencies.** Protanopia and deuteranopia simulated with the matrices of
//!   Machado, Oliveira & Fernandes (2009) at severity 1.0, applied to linear sRGB. Chosen over
//!   Viénot, Brettel & Mollon (1999) because the same model gives a published matrix for every
//!   severity (anomalous trichromacy too, should a rule need it), it is what colorspacious and
//!   Chromium's vision-deficiency emulation implement, so a finding can be checked with common
//!   tools, and at severity 1.0 it makes the same protan and deutan confusions as the dichromat
//!   models it was compared with in the paper. The fixture `tests/fixtures/cvd.json` (made by
//!   `scripts/cvd_fixture.py` with colorspacious) pins it.

use crate::scene::Color;

/// A colour in CIE 1976 L\*a\*b\* (D65 white, 2° observer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lab {
    /// Lightness, 0 (black) to 100 (the white point).
    pub l: f64,
    /// Green (negative) to red (positive).
    pub a: f64,
    /// Blue (negative) to yellow (positive).
    pub b: f64,
}

/// The D65 white point in XYZ with Y = 1 (Lindbloom's tabulation, matching [`SRGB_TO_XYZ`]).
pub const D65_WHITE: [f64; 3] = [0.95047, 1.0, 1.08883];

/// Linear sRGB to XYZ (D65, Y of white = 1), as Lindbloom tabulates it: each row sums to the
/// corresponding coordinate of [`D65_WHITE`], so sRGB white is L\* 100, a\* = b\* = 0.
pub const SRGB_TO_XYZ: [[f64; 3]; 3] =
    [[0.4124564, 0.3575761, 0.1804375], [0.2126729, 0.7151522, 0.0721750], [0.0193339, 0.1191920, 0.9503041]];

/// A colour-vision deficiency (dichromacy) that [`simulate_linear`] can simulate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Deficiency {
    /// No working long-wavelength (red) cones; about 1 % of men.
    Protanopia,
    /// No working medium-wavelength (green) cones; about 1 % of men (deuteranomaly, its milder
    /// form, about 5 %).
    Deuteranopia,
}

impl Deficiency {
    /// The red–green deficiencies, which together affect about 8 % of men of European descent.
    pub const ALL: [Deficiency; 2] = [Deficiency::Protanopia, Deficiency::Deuteranopia];

    /// The lowercase name, e.g. `deuteranopia`.
    pub fn name(self) -> &'static str {
        match self {
            Deficiency::Protanopia => "protanopia",
            Deficiency::Deuteranopia => "deuteranopia",
        }
    }

    /// The Machado, Oliveira & Fernandes (2009) matrix at severity 1.0, acting on linear sRGB
    /// (from the paper's supplementary table; each row sums to 1 up to its six decimals, so
    /// greys stay grey).
    pub fn matrix(self) -> [[f64; 3]; 3] {
        match self {
            Deficiency::Protanopia => {
                [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216], [-0.003882, -0.048116, 1.051998]]
            }
            Deficiency::Deuteranopia => {
                [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413], [-0.011820, 0.042940, 0.968881]]
            }
        }
    }
}

fn mul(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    let row = |r: &[f64; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    [row(&m[0]), row(&m[1]), row(&m[2])]
}

/// Decode one sRGB channel (0..=1) to linear light (IEC 61966-2-1).
pub fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 { v / 12.92 } else { ((v + 0.055) / 1.055).powf(2.4) }
}

/// Encode linear light as an sRGB channel, the inverse of [`srgb_to_linear`]. Values outside
/// 0..=1 are not clipped: negative values continue the linear segment, values above 1 the
/// power law.
pub fn linear_to_srgb(v: f64) -> f64 {
    if v <= 0.0031308 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 }
}

/// The linear-light RGB of an 8-bit sRGB colour (alpha ignored), each channel 0..=1.
pub fn linear_rgb(color: Color) -> [f64; 3] {
    let c = |v: u8| srgb_to_linear(v as f64 / 255.0);
    [c(color.r), c(color.g), c(color.b)]
}

/// Linear sRGB to CIE XYZ (D65, Y of white = 1).
pub fn linear_to_xyz(rgb: [f64; 3]) -> [f64; 3] {
    mul(&SRGB_TO_XYZ, rgb)
}

/// CIE XYZ (Y of white = 1) to CIELAB relative to [`D65_WHITE`].
pub fn xyz_to_lab(xyz: [f64; 3]) -> Lab {
    const EPSILON: f64 = 216.0 / 24389.0;
    const KAPPA: f64 = 24389.0 / 27.0;
    let f = |t: f64| if t > EPSILON { t.cbrt() } else { (KAPPA * t + 16.0) / 116.0 };
    let [fx, fy, fz] = [f(xyz[0] / D65_WHITE[0]), f(xyz[1] / D65_WHITE[1]), f(xyz[2] / D65_WHITE[2])];
    Lab { l: 116.0 * fy - 16.0, a: 500.0 * (fx - fy), b: 200.0 * (fy - fz) }
}

/// CIELAB of a linear-sRGB colour.
pub fn lab_from_linear(rgb: [f64; 3]) -> Lab {
    xyz_to_lab(linear_to_xyz(rgb))
}

/// CIELAB of an 8-bit sRGB colour (alpha ignored).
pub fn lab(color: Color) -> Lab {
    lab_from_linear(linear_rgb(color))
}

/// The CIEDE2000 colour difference ΔE₀₀ of two CIELAB colours (k_L = k_C = k_H = 1). About 1 is
/// a just-noticeable difference between large patches side by side; marks as small as chart
/// symbols need several times that to be told apart at a glance. Symmetric, and exactly 0 for
/// equal colours.
pub fn ciede2000(x: Lab, y: Lab) -> f64 {
    const POW25_7: f64 = 6_103_515_625.0; // 25⁷
    let c7 = |c: f64| {
        let c7 = c.powi(7);
        (c7 / (c7 + POW25_7)).sqrt()
    };
    let hue = |b: f64, a: f64| {
        if a == 0.0 && b == 0.0 { 0.0 } else { b.atan2(a).to_degrees().rem_euclid(360.0) }
    };

    let c_bar = (x.a.hypot(x.b) + y.a.hypot(y.b)) / 2.0;
    let g = 0.5 * (1.0 - c7(c_bar));
    let (a1, a2) = ((1.0 + g) * x.a, (1.0 + g) * y.a);
    let (c1, c2) = (a1.hypot(x.b), a2.hypot(y.b));
    let (h1, h2) = (hue(x.b, a1), hue(y.b, a2));

    let dl = y.l - x.l;
    let dc = c2 - c1;
    let chroma_product = c1 * c2;
    let dh = if chroma_product == 0.0 {
        0.0
    } else if h2 - h1 > 180.0 {
        h2 - h1 - 360.0
    } else if h2 - h1 < -180.0 {
        h2 - h1 + 360.0
    } else {
        h2 - h1
    };
    let d_big_h = 2.0 * chroma_product.sqrt() * (dh.to_radians() / 2.0).sin();

    let l_bar = (x.l + y.l) / 2.0;
    let c_bar = (c1 + c2) / 2.0;
    let h_bar = if chroma_product == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        (h1 + h2) / 2.0
    } else if h1 + h2 < 360.0 {
        (h1 + h2 + 360.0) / 2.0
    } else {
        (h1 + h2 - 360.0) / 2.0
    };

    let cos = |deg: f64| deg.to_radians().cos();
    let t = 1.0 - 0.17 * cos(h_bar - 30.0) + 0.24 * cos(2.0 * h_bar) + 0.32 * cos(3.0 * h_bar + 6.0)
        - 0.20 * cos(4.0 * h_bar - 63.0);
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
    let r_c = 2.0 * c7(c_bar);
    let l50 = (l_bar - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * c_bar;
    let s_h = 1.0 + 0.015 * c_bar * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;

    let (l, c, h) = (dl / s_l, dc / s_c, d_big_h / s_h);
    (l * l + c * c + h * h + r_t * c * h).max(0.0).sqrt()
}

/// A linear-sRGB colour as a dichromat with `deficiency` sees it (Machado et al. 2009, severity
/// 1.0). Not clipped: saturated colours can map slightly outside 0..=1.
pub fn simulate_linear(rgb: [f64; 3], deficiency: Deficiency) -> [f64; 3] {
    mul(&deficiency.matrix(), rgb)
}

/// An 8-bit sRGB colour as a dichromat with `deficiency` sees it, in linear sRGB clipped to
/// 0..=1 (what a display could show).
pub fn simulate(color: Color, deficiency: Deficiency) -> [f64; 3] {
    simulate_linear(linear_rgb(color), deficiency).map(|v| v.clamp(0.0, 1.0))
}

/// CIELAB of `color` as seen with normal vision (`None`) or with a deficiency.
pub fn lab_seen(color: Color, deficiency: Option<Deficiency>) -> Lab {
    match deficiency {
        None => lab(color),
        Some(d) => lab_from_linear(simulate(color, d)),
    }
}

/// ΔE₀₀ between two 8-bit colours as seen with normal vision (`None`) or with a deficiency.
pub fn difference(x: Color, y: Color, deficiency: Option<Deficiency>) -> f64 {
    ciede2000(lab_seen(x, deficiency), lab_seen(y, deficiency))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lab3(l: f64, a: f64, b: f64) -> Lab {
        Lab { l, a, b }
    }

    /// Table 1 of Sharma, Wu & Dalal (2005), "The CIEDE2000 color-difference formula:
    /// implementation notes, supplementary test data, and mathematical observations", Color
    /// Research & Application 30(1): the 34 pairs and their ΔE₀₀ to four decimals.
    const SHARMA: [([f64; 3], [f64; 3], f64); 34] = [
        ([50.0000, 2.6772, -79.7751], [50.0000, 0.0000, -82.7485], 2.0425),
        ([50.0000, 3.1571, -77.2803], [50.0000, 0.0000, -82.7485], 2.8615),
        ([50.0000, 2.8361, -74.0200], [50.0000, 0.0000, -82.7485], 3.4412),
        ([50.0000, -1.3802, -84.2814], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, -1.1848, -84.8006], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, -0.9009, -85.5211], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, 0.0000, 0.0000], [50.0000, -1.0000, 2.0000], 2.3669),
        ([50.0000, -1.0000, 2.0000], [50.0000, 0.0000, 0.0000], 2.3669),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0009], 7.1792),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0010], 7.1792),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0011], 7.2195),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0012], 7.2195),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0009, -2.4900], 4.8045),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0010, -2.4900], 4.8045),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0011, -2.4900], 4.7461),
        ([50.0000, 2.5000, 0.0000], [50.0000, 0.0000, -2.5000], 4.3065),
        ([50.0000, 2.5000, 0.0000], [73.0000, 25.0000, -18.0000], 27.1492),
        ([50.0000, 2.5000, 0.0000], [61.0000, -5.0000, 29.0000], 22.8977),
        ([50.0000, 2.5000, 0.0000], [56.0000, -27.0000, -3.0000], 31.9030),
        ([50.0000, 2.5000, 0.0000], [58.0000, 24.0000, 15.0000], 19.4535),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.1736, 0.5854], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.2972, 0.0000], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 1.8634, 0.5757], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.2592, 0.3350], 1.0000),
        ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
        ([63.0109, -31.0961, -5.8663], [62.8187, -29.7946, -4.0864], 1.2630),
        ([61.2901, 3.7196, -5.3901], [61.4292, 2.2480, -4.9620], 1.8731),
        ([35.0831, -44.1164, 3.7933], [35.0232, -40.0716, 1.5901], 1.8645),
        ([22.7233, 20.0904, -46.6940], [23.0331, 14.9730, -42.5619], 2.0373),
        ([36.4612, 47.8580, 18.3852], [36.2715, 50.5065, 21.2231], 1.4146),
        ([90.8027, -2.0831, 1.4410], [91.1528, -1.6435, 0.0447], 1.4441),
        ([90.9257, -0.5406, -0.9208], [88.6381, -0.8985, -0.7239], 1.5381),
        ([6.7747, -0.2908, -2.4247], [5.8714, -0.0985, -2.2286], 0.6377),
        ([2.0776, 0.0795, -1.1350], [0.9033, -0.0636, -0.5514], 0.9082),
    ];

    #[test]
    fn ciede2000_matches_sharma_wu_dalal() {
        for (i, (p, q, want)) in SHARMA.iter().enumerate() {
            let (x, y) = (lab3(p[0], p[1], p[2]), lab3(q[0], q[1], q[2]));
            let got = ciede2000(x, y);
            assert!((got - want).abs() < 1e-4, "pair {}: ΔE00 {got:.6}, published {want}", i + 1);
            let back = ciede2000(y, x);
            assert!((got - back).abs() < 1e-12, "pair {}: not symmetric ({got} vs {back})", i + 1);
        }
    }

    #[test]
    fn ciede2000_is_zero_only_for_equal_colours() {
        for c in [lab3(50.0, 10.0, -20.0), lab3(0.0, 0.0, 0.0), lab3(100.0, 0.0, 0.0), lab3(35.0, -44.0, 3.8)] {
            assert_eq!(ciede2000(c, c), 0.0);
        }
        assert!(ciede2000(lab3(50.0, 0.0, 0.0), lab3(51.0, 0.0, 0.0)) > 0.5);
        // Black and white are as different as two colours get: ΔE00 100 (L* only, S_L = 1 at
        // the mean lightness 50; the tabulated matrix puts white at L* 100.000004).
        assert!((ciede2000(lab(Color::BLACK), lab(Color::WHITE)) - 100.0).abs() < 1e-4);
    }

    #[test]
    fn lab_of_the_srgb_primaries_matches_published_values() {
        // Lindbloom's tables (sRGB, D65, 2°), four decimals.
        let published = [
            (Color::rgb(255, 0, 0), [53.2408, 80.0925, 67.2032]),
            (Color::rgb(0, 255, 0), [87.7347, -86.1827, 83.1793]),
            (Color::rgb(0, 0, 255), [32.2970, 79.1875, -107.8602]),
            (Color::rgb(255, 255, 255), [100.0, 0.0, 0.0]),
            (Color::rgb(0, 0, 0), [0.0, 0.0, 0.0]),
        ];
        for (c, [l, a, b]) in published {
            let got = lab(c);
            let ok = (got.l - l).abs() < 1e-4 && (got.a - a).abs() < 1e-4 && (got.b - b).abs() < 1e-4;
            assert!(ok, "{}: {got:?}, published ({l}, {a}, {b})", c.hex());
        }
        // Greys have no chroma, and mid grey #777777 is L* 50.0 to within a tenth.
        for v in [0x20u8, 0x77, 0x80, 0xc8] {
            let g = lab(Color::rgb(v, v, v));
            assert!(g.a.abs() < 1e-4 && g.b.abs() < 1e-4, "{v:#x}: {g:?}");
        }
        assert!((lab(Color::rgb(0x77, 0x77, 0x77)).l - 50.0).abs() < 0.1);
        // Below ε the L* curve is linear: #010101 is L* 0.2742 (Y = 0.000304).
        assert!((lab(Color::rgb(1, 1, 1)).l - 0.2742).abs() < 1e-3);
    }

    #[test]
    fn transfer_function_round_trips() {
        for i in 0..=255u8 {
            let v = i as f64 / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(v)) - v).abs() < 1e-12, "{i}");
        }
        // Out-of-range values continue the curve instead of turning into NaN.
        assert!((linear_to_srgb(-0.01) + 0.1292).abs() < 1e-12);
        assert!(linear_to_srgb(1.2) > 1.0 && linear_to_srgb(1.2).is_finite());
    }

    #[derive(serde::Deserialize)]
    struct Fixture {
        matrices: std::collections::BTreeMap<String, Vec<Vec<String>>>,
        cases: Vec<Case>,
    }

    #[derive(serde::Deserialize)]
    struct Case {
        hex: String,
        protanopia: Vec<String>,
        deuteranopia: Vec<String>,
    }

    fn fixture() -> Fixture {
        serde_json::from_str(include_str!("../../tests/fixtures/cvd.json")).expect("fixture parses")
    }

    fn num(s: &str) -> f64 {
        s.parse().expect("fixture number")
    }

    #[test]
    fn machado_matrices_are_colorspacious_matrices() {
        let f = fixture();
        for d in Deficiency::ALL {
            let theirs = f.matrices.get(d.name()).expect("matrix in fixture");
            for (i, row) in d.matrix().iter().enumerate() {
                for (j, v) in row.iter().enumerate() {
                    assert_eq!(*v, num(&theirs[i][j]), "{} [{i}][{j}]", d.name());
                }
                // Rows sum to 1 (to the table's precision): greys are seen unchanged.
                assert!((row.iter().sum::<f64>() - 1.0).abs() < 2e-6, "{} row {i}", d.name());
            }
        }
    }

    #[test]
    fn simulation_matches_colorspacious_fixture() {
        let f = fixture();
        assert!(f.cases.len() >= 100, "{} cases", f.cases.len());
        let mut out_of_gamut = 0;
        for case in &f.cases {
            let c = crate::guide::color::parse_color(&case.hex).expect("fixture colour");
            for (d, want) in
                [(Deficiency::Protanopia, &case.protanopia), (Deficiency::Deuteranopia, &case.deuteranopia)]
            {
                let got = simulate_linear(linear_rgb(c), d).map(linear_to_srgb);
                for k in 0..3 {
                    let w = num(&want[k]);
                    assert!((got[k] - w).abs() < 1e-9, "{} {}: channel {k} {} vs {w}", case.hex, d.name(), got[k]);
                    out_of_gamut += usize::from(!(0.0..=1.0).contains(&w));
                }
            }
        }
        // The fixture exercises unclipped values too.
        assert!(out_of_gamut > 10, "{out_of_gamut}");
    }

    #[test]
    fn dichromats_confuse_red_and_green_but_not_blue_and_orange() {
        let (red, green) = (Color::rgb(0xd6, 0x27, 0x28), Color::rgb(0x2c, 0xa0, 0x2c));
        let (blue, orange) = (Color::rgb(0x00, 0x72, 0xb2), Color::rgb(0xe6, 0x9f, 0x00));
        let normal = difference(red, green, None);
        for d in Deficiency::ALL {
            let seen = difference(red, green, Some(d));
            assert!(seen < normal / 2.0, "{}: {seen} vs normal {normal}", d.name());
            assert!(difference(blue, orange, Some(d)) > 40.0, "{}", d.name());
            // Greys, black and white are seen unchanged.
            for v in [0u8, 0x80, 0xff] {
                let g = Color::rgb(v, v, v);
                assert!(difference(g, g, Some(d)) == 0.0);
                assert!(ciede2000(lab_seen(g, Some(d)), lab(g)) < 1e-3, "{} {v}", d.name());
            }
        }
        // Clipping keeps every simulated channel displayable.
        for c in [Color::rgb(0xfb, 0xe3, 0x03), Color::rgb(0, 0, 255), Color::rgb(255, 0, 0)] {
            for d in Deficiency::ALL {
                assert!(simulate(c, d).iter().all(|v| (0.0..=1.0).contains(v)));
            }
        }
    }
}
