//! `KHR_draco_mesh_compression`: a primitive whose triangles and attributes are one Draco
//! stream in a buffer view, decoded by the `draco-core` crate under limits that match the
//! scene's mesh budget. The extension names, for each glTF attribute, the Draco attribute
//! (by unique id) that holds it.

use crate::limits::Limits;
use draco_core::{DataType, DecodeLimits, DecoderBuffer, MeshDecoder, PointAttribute};
use glam::{Vec2, Vec3, Vec4};
use lucent::Rgb;
use lucent::shape::Mesh;
use serde_json::Value;

/// Most bytes of decoded attribute values one stream may give.
const MAX_DECODED_BYTES: u64 = 1 << 30;

/// The mesh of the Draco stream `bytes`, with the attributes `attributes` (the extension's
/// `{"POSITION": id, …}`) names: positions, and when named, normals, the texture coordinates
/// of set `uv_set`, `COLOR_0` and tangents. Other attributes (joints, weights, other sets) are
/// not read from the stream.
pub(super) fn decode(bytes: &[u8], attributes: &Value, uv_set: u32) -> Result<Mesh, String> {
    let limits = DecodeLimits::default()
        .with_max_points(Limits::DEFAULT.geometry)
        .with_max_faces(Limits::DEFAULT.geometry)
        .with_max_decoded_bytes(MAX_DECODED_BYTES);
    let mut buffer = DecoderBuffer::new(bytes).with_limits(limits);
    let mut mesh = draco_core::Mesh::new();
    MeshDecoder::new()
        .decode(&mut buffer, &mut mesh)
        .map_err(|e| format!("its Draco stream cannot be decoded: {e}"))?;
    let n = mesh.num_points();
    let attribute = |name: &str| -> Result<Option<&PointAttribute>, String> {
        let Some(id) = attributes.get(name) else {
            return Ok(None);
        };
        let id = id
            .as_u64()
            .and_then(|id| u32::try_from(id).ok())
            .ok_or_else(|| format!("its Draco attribute id for {name} is not a number"))?;
        mesh.attribute_by_unique_id(id)
            .map(Some)
            .ok_or_else(|| format!("its Draco stream has no attribute {id} (for {name})"))
    };
    let values = |a: &PointAttribute, width: usize| -> Result<Vec<f32>, String> {
        let scale = match (a.normalized(), a.data_type()) {
            (false, _) => 1.0,
            (true, DataType::Uint8) => 1.0 / 255.0,
            (true, DataType::Int8) => 1.0 / 127.0,
            (true, DataType::Uint16) => 1.0 / 65535.0,
            (true, DataType::Int16) => 1.0 / 32767.0,
            (true, other) => return Err(format!("a normalised Draco attribute of {other:?}")),
        };
        let v: Vec<f32> = a
            .read_f32s(n, width)
            .into_iter()
            .map(|x| x * scale)
            .collect();
        if v.iter().all(|x| x.is_finite()) {
            Ok(v)
        } else {
            Err("its Draco stream holds a number that is not finite".into())
        }
    };
    let position = attribute("POSITION")?.ok_or("its Draco extension names no POSITION")?;
    let positions: Vec<Vec3> = values(position, 3)?
        .chunks_exact(3)
        .map(Vec3::from_slice)
        .collect();
    let mut triangles = Vec::with_capacity(mesh.num_faces());
    for face in mesh.faces() {
        let t = face.map(|p| p.0);
        if t.iter().any(|&i| i as usize >= n) {
            return Err(format!("a Draco face names a point beyond its {n}"));
        }
        triangles.push(t);
    }
    let mut out = Mesh::new(positions, triangles);
    if let Some(a) = attribute("NORMAL")? {
        out.normals = values(a, 3)?
            .chunks_exact(3)
            .map(|c| Vec3::from_slice(c).try_normalize().unwrap_or(Vec3::Z))
            .collect();
    }
    if let Some(a) = attribute(&format!("TEXCOORD_{uv_set}"))? {
        out.uvs = values(a, 2)?
            .chunks_exact(2)
            .map(Vec2::from_slice)
            .collect();
    }
    if let Some(a) = attribute("COLOR_0")? {
        out.colors = values(a, 3)?
            .chunks_exact(3)
            .map(|c| Rgb::new(c[0].max(0.0), c[1].max(0.0), c[2].max(0.0)))
            .collect();
    }
    if let Some(a) = attribute("TANGENT")? {
        out.tangents = values(a, 4)?
            .chunks_exact(4)
            .map(|c| {
                let t = Vec3::from_slice(&c[..3]).try_normalize().unwrap_or(Vec3::X);
                t.extend(if c[3] < 0.0 { -1.0 } else { 1.0 })
            })
            .collect::<Vec<Vec4>>();
    }
    Ok(out)
}
