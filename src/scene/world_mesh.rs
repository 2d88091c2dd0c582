//! Triangle meshes in world coordinates, as 3-D kinds hand them to the mesh file writers
//! (`--format glb`, `ply`, `obj`): unlike a scene's [`super::Mesh`], nothing is projected or lit.

/// One named surface: positions in world units, a unit normal and a colour per vertex, and
/// triangles wound counter-clockwise seen from the side the normals point to.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WorldMesh {
    /// The surface's name (`iso = 300`), kept by formats that name objects.
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit normal per vertex.
    pub normals: Vec<[f32; 3]>,
    /// Straight-alpha RGBA colour per vertex.
    pub colors: Vec<[u8; 4]>,
    /// Triangles as indices into the vertices.
    pub triangles: Vec<[u32; 3]>,
}

impl WorldMesh {
    /// The smallest and largest coordinate along each axis (`None` without vertices).
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            ([lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])], [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])])
        }))
    }

    /// Whether every triangle index names a vertex and every vertex has a normal and a colour.
    pub fn is_consistent(&self) -> bool {
        let n = self.positions.len();
        self.normals.len() == n && self.colors.len() == n && self.triangles.iter().flatten().all(|&i| (i as usize) < n)
    }
}
