//! Filling a [`SampleBuf`] chunk by chunk, so that readers convert values as
//! they read them instead of holding the file's bytes and the samples at once.

use crate::data::grid::ScalarType;
use crate::data::volume::SampleBuf;

/// An empty buffer of `ty` with room for `n` values.
pub fn with_capacity(ty: ScalarType, n: usize) -> SampleBuf {
    match ty {
        ScalarType::U8 => SampleBuf::U8(Vec::with_capacity(n)),
        ScalarType::I8 => SampleBuf::I8(Vec::with_capacity(n)),
        ScalarType::U16 => SampleBuf::U16(Vec::with_capacity(n)),
        ScalarType::I16 => SampleBuf::I16(Vec::with_capacity(n)),
        ScalarType::U32 => SampleBuf::U32(Vec::with_capacity(n)),
        ScalarType::I32 => SampleBuf::I32(Vec::with_capacity(n)),
        ScalarType::F32 => SampleBuf::F32(Vec::with_capacity(n)),
        ScalarType::F64 => SampleBuf::F64(Vec::with_capacity(n)),
    }
}

/// Appends `values` (of the same type as `out`) to `out`.
///
/// # Panics
/// When the types differ: the callers convert first.
pub fn append(out: &mut SampleBuf, values: SampleBuf) {
    match (out, values) {
        (SampleBuf::U8(o), SampleBuf::U8(v)) => o.extend(v),
        (SampleBuf::I8(o), SampleBuf::I8(v)) => o.extend(v),
        (SampleBuf::U16(o), SampleBuf::U16(v)) => o.extend(v),
        (SampleBuf::I16(o), SampleBuf::I16(v)) => o.extend(v),
        (SampleBuf::U32(o), SampleBuf::U32(v)) => o.extend(v),
        (SampleBuf::I32(o), SampleBuf::I32(v)) => o.extend(v),
        (SampleBuf::F32(o), SampleBuf::F32(v)) => o.extend(v),
        (SampleBuf::F64(o), SampleBuf::F64(v)) => o.extend(v),
        (o, v) => panic!("appending {:?} values to a {:?} buffer", v.scalar_type(), o.scalar_type()),
    }
}

/// Appends `slope * v + inter` for every value `v` of `values` to `out`,
/// which is `f64` or `f32` (computed in `f64`, then rounded).
///
/// # Panics
/// When `out` is neither `f32` nor `f64`.
pub fn append_scaled(out: &mut SampleBuf, values: &SampleBuf, slope: f64, inter: f64) {
    let n = values.len();
    let value = |i: usize| -> f64 {
        match values {
            SampleBuf::U8(v) => f64::from(v[i]),
            SampleBuf::I8(v) => f64::from(v[i]),
            SampleBuf::U16(v) => f64::from(v[i]),
            SampleBuf::I16(v) => f64::from(v[i]),
            SampleBuf::U32(v) => f64::from(v[i]),
            SampleBuf::I32(v) => f64::from(v[i]),
            SampleBuf::F32(v) => f64::from(v[i]),
            SampleBuf::F64(v) => v[i],
        }
    };
    match out {
        SampleBuf::F64(o) => o.extend((0..n).map(|i| slope * value(i) + inter)),
        SampleBuf::F32(o) => o.extend((0..n).map(|i| (slope * value(i) + inter) as f32)),
        other => panic!("scaled values go into f32 or f64, not {:?}", other.scalar_type()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn appends_and_scales_chunks() {
        let mut out = with_capacity(ScalarType::I16, 4);
        append(&mut out, SampleBuf::I16(vec![1, 2]));
        append(&mut out, SampleBuf::I16(vec![3]));
        assert_eq!(out, SampleBuf::I16(vec![1, 2, 3]));
        let mut scaled = with_capacity(ScalarType::F32, 2);
        append_scaled(&mut scaled, &SampleBuf::U8(vec![0, 10]), 2.0, -1.0);
        assert_eq!(scaled, SampleBuf::F32(vec![-1.0, 19.0]));
    }
}
