//! glTF 2.0 binary (`.glb`): one JSON chunk describing a node, mesh and material per surface
//! (with no surface, the asset alone: glTF forbids empty arrays), and one binary chunk holding,
//! per surface, positions (float VEC3, with the `min` and `max` glTF requires), unit normals
//! (float VEC3), colours (normalised unsigned-byte VEC4, `COLOR_0`) and triangle indices
//! (unsigned int). Materials are double-sided and unlit-looking PBR (metallic 0, rough), `BLEND`
//! when a surface has a translucent vertex. Every chunk and buffer view starts on a 4-byte
//! boundary, as the format requires.

use serde_json::{Value, json};

use super::{WorldMesh, writable};

const MAGIC: u32 = 0x4654_6C67; // "glTF"
const CHUNK_JSON: u32 = 0x4E4F_534A; // "JSON"
const CHUNK_BIN: u32 = 0x004E_4942; // "BIN\0"
const FLOAT: u32 = 5126;
const UNSIGNED_BYTE: u32 = 5121;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Collects the binary chunk and the buffer views and accessors pointing into it.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    /// Appends `bytes` as a buffer view for `target` and an accessor over it; returns the
    /// accessor's index.
    fn add(&mut self, bytes: &[u8], target: u32, mut accessor: Value) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let view = self.views.len();
        self.views.push(json!({
            "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len(), "target": target
        }));
        self.bin.extend_from_slice(bytes);
        accessor["bufferView"] = json!(view);
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }
}

fn floats(values: &[[f32; 3]]) -> Vec<u8> {
    values.iter().flatten().flat_map(|v| v.to_le_bytes()).collect()
}

/// The meshes as one glTF 2.0 binary file.
pub fn to_glb(meshes: &[WorldMesh]) -> Vec<u8> {
    let mut b = Builder::default();
    let (mut nodes, mut gltf_meshes, mut materials) = (Vec::new(), Vec::new(), Vec::new());
    for (k, m) in writable(meshes).enumerate() {
        let (lo, hi) = m.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
        let count = m.positions.len();
        let position = b.add(
            &floats(&m.positions),
            ARRAY_BUFFER,
            json!({ "componentType": FLOAT, "count": count, "type": "VEC3", "min": lo, "max": hi }),
        );
        let normal =
            b.add(&floats(&m.normals), ARRAY_BUFFER, json!({ "componentType": FLOAT, "count": count, "type": "VEC3" }));
        let colours: Vec<u8> = m.colors.iter().flatten().copied().collect();
        let colour = b.add(
            &colours,
            ARRAY_BUFFER,
            json!({ "componentType": UNSIGNED_BYTE, "normalized": true, "count": count, "type": "VEC4" }),
        );
        let indices: Vec<u8> = m.triangles.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
        let index = b.add(
            &indices,
            ELEMENT_ARRAY_BUFFER,
            json!({ "componentType": UNSIGNED_INT, "count": m.triangles.len() * 3, "type": "SCALAR" }),
        );
        let translucent = m.colors.iter().any(|c| c[3] < 255);
        materials.push(json!({
            "name": m.name,
            "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9 },
            "doubleSided": true,
            "alphaMode": if translucent { "BLEND" } else { "OPAQUE" },
        }));
        gltf_meshes.push(json!({
            "name": m.name,
            "primitives": [{
                "attributes": { "POSITION": position, "NORMAL": normal, "COLOR_0": colour },
                "indices": index, "material": k, "mode": 4
            }]
        }));
        nodes.push(json!({ "name": m.name, "mesh": k }));
    }
    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    let node_ids: Vec<usize> = (0..nodes.len()).collect();
    let mut doc = json!({ "asset": { "version": "2.0", "generator": "dataink" } });
    if !gltf_meshes.is_empty() {
        doc["scene"] = json!(0);
        doc["scenes"] = json!([{ "nodes": node_ids }]);
        doc["nodes"] = json!(nodes);
        doc["meshes"] = json!(gltf_meshes);
        doc["materials"] = json!(materials);
        doc["accessors"] = json!(b.accessors);
        doc["bufferViews"] = json!(b.views);
        doc["buffers"] = json!([{ "byteLength": b.bin.len() }]);
    }
    let mut text = doc.to_string().into_bytes();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let bin_chunk = if b.bin.is_empty() { 0 } else { 8 + b.bin.len() };
    let total = 12 + 8 + text.len() + bin_chunk;
    let mut out = Vec::with_capacity(total);
    for word in [MAGIC, 2, total as u32, text.len() as u32, CHUNK_JSON] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&text);
    if !b.bin.is_empty() {
        out.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(&b.bin);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"))
    }

    #[test]
    fn a_glb_file_reads_back_to_its_meshes() {
        let quad = WorldMesh {
            name: "iso = 1".into(),
            positions: vec![[0.0, 0.0, 0.0], [2.0, 0.0, -1.0], [2.0, 3.0, 0.5], [0.0, 3.0, 0.0]],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            colors: vec![[200, 100, 50, 128]; 4],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let glb = to_glb(&[quad.clone(), WorldMesh::default()]);
        assert_eq!((word(&glb, 0), word(&glb, 4), word(&glb, 8) as usize), (MAGIC, 2, glb.len()));
        let json_len = word(&glb, 12) as usize;
        assert_eq!((json_len % 4, word(&glb, 16)), (0, CHUNK_JSON));
        let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
        let bin_at = 20 + json_len;
        assert_eq!(word(&glb, bin_at + 4), CHUNK_BIN);
        let bin = &glb[bin_at + 8..bin_at + 8 + word(&glb, bin_at) as usize];
        assert_eq!(doc["buffers"][0]["byteLength"], bin.len());
        assert_eq!(doc["meshes"].as_array().map(Vec::len), Some(1), "the empty mesh is left out");
        assert_eq!(doc["materials"][0]["alphaMode"], "BLEND");
        let prim = &doc["meshes"][0]["primitives"][0];
        let accessor = |name: &str| &doc["accessors"][prim["attributes"][name].as_u64().expect("index") as usize];
        let pos = accessor("POSITION");
        assert_eq!(pos["min"], json!([0.0, 0.0, -1.0]));
        assert_eq!(pos["max"], json!([2.0, 3.0, 0.5]));
        // The positions read back from the binary chunk through their buffer view.
        let view = &doc["bufferViews"][pos["bufferView"].as_u64().expect("view") as usize];
        let (off, len) =
            (view["byteOffset"].as_u64().expect("offset") as usize, view["byteLength"].as_u64().expect("len") as usize);
        assert_eq!(off % 4, 0);
        let back: Vec<f32> =
            bin[off..off + len].chunks(4).map(|c| f32::from_le_bytes(c.try_into().expect("4"))).collect();
        assert_eq!(back, quad.positions.iter().flatten().copied().collect::<Vec<f32>>());
        let idx = &doc["accessors"][prim["indices"].as_u64().expect("indices") as usize];
        assert_eq!((idx["count"].as_u64(), idx["componentType"].as_u64()), (Some(6), Some(u64::from(UNSIGNED_INT))));
        assert_eq!(accessor("COLOR_0")["normalized"], true);
    }
}
