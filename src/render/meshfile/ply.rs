//! PLY, binary little-endian 1.0: every surface's vertices (position, normal, RGBA) in one
//! vertex element and their triangles in one face element, indices offset per surface.

use super::{WorldMesh, writable};

/// The meshes as one PLY file.
pub fn to_ply(meshes: &[WorldMesh]) -> Vec<u8> {
    let meshes: Vec<&WorldMesh> = writable(meshes).collect();
    let vertices: usize = meshes.iter().map(|m| m.positions.len()).sum();
    let faces: usize = meshes.iter().map(|m| m.triangles.len()).sum();
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment surfaces: {}\nelement vertex {vertices}\n\
         property float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n\
         element face {faces}\nproperty list uchar uint vertex_indices\nend_header\n",
        names.join("; ").replace(['\n', '\r'], " ")
    )
    .into_bytes();
    for m in &meshes {
        for ((p, n), c) in m.positions.iter().zip(&m.normals).zip(&m.colors) {
            for v in p.iter().chain(n) {
                out.extend_from_slice(&v.to_le_bytes());
            }
            out.extend_from_slice(c);
        }
    }
    let mut offset = 0u32;
    for m in &meshes {
        for t in &m.triangles {
            out.push(3);
            for i in t {
                out.extend_from_slice(&(i + offset).to_le_bytes());
            }
        }
        offset += m.positions.len() as u32;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ply_file_has_its_header_counts_and_little_endian_records() {
        let tri = WorldMesh {
            name: "a".into(),
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            normals: vec![[0.0, 0.0, 1.0]; 3],
            colors: vec![[255, 0, 0, 255]; 3],
            triangles: vec![[0, 1, 2]],
        };
        let bytes = to_ply(&[tri.clone(), WorldMesh { name: "b".into(), ..tri }]);
        let end = b"end_header\n";
        let at = bytes.windows(end.len()).position(|w| w == end).expect("header") + end.len();
        let header = std::str::from_utf8(&bytes[..at]).expect("text header");
        assert!(header.contains("element vertex 6\n") && header.contains("element face 2\n"), "{header}");
        assert!(header.contains("comment surfaces: a; b\n"));
        // 6 vertices of 6 floats and 4 bytes, 2 faces of 1 + 3 × 4 bytes.
        assert_eq!(bytes.len() - at, 6 * 28 + 2 * 13);
        let second_x = f32::from_le_bytes(bytes[at + 28..at + 32].try_into().expect("4 bytes"));
        assert_eq!(second_x, 1.0);
        let last_face = &bytes[bytes.len() - 13..];
        assert_eq!(last_face[0], 3);
        assert_eq!(u32::from_le_bytes(last_face[1..5].try_into().expect("4 bytes")), 3, "offset by the first mesh");
    }
}
