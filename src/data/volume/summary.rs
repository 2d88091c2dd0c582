//! A volume described in a few lines for `dataink data`: its size and voxel type, spacing with
//! its unit, value range, placement in the world and memory.

use std::fmt::Write;

use super::Volume;

/// A number as short text: integers without a fraction, others to 6 significant digits.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if v.abs() < 1e-4 {
        return format!("{v:.3e}");
    }
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v:.0}")
    } else {
        let text = format!("{v:.6}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Bytes as KiB, MiB or GiB.
fn bytes(n: usize) -> String {
    let n = n as f64;
    match n {
        n if n >= 1024.0 * 1024.0 * 1024.0 => format!("{:.1} GiB", n / (1024.0 * 1024.0 * 1024.0)),
        n if n >= 1024.0 * 1024.0 => format!("{:.1} MiB", n / (1024.0 * 1024.0)),
        n if n >= 1024.0 => format!("{:.1} KiB", n / 1024.0),
        n => format!("{n} bytes"),
    }
}

/// The lines describing `volume`, read as `format` (e.g. "NIfTI-1"), each starting with two spaces.
pub fn describe(volume: &Volume) -> String {
    let [nx, ny, nz] = volume.dims();
    let ty = super::type_name(volume.voxels().voxel_type());
    let unit = volume.unit().map_or(String::new(), |u| format!(" {}", u.symbol()));
    let spacing = volume.spacing().map(short);
    let mut out = String::new();
    let _ = writeln!(out, "  dims: {nx} × {ny} × {nz} ({} voxels), stored as {ty}", volume.len());
    let _ = writeln!(out, "  spacing: {} × {} × {}{unit}", spacing[0], spacing[1], spacing[2]);
    let (range, missing) = volume.range();
    let range =
        range.map_or("none (every voxel is missing)".to_string(), |(lo, hi)| format!("{} to {}", short(lo), short(hi)));
    let _ = write!(out, "  values: {range}");
    if missing > 0 {
        let _ = write!(out, ", {missing} missing");
    }
    if let Some(s) = volume.scale() {
        let _ = write!(out, " (stored × {} + {})", short(s.slope), short(s.inter));
    }
    out.push('\n');
    let _ = writeln!(out, "  orientation: {} (voxel axes i, j, k along these world directions)", volume.orientation());
    // Rounding noise of a rotation stored as float32 (1e-8 beside 1.5) is shown as 0.
    let affine = volume.affine();
    let size = affine.iter().flat_map(|row| &row[..3]).fold(0.0f64, |m, v| m.max(v.abs()));
    for (row, axis) in affine.iter().zip(["x", "y", "z"]) {
        let clean = |(c, &v): (usize, &f64)| if c < 3 && v.abs() < size * 1e-6 { 0.0 } else { v };
        let cells: Vec<String> = row.iter().enumerate().map(|c| format!("{:>10}", short(clean(c)))).collect();
        let _ = writeln!(out, "  affine {axis}: [{}]", cells.join(" "));
    }
    let _ = writeln!(out, "  memory: {}", bytes(volume.voxels().memory_bytes()));
    out
}

#[cfg(test)]
mod tests {
    use super::super::{Scale, SpaceUnit, Voxels};
    use super::*;

    #[test]
    fn a_summary_names_size_type_spacing_range_and_memory() {
        let v = Volume::new([2, 1, 2], Voxels::I16(vec![-3, 7, 0, 4]), [0.5, 1.0, 2.5])
            .expect("volume")
            .with_scale(Some(Scale { slope: 2.0, inter: 1.0 }))
            .with_unit(Some(SpaceUnit::Millimetre));
        let text = describe(&v);
        assert!(text.contains("  dims: 2 × 1 × 2 (4 voxels), stored as i16\n"), "{text}");
        assert!(text.contains("  spacing: 0.5 × 1 × 2.5 mm\n"), "{text}");
        assert!(text.contains("  values: -5 to 15 (stored × 2 + 1)\n"), "{text}");
        assert!(text.contains("  orientation: RAS"), "{text}");
        assert!(text.contains("  affine z: [         0          0        2.5          0]"), "{text}");
        assert!(text.contains("  memory: 8 bytes\n"), "{text}");
        assert_eq!(bytes(256 * 1024 * 1024), "256.0 MiB");
        assert_eq!(short(1e-9), "1.000e-9");
        assert_eq!((short(-0.0), short(0.1 + 0.2), short(-1.5)), ("0".into(), "0.3".into(), "-1.5".into()));
    }
}
