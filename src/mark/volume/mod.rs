//! Kinds drawing 3-D scalar fields: `slice` (planes through a volume as images),
//! `isosurface` (surfaces of constant value, shaded in 3-D) and `volume` (direct volume
//! rendering by ray casting, in `direct`, label volumes in `labels`), with the volume's box as
//! they draw it (`box_frame`).

pub mod box_frame;
pub mod direct;
pub mod inset;
pub mod isosurface;
pub mod labels;
pub mod planes;
pub mod slice;

/// What a volume chart showed of its volume, for the lint rules.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VolumeFacts {
    /// The smallest and largest value that is not missing (`None` when every voxel is).
    pub range: Option<(f64, f64)>,
    /// The iso values the spec asked for (isosurface `levels`).
    pub levels: Vec<f64>,
    /// The share of the voxels that are not missing which the transfer function shows: opacity
    /// of at least [`SHOWN_OPACITY`] per voxel length (composite volume rendering only).
    pub shown: Option<f64>,
    /// Whether colours stand for values or labels that a legend must decode.
    pub coloured: bool,
}

/// The opacity per voxel length from which a transfer function counts a voxel as shown: one
/// 8-bit level.
pub const SHOWN_OPACITY: f64 = 1.0 / 255.0;
