//! Reading accessors: typed, strided views into buffers, optionally sparse.
//!
//! Before anything is allocated, the bytes an accessor needs (`offset + stride·(count − 1) +
//! element size`) are checked against its buffer view, and the view against the bytes its
//! buffer really holds; an accessor without a view (zeros, with its sparse elements replaced)
//! is capped at [`MAX_ZERO_FILLED`] elements. So reading an accessor allocates at most a small
//! multiple of the bytes that back it, or 16 MiB for one without a view.

use gltf::accessor::sparse::IndexType;
use gltf::accessor::{DataType, Dimensions};
use gltf::buffer::View;

/// Largest number of vertices or triangles in one merged mesh.
pub(super) const MAX_ELEMENTS: usize = 1 << 28;

/// Largest number of elements of an accessor without a buffer view. Such an accessor is zeros
/// save its sparse elements, so its count is backed by no bytes: with the general cap, a
/// 500-byte file could ask for 2^28 zero positions (3 GiB at once, and tens of GiB once
/// triangulated and built). 2^20 VEC4 floats are 16 MiB; files use view-less accessors for
/// small sparse edits (morph targets, which are not read here), not for whole meshes.
pub(super) const MAX_ZERO_FILLED: usize = 1 << 20;

/// The bytes of `view`, checked against the buffers' real lengths.
pub(super) fn view_bytes<'b>(buffers: &'b [Vec<u8>], view: &View) -> Result<&'b [u8], String> {
    let b = view.buffer().index();
    let data = buffers
        .get(b)
        .ok_or_else(|| format!("buffer view {} names a missing buffer {b}", view.index()))?;
    let (offset, length) = (view.offset(), view.length());
    offset
        .checked_add(length)
        .filter(|&end| end <= data.len())
        .map(|end| &data[offset..end])
        .ok_or_else(|| {
            format!(
                "buffer view {} covers bytes {offset}..{} of buffer {b}, which holds {} bytes",
                view.index(),
                offset.saturating_add(length),
                data.len()
            )
        })
}

/// Checks that `count` elements of `element` bytes, `stride` apart from `offset`, fit in `len`
/// bytes; `what` names the data in the message.
fn check_fits(
    what: &str,
    count: usize,
    element: usize,
    stride: usize,
    offset: usize,
    len: usize,
) -> Result<(), String> {
    if count == 0 {
        return Ok(());
    }
    let need = (count as u128 - 1) * stride as u128 + element as u128 + offset as u128;
    if need > len as u128 {
        return Err(format!(
            "{what} claims {count} elements ({need} bytes from byte {offset}), more than the {len} bytes of its buffer view hold"
        ));
    }
    Ok(())
}

/// One component of type `ty` at the start of `b` (which holds at least its size), as `f32`;
/// normalized integers map to [0, 1] or [−1, 1] as the glTF specification says.
fn component_f32(b: &[u8], ty: DataType, normalized: bool) -> f32 {
    match ty {
        DataType::I8 => {
            let v = f32::from(b[0] as i8);
            if normalized { (v / 127.0).max(-1.0) } else { v }
        }
        DataType::U8 => {
            let v = f32::from(b[0]);
            if normalized { v / 255.0 } else { v }
        }
        DataType::I16 => {
            let v = f32::from(i16::from_le_bytes([b[0], b[1]]));
            if normalized {
                (v / 32767.0).max(-1.0)
            } else {
                v
            }
        }
        DataType::U16 => {
            let v = f32::from(u16::from_le_bytes([b[0], b[1]]));
            if normalized { v / 65535.0 } else { v }
        }
        DataType::U32 => {
            let v = u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32;
            if normalized {
                (f64::from(v) / f64::from(u32::MAX)) as f32
            } else {
                v
            }
        }
        DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    }
}

/// One unsigned integer component (indices); `None` for other types.
fn component_u32(b: &[u8], ty: DataType) -> Option<u32> {
    Some(match ty {
        DataType::U8 => u32::from(b[0]),
        DataType::U16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
        DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        _ => return None,
    })
}

/// The elements of accessor `a`, flattened (`count × components` values), each component read
/// by `read` from its bytes. Matrices are refused (their columns are padded; no attribute read
/// here uses them).
fn read_with<T: Copy + Default>(
    buffers: &[Vec<u8>],
    a: &gltf::Accessor,
    read: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, String> {
    let what = format!("accessor {}", a.index());
    let width = match a.dimensions() {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        d => return Err(format!("{what} holds matrices ({d:?}), not vectors")),
    };
    let size = a.data_type().size();
    let element = width * size;
    let count = a.count();
    let mut out;
    match a.view() {
        Some(view) => {
            let bytes = view_bytes(buffers, &view)?;
            let stride = view.stride().unwrap_or(element);
            if stride < element {
                return Err(format!(
                    "buffer view {} has a byte stride of {stride}, less than the {element} bytes of {what}'s elements",
                    view.index()
                ));
            }
            check_fits(&what, count, element, stride, a.offset(), bytes.len())?;
            out = Vec::with_capacity(count * width);
            for i in 0..count {
                let start = a.offset() + i * stride;
                let e = &bytes[start..start + element];
                out.extend(e.chunks_exact(size).map(&read));
            }
        }
        None => {
            if count > MAX_ZERO_FILLED {
                return Err(format!(
                    "{what} has no buffer view and claims {count} elements; at most {MAX_ZERO_FILLED} are supported without one"
                ));
            }
            out = vec![T::default(); count * width];
        }
    }
    if let Some(sparse) = a.sparse() {
        let n = sparse.count();
        if n > count {
            return Err(format!(
                "{what} replaces {n} sparse elements of its {count}"
            ));
        }
        let indices = sparse.indices();
        let index_size = match indices.index_type() {
            IndexType::U8 => 1,
            IndexType::U16 => 2,
            IndexType::U32 => 4,
        };
        let index_bytes = view_bytes(buffers, &indices.view())?;
        let index_what = format!("the sparse indices of {what}");
        check_fits(
            &index_what,
            n,
            index_size,
            index_size,
            indices.offset(),
            index_bytes.len(),
        )?;
        let values = sparse.values();
        let value_bytes = view_bytes(buffers, &values.view())?;
        let value_what = format!("the sparse values of {what}");
        check_fits(
            &value_what,
            n,
            element,
            element,
            values.offset(),
            value_bytes.len(),
        )?;
        for k in 0..n {
            let at = indices.offset() + k * index_size;
            let b = &index_bytes[at..at + index_size];
            let i = match index_size {
                1 => usize::from(b[0]),
                2 => usize::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
            };
            if i >= count {
                return Err(format!(
                    "{index_what}: index {i} out of range ({count} elements)"
                ));
            }
            let at = values.offset() + k * element;
            let e = &value_bytes[at..at + element];
            for (slot, c) in out[i * width..(i + 1) * width]
                .iter_mut()
                .zip(e.chunks_exact(size))
            {
                *slot = read(c);
            }
        }
    }
    Ok(out)
}

/// The 4×4 float matrices of accessor `a` (column by column, as glTF stores them): skins'
/// inverse bind matrices. Other component types and sparse matrices are refused.
pub(super) fn read_matrices(
    buffers: &[Vec<u8>],
    a: &gltf::Accessor,
) -> Result<Vec<glam::Mat4>, String> {
    let what = format!("accessor {}", a.index());
    if a.dimensions() != Dimensions::Mat4 || a.data_type() != DataType::F32 {
        return Err(format!("{what} holds no float 4×4 matrices"));
    }
    if a.sparse().is_some() {
        return Err(format!("{what}: sparse matrices are not read"));
    }
    let view = a
        .view()
        .ok_or_else(|| format!("{what} holds matrices without a buffer view"))?;
    let bytes = view_bytes(buffers, &view)?;
    let element = 64;
    let stride = view.stride().unwrap_or(element).max(element);
    check_fits(&what, a.count(), element, stride, a.offset(), bytes.len())?;
    let matrices: Vec<glam::Mat4> = (0..a.count())
        .map(|i| {
            let start = a.offset() + i * stride;
            let mut cols = [0.0f32; 16];
            for (k, c) in bytes[start..start + element].chunks_exact(4).enumerate() {
                cols[k] = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
            }
            glam::Mat4::from_cols_array(&cols)
        })
        .collect();
    if matrices.iter().any(|m| !m.is_finite()) {
        return Err(format!("{what} holds a matrix that is not finite"));
    }
    Ok(matrices)
}

/// The elements of `a` as floats, flattened; `widths` lists the vector sizes accepted.
pub(super) fn read_floats(
    buffers: &[Vec<u8>],
    a: &gltf::Accessor,
    widths: &[usize],
) -> Result<(Vec<f32>, usize), String> {
    let width = a.dimensions().multiplicity();
    if !widths.contains(&width) {
        return Err(format!(
            "accessor {} holds {:?} elements; expected vectors of {}",
            a.index(),
            a.dimensions(),
            widths
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(" or ")
        ));
    }
    let (ty, normalized) = (a.data_type(), a.normalized());
    let values = read_with(buffers, a, |b| component_f32(b, ty, normalized))?;
    Ok((values, width))
}

/// The elements of `a` as vertex indices: scalars of unsigned bytes, shorts or ints.
pub(super) fn read_indices(buffers: &[Vec<u8>], a: &gltf::Accessor) -> Result<Vec<u32>, String> {
    let ty = a.data_type();
    if a.dimensions() != Dimensions::Scalar || component_u32(&[0; 4], ty).is_none() {
        return Err(format!(
            "accessor {} cannot hold indices: {:?} of {:?} (expected scalars of unsigned integers)",
            a.index(),
            a.dimensions(),
            ty
        ));
    }
    read_with(buffers, a, |b| component_u32(b, ty).unwrap_or(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalized_integers_follow_the_specification() {
        assert_eq!(component_f32(&[255], DataType::U8, true), 1.0);
        assert_eq!(component_f32(&[0x80], DataType::I8, true), -1.0);
        assert_eq!(component_f32(&[0x81], DataType::I8, true), -1.0);
        assert_eq!(component_f32(&[127], DataType::I8, true), 1.0);
        assert_eq!(component_f32(&[127], DataType::I8, false), 127.0);
        assert_eq!(component_f32(&[0xff, 0xff], DataType::U16, true), 1.0);
        assert_eq!(component_f32(&[0x00, 0x80], DataType::I16, true), -1.0);
        assert_eq!(
            component_f32(&1.5f32.to_le_bytes(), DataType::F32, false),
            1.5
        );
        assert_eq!(component_u32(&[1, 1, 0, 0], DataType::U32), Some(257));
        assert_eq!(component_u32(&[1, 1], DataType::I16), None);
    }

    #[test]
    fn sizes_are_checked_without_overflow() {
        assert!(check_fits("a", 3, 12, 12, 0, 36).is_ok());
        assert!(check_fits("a", 3, 12, 12, 1, 36).is_err());
        assert!(check_fits("a", 3, 12, 16, 0, 44).is_ok());
        assert!(check_fits("a", 0, 12, 12, 1000, 0).is_ok());
        let e = check_fits("accessor 0", usize::MAX, 12, 12, 0, 36).unwrap_err();
        assert!(e.contains("more than the 36 bytes"), "{e}");
    }
}
