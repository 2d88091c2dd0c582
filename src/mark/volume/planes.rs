//! The planes a `slice` chart asks for, resolved against its volume: planes along a world axis
//! at given positions or spread evenly through the volume, or oblique planes given by a point and
//! a normal. Every plane must cut the volume; errors point at the spec entry that misses.

use crate::enrich::volume::{Interpolation, Plane, Sampler};
use crate::guide::format::format_value;
use crate::mark::MarkError;
use crate::spec::PathSeg;

use super::slice::{SliceAxis, SliceOptions};

/// Most slices one chart draws.
pub const MAX_SLICES: usize = 64;

/// One plane to draw: where it lies, what its panel is called, where it cuts the volume, and
/// the spec entry that asked for it.
#[derive(Clone, Debug)]
pub struct Slice {
    /// The plane.
    pub plane: Plane,
    /// The panel's heading (`z = 20 mm`, `plane 2`).
    pub label: String,
    /// The polygon the volume's covered box cuts from the plane, in plane coordinates.
    pub outline: Vec<(f64, f64)>,
    /// The names of the plane's two axes (`x` and `y` for an axial slice, `u` and `v` oblique).
    pub axis_names: [&'static str; 2],
}

impl Slice {
    /// The bounds of the outline: `(u0, u1, v0, v1)`.
    pub fn bounds(&self) -> (f64, f64, f64, f64) {
        self.outline
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(a, b, c, d), &(u, v)| {
                (a.min(u), b.max(u), c.min(v), d.max(v))
            })
    }
}

fn axis_index(axis: SliceAxis) -> usize {
    match axis {
        SliceAxis::X => 0,
        SliceAxis::Y => 1,
        SliceAxis::Z => 2,
    }
}

const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The slices of a chart, in panel order.
pub fn resolve(
    options: &SliceOptions,
    sampler: &Sampler<'_>,
    how: Interpolation,
    unit: &str,
) -> Result<Vec<Slice>, MarkError> {
    let corners = sampler.corners(how);
    if let Some(planes) = &options.planes {
        for key in ["axis", "at", "count", "between"] {
            let given = match key {
                "axis" => options.axis.is_some(),
                "at" => options.at.is_some(),
                "count" => options.count.is_some(),
                _ => options.between.is_some(),
            };
            if given {
                return Err(MarkError::at(
                    &[key],
                    format!("`{key}` and `planes` are both given"),
                    "draw slices along an axis (`axis` with `at` or `count`) or oblique `planes`, not both; use two charts for both",
                ));
            }
        }
        check_count(planes.len(), "planes")?;
        return planes
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let path = |key: &str| vec![PathSeg::from("planes"), PathSeg::Index(k), PathSeg::from(key)];
                let plane = Plane::new(p.point, p.normal).map_err(|message| {
                    MarkError::at_path(
                        path("normal"),
                        message,
                        "give a point and a non-zero normal, e.g. { point = [0, 0, 0], normal = [0, 1, 1] }",
                    )
                })?;
                let outline = plane.cut(&corners);
                if outline.is_empty() {
                    return Err(MarkError::at_path(
                        path("point"),
                        format!(
                            "the plane through {} with normal {} misses the volume",
                            triple(p.point),
                            triple(p.normal)
                        ),
                        format!("the volume spans {}", spans(&corners, unit)),
                    ));
                }
                Ok(Slice { plane, label: format!("plane {}", k + 1), outline, axis_names: ["u", "v"] })
            })
            .collect();
    }
    let axis = axis_index(options.axis.unwrap_or(SliceAxis::Z));
    let (lo, hi) = span(&corners, axis);
    let (positions, key) = match (&options.at, options.count) {
        (Some(_), Some(_)) => {
            return Err(MarkError::at(
                &["count"],
                "`at` and `count` are both given",
                "list the positions with `at`, or ask for evenly spaced slices with `count`",
            ));
        }
        (Some(_), None) if options.between.is_some() => {
            return Err(MarkError::at(
                &["between"],
                "`between` is given with `at`",
                "`between` is the range `count` slices spread over; with `at` the positions are given",
            ));
        }
        (Some(at), None) => {
            check_count(at.len(), "at")?;
            (at.clone(), "at")
        }
        (None, count) => {
            let count = count.unwrap_or(1) as usize;
            check_count(count, "count")?;
            let (from, to, ends) = match options.between {
                None => (lo, hi, false),
                Some([a, b]) if a.is_finite() && b.is_finite() && a < b => {
                    let slack = 1e-9 * (hi - lo).abs().max(1.0);
                    if a < lo - slack || b > hi + slack {
                        return Err(MarkError::at(
                            &["between"],
                            format!("between [{}, {}] reaches beyond the volume", format_value(a), format_value(b)),
                            format!(
                                "the volume spans {} from {} to {}{}",
                                AXIS_NAMES[axis],
                                format_value(lo),
                                format_value(hi),
                                if unit.is_empty() { String::new() } else { format!(" {unit}") }
                            ),
                        ));
                    }
                    (a, b, true)
                }
                Some(range) => {
                    return Err(MarkError::at(
                        &["between"],
                        format!("{range:?} is not two increasing numbers"),
                        "give the range the slices spread over, e.g. between = [-40, 70]",
                    ));
                }
            };
            (evenly_spaced(sampler, axis, (from, to), count, ends), "count")
        }
    };
    let others: Vec<usize> = (0..3).filter(|&a| a != axis).collect();
    let axis_names = [AXIS_NAMES[others[0]], AXIS_NAMES[others[1]]];
    positions
        .iter()
        .enumerate()
        .map(|(k, &at)| {
            let label =
                format!("{} = {}{}", AXIS_NAMES[axis], format_value(at), if unit.is_empty() { "" } else { " " });
            let label = format!("{label}{unit}");
            let outline = if at.is_finite() { Plane::along_axis(axis, at).cut(&corners) } else { Vec::new() };
            if outline.is_empty() {
                let path =
                    if key == "at" { vec![PathSeg::from("at"), PathSeg::Index(k)] } else { vec![PathSeg::from(key)] };
                return Err(MarkError::at_path(
                    path,
                    format!("{label} misses the volume"),
                    format!(
                        "the volume spans {} from {} to {}{}",
                        AXIS_NAMES[axis],
                        format_value(lo),
                        format_value(hi),
                        if unit.is_empty() { String::new() } else { format!(" {unit}") }
                    ),
                ));
            }
            Ok(Slice { plane: Plane::along_axis(axis, at), label, outline, axis_names })
        })
        .collect()
}

fn check_count(n: usize, key: &str) -> Result<(), MarkError> {
    if (1..=MAX_SLICES).contains(&n) {
        return Ok(());
    }
    Err(MarkError::at(
        &[key],
        format!("{n} slices asked for; a chart draws 1 to {MAX_SLICES}"),
        "split the slices over several charts",
    ))
}

/// `count` evenly spaced positions along world `axis`: from `lo` to `hi` inclusive when `ends`
/// (the middle for one), else at the middles of `count` equal parts (so no slice lies on the
/// volume's empty outer face). When a voxel axis runs along the world axis each is moved to the
/// nearest voxel plane, so the slices show voxels rather than blends of two planes.
fn evenly_spaced(sampler: &Sampler<'_>, axis: usize, (lo, hi): (f64, f64), count: usize, ends: bool) -> Vec<f64> {
    let affine = sampler.volume().affine();
    let dims = sampler.volume().dims();
    let along = (0..3).find(|&a| {
        let column = [affine[0][a], affine[1][a], affine[2][a]];
        column[axis] != 0.0 && (0..3).all(|w| w == axis || column[w].abs() <= 1e-9 * column[axis].abs())
    });
    (0..count)
        .map(|k| {
            let part = match (ends, count) {
                (true, 2..) => k as f64 / (count - 1) as f64,
                _ => (k as f64 + 0.5) / count as f64,
            };
            let at = lo + (hi - lo) * part;
            match along {
                Some(a) => {
                    let step = affine[axis][a];
                    let index = ((at - affine[axis][3]) / step).round().clamp(0.0, dims[a].saturating_sub(1) as f64);
                    affine[axis][3] + index * step
                }
                None => at,
            }
        })
        .collect()
}

/// The smallest and largest world coordinate along `axis` of the box with `corners`.
fn span(corners: &[[f64; 3]; 8], axis: usize) -> (f64, f64) {
    corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c[axis]), hi.max(c[axis])))
}

fn spans(corners: &[[f64; 3]; 8], unit: &str) -> String {
    let parts: Vec<String> = (0..3)
        .map(|a| {
            let (lo, hi) = span(corners, a);
            format!("{} {} to {}", AXIS_NAMES[a], format_value(lo), format_value(hi))
        })
        .collect();
    let unit = if unit.is_empty() { String::new() } else { format!(" ({unit})") };
    format!("{}{unit}", parts.join(", "))
}

fn triple(p: [f64; 3]) -> String {
    format!("({}, {}, {})", format_value(p[0]), format_value(p[1]), format_value(p[2]))
}
