//! Wavefront OBJ: one named object per surface, vertices with their colour (`v x y z r g b`, the
//! extension MeshLab and Blender read), normals (`vn`) and faces `f a//a b//b c//c`, indices
//! counted from 1 across the file.

use std::fmt::Write;

use super::{WorldMesh, writable};

/// The meshes as one OBJ file.
pub fn to_obj(meshes: &[WorldMesh]) -> String {
    let mut out = String::from("# dataink surfaces\n");
    let mut offset = 1u64;
    for (k, m) in writable(meshes).enumerate() {
        let name: String = m.name.chars().map(|c| if c.is_whitespace() { '_' } else { c }).collect();
        let _ = writeln!(out, "o {}", if name.is_empty() { format!("surface_{}", k + 1) } else { name });
        for (p, c) in m.positions.iter().zip(&m.colors) {
            let rgb = c.map(|v| f32::from(v) / 255.0);
            let _ = writeln!(out, "v {} {} {} {} {} {}", p[0], p[1], p[2], rgb[0], rgb[1], rgb[2]);
        }
        for n in &m.normals {
            let _ = writeln!(out, "vn {} {} {}", n[0], n[1], n[2]);
        }
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| u64::from(i) + offset);
            let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
        }
        offset += m.positions.len() as u64;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_indices_count_from_one_across_objects() {
        let tri = WorldMesh {
            name: "iso = 3".into(),
            positions: vec![[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, 1.0, 0.0]],
            normals: vec![[0.0, 0.0, 1.0]; 3],
            colors: vec![[255, 0, 0, 255]; 3],
            triangles: vec![[0, 1, 2]],
        };
        let text = to_obj(&[tri.clone(), tri]);
        assert!(text.contains("o iso_=_3\nv 0 0 0 1 0 0\nv 1.5 0 0 1 0 0\n"), "{text}");
        assert!(text.contains("f 1//1 2//2 3//3\n"));
        assert!(text.contains("f 4//4 5//5 6//6\n"));
        assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 6);
    }
}
