//! Reading glTF accessors with every offset, stride and count checked.
//!
//! The `gltf` crate's readers assume a well-formed file: a zero `count`, a stride smaller than
//! the element, or a component type other than the one asked for trips a panic or debug
//! assertion there. Here each such case is an error message instead.

use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;

use crate::error::LoadErrorKind;
use crate::limits::MAX_VERTICES;

/// The loaded bytes of each glTF buffer, indexed like `document.buffers()`, each exactly
/// `byteLength` long.
pub(crate) type Buffers = [Vec<u8>];

fn corrupt(msg: String) -> LoadErrorKind {
    LoadErrorKind::CorruptGltf(msg)
}

/// The bytes of a buffer view, checked against its buffer.
pub(crate) fn view_bytes<'b>(view: &gltf::buffer::View, buffers: &'b Buffers) -> Result<&'b [u8], LoadErrorKind> {
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or_else(|| corrupt(format!("bufferView {} names a missing buffer", view.index())))?;
    view.offset().checked_add(view.length()).and_then(|end| buffer.get(view.offset()..end)).ok_or_else(|| {
        corrupt(format!(
            "bufferView {} spans bytes {}..{}+{} but buffer {} has {} bytes",
            view.index(),
            view.offset(),
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        ))
    })
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn components(d: Dimensions) -> Option<usize> {
    match d {
        Dimensions::Scalar => Some(1),
        Dimensions::Vec2 => Some(2),
        Dimensions::Vec3 => Some(3),
        Dimensions::Vec4 => Some(4),
        // Matrices carry column padding rules and are never vertex data we use.
        Dimensions::Mat2 | Dimensions::Mat3 | Dimensions::Mat4 => None,
    }
}

/// The accessor's elements copied tightly packed (sparse substitution applied).
fn packed_bytes(acc: &Accessor, buffers: &Buffers) -> Result<(Vec<u8>, usize), LoadErrorKind> {
    let idx = acc.index();
    let count = acc.count();
    if count > MAX_VERTICES {
        return Err(LoadErrorKind::TooLarge(format!("accessor {idx} has {count} elements (limit {MAX_VERTICES})")));
    }
    let ncomp = components(acc.dimensions())
        .ok_or_else(|| corrupt(format!("accessor {idx} is a matrix, expected scalar or vector data")))?;
    let elem = ncomp * component_size(acc.data_type());
    let mut out = vec![0u8; count * elem];

    // Without a bufferView the base values are zeros (only meaningful with sparse data).
    if let Some(view) = acc.view() {
        let data = view_bytes(&view, buffers)?;
        let stride = view.stride().unwrap_or(elem);
        if stride < elem {
            return Err(corrupt(format!(
                "accessor {idx}: byteStride {stride} is smaller than its {elem}-byte element"
            )));
        }
        if count > 0 {
            let end = stride
                .checked_mul(count - 1)
                .and_then(|s| s.checked_add(acc.offset()))
                .and_then(|s| s.checked_add(elem))
                .filter(|&end| end <= data.len())
                .ok_or_else(|| {
                    corrupt(format!(
                        "accessor {idx} ({count} elements of {elem} bytes, stride {stride}, offset {}) overruns bufferView {} ({} bytes)",
                        acc.offset(),
                        view.index(),
                        data.len()
                    ))
                })?;
            let data = &data[acc.offset()..end];
            for (i, dst) in out.chunks_exact_mut(elem).enumerate() {
                dst.copy_from_slice(&data[i * stride..i * stride + elem]);
            }
        }
    }

    if let Some(sparse) = acc.sparse() {
        let n = sparse.count();
        if n > count {
            return Err(corrupt(format!("accessor {idx}: {n} sparse values for {count} elements")));
        }
        let isize_ = sparse.indices().index_type_size();
        let idx_bytes =
            sub_slice(&sparse.indices().view(), buffers, sparse.indices().offset(), n * isize_, idx, "indices")?;
        let val_bytes = sub_slice(&sparse.values().view(), buffers, sparse.values().offset(), n * elem, idx, "values")?;
        for k in 0..n {
            let b = &idx_bytes[k * isize_..(k + 1) * isize_];
            let target = match isize_ {
                1 => b[0] as usize,
                2 => u16::from_le_bytes([b[0], b[1]]) as usize,
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
            };
            if target >= count {
                return Err(corrupt(format!("accessor {idx}: sparse index {target} out of range ({count} elements)")));
            }
            out[target * elem..(target + 1) * elem].copy_from_slice(&val_bytes[k * elem..(k + 1) * elem]);
        }
    }
    Ok((out, ncomp))
}

fn sub_slice<'b>(
    view: &gltf::buffer::View,
    buffers: &'b Buffers,
    offset: usize,
    len: usize,
    idx: usize,
    what: &str,
) -> Result<&'b [u8], LoadErrorKind> {
    let data = view_bytes(view, buffers)?;
    offset
        .checked_add(len)
        .and_then(|end| data.get(offset..end))
        .ok_or_else(|| corrupt(format!("accessor {idx}: sparse {what} overrun bufferView {}", view.index())))
}

trait IndexTypeSize {
    fn index_type_size(&self) -> usize;
}

impl IndexTypeSize for gltf::accessor::sparse::Indices<'_> {
    fn index_type_size(&self) -> usize {
        use gltf::accessor::sparse::IndexType;
        match self.index_type() {
            IndexType::U8 => 1,
            IndexType::U16 => 2,
            IndexType::U32 => 4,
        }
    }
}

/// Reads a float vector attribute (`N` components), converting normalized integer
/// components (KHR_mesh_quantization style) to floats as the glTF spec defines.
pub(crate) fn read_vectors<const N: usize>(
    acc: &Accessor,
    buffers: &Buffers,
    what: &str,
) -> Result<Vec<[f32; N]>, LoadErrorKind> {
    let got = components(acc.dimensions());
    if got != Some(N) {
        return Err(corrupt(format!(
            "accessor {} for {what} is {:?}, expected a {N}-component vector",
            acc.index(),
            acc.dimensions()
        )));
    }
    let (bytes, _) = packed_bytes(acc, buffers)?;
    let (ty, norm) = (acc.data_type(), acc.normalized());
    let size = component_size(ty);
    let values: Vec<f32> = bytes.chunks_exact(size).map(|b| decode_component(ty, norm, b)).collect();
    Ok(values
        .chunks_exact(N)
        .map(|c| {
            let mut v = [0.0; N];
            v.copy_from_slice(c);
            v
        })
        .collect())
}

/// Reads a `COLOR_n` attribute as linear RGBA: VEC3 (alpha 1) or VEC4 of floats, or of
/// normalized unsigned bytes or shorts (the component types the glTF spec allows for colours).
pub(crate) fn read_colors(acc: &Accessor, buffers: &Buffers, what: &str) -> Result<Vec<[f32; 4]>, LoadErrorKind> {
    let n = match acc.dimensions() {
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        other => {
            return Err(corrupt(format!("accessor {} for {what} is {other:?}, expected VEC3 or VEC4", acc.index())));
        }
    };
    let (ty, norm) = (acc.data_type(), acc.normalized());
    if !(ty == DataType::F32 || (norm && matches!(ty, DataType::U8 | DataType::U16))) {
        return Err(corrupt(format!(
            "accessor {} for {what} is {ty:?}{}, expected float or normalized unsigned byte/short",
            acc.index(),
            if norm { " (normalized)" } else { "" }
        )));
    }
    let (bytes, _) = packed_bytes(acc, buffers)?;
    let size = component_size(ty);
    let values: Vec<f32> = bytes.chunks_exact(size).map(|b| decode_component(ty, norm, b)).collect();
    Ok(values.chunks_exact(n).map(|c| [c[0], c[1], c[2], if n == 4 { c[3] } else { 1.0 }]).collect())
}

/// Reads a vertex index accessor (unsigned byte, short or int scalars).
pub(crate) fn read_indices(acc: &Accessor, buffers: &Buffers) -> Result<Vec<u32>, LoadErrorKind> {
    let ty = acc.data_type();
    if acc.dimensions() != Dimensions::Scalar || !matches!(ty, DataType::U8 | DataType::U16 | DataType::U32) {
        return Err(corrupt(format!(
            "index accessor {} is {:?} of {:?}, expected SCALAR unsigned byte/short/int",
            acc.index(),
            acc.dimensions(),
            ty
        )));
    }
    let (bytes, _) = packed_bytes(acc, buffers)?;
    Ok(match ty {
        DataType::U8 => bytes.iter().map(|&b| u32::from(b)).collect(),
        DataType::U16 => bytes.chunks_exact(2).map(|b| u32::from(u16::from_le_bytes([b[0], b[1]]))).collect(),
        _ => bytes.chunks_exact(4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect(),
    })
}

fn decode_component(ty: DataType, normalized: bool, b: &[u8]) -> f32 {
    match ty {
        DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::I8 => {
            let v = f32::from(b[0] as i8);
            if normalized {
                (v / 127.0).max(-1.0)
            } else {
                v
            }
        }
        DataType::U8 => {
            let v = f32::from(b[0]);
            if normalized {
                v / 255.0
            } else {
                v
            }
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
            if normalized {
                v / 65535.0
            } else {
                v
            }
        }
        DataType::U32 => {
            let v = u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32;
            if normalized {
                v / u32::MAX as f32
            } else {
                v
            }
        }
    }
}
