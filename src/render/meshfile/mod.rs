//! 3-D surfaces written as files other tools open: glTF 2.0 binary (`glb`: Blender, three.js,
//! ParaView, every web viewer), PLY (binary little-endian: MeshLab, CloudCompare, Open3D) and
//! Wavefront OBJ (text, with per-vertex colours as MeshLab writes them). Several surfaces go into
//! one file: separate meshes in glTF, named objects in OBJ, one vertex list in PLY.

pub mod glb;
pub mod obj;
pub mod ply;

use crate::scene::WorldMesh;

/// The meshes that can be written: consistent ones, empty ones left out.
fn writable(meshes: &[WorldMesh]) -> impl Iterator<Item = &WorldMesh> {
    meshes.iter().filter(|m| m.is_consistent() && !m.triangles.is_empty())
}
