//! Volumes read plane by plane: a [`PlaneSource`] hands out whole z-planes
//! of a scalar volume in any order, so a pass over z (the streaming octree
//! build, the store writer) holds a few planes, never the volume.
//!
//! A source may be a volume in memory ([`GridPlanes`]), a generator that can
//! compute any plane, or a store read box by box.

use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridShape, Sample, Samples, ScalarType};
use crate::data::volume::SampleBuf;
use std::ops::Range;

/// A scalar volume read as whole z-planes, with random access.
pub trait PlaneSource {
    /// Samples per axis, spacing and origin.
    fn shape(&self) -> GridShape;
    /// The samples' type (every buffer [`Self::read_planes`] returns is of it).
    fn scalar_type(&self) -> ScalarType;
    /// The planes `z` (x fastest, then y, then z), `nx * ny * z.len()` values.
    ///
    /// # Errors
    ///
    /// Whatever reading the samples fails with.
    fn read_planes(&self, z: Range<usize>) -> Result<SampleBuf>;
}

/// The planes of a grid in memory: one component of a [`Grid`], copied out
/// plane by plane.
#[derive(Debug, Clone, Copy)]
pub struct GridPlanes<'a>(pub Grid<'a>);

impl PlaneSource for GridPlanes<'_> {
    fn shape(&self) -> GridShape {
        *self.0.shape()
    }
    fn scalar_type(&self) -> ScalarType {
        self.0.samples().scalar_type()
    }
    fn read_planes(&self, z: Range<usize>) -> Result<SampleBuf> {
        let g = &self.0;
        let [nx, ny, nz] = g.dims();
        if z.start > z.end || z.end > nz {
            return Err(Error::InvalidArgument(format!("planes {z:?} are outside the grid's {nz}")));
        }
        let (c, n) = (g.components(), g.component());
        let (first, last) = (z.start * nx * ny, z.end * nx * ny);
        fn take<T: Copy>(v: &[T], first: usize, last: usize, c: usize, n: usize) -> Vec<T> {
            if c == 1 {
                v[first..last].to_vec()
            } else {
                (first..last).map(|p| v[p * c + n]).collect()
            }
        }
        Ok(match g.samples() {
            Samples::U8(v) => SampleBuf::U8(take(v, first, last, c, n)),
            Samples::I8(v) => SampleBuf::I8(take(v, first, last, c, n)),
            Samples::U16(v) => SampleBuf::U16(take(v, first, last, c, n)),
            Samples::I16(v) => SampleBuf::I16(take(v, first, last, c, n)),
            Samples::U32(v) => SampleBuf::U32(take(v, first, last, c, n)),
            Samples::I32(v) => SampleBuf::I32(take(v, first, last, c, n)),
            Samples::F32(v) => SampleBuf::F32(take(v, first, last, c, n)),
            Samples::F64(v) => SampleBuf::F64(take(v, first, last, c, n)),
        })
    }
}

/// The values of `buf` as a `Vec<T>`, without a copy; `None` when `buf`
/// holds another type than `T`.
pub fn into_vec<T: Sample>(buf: SampleBuf) -> Option<Vec<T>> {
    use std::any::Any;
    let any: Box<dyn Any> = match buf {
        SampleBuf::U8(v) => Box::new(v),
        SampleBuf::I8(v) => Box::new(v),
        SampleBuf::U16(v) => Box::new(v),
        SampleBuf::I16(v) => Box::new(v),
        SampleBuf::U32(v) => Box::new(v),
        SampleBuf::I32(v) => Box::new(v),
        SampleBuf::F32(v) => Box::new(v),
        SampleBuf::F64(v) => Box::new(v),
    };
    any.downcast::<Vec<T>>().ok().map(|b| *b)
}

/// A computation generic over the sample type, run for a [`ScalarType`]
/// known only at run time ([`for_type`]).
pub trait TypeVisitor {
    /// What the computation returns.
    type Output;
    /// Runs the computation for samples of type `T`.
    fn visit<T: Sample>(self) -> Self::Output;
}

/// Runs `visitor` for the sample type `ty` names.
pub fn for_type<V: TypeVisitor>(ty: ScalarType, visitor: V) -> V::Output {
    match ty {
        ScalarType::U8 => visitor.visit::<u8>(),
        ScalarType::I8 => visitor.visit::<i8>(),
        ScalarType::U16 => visitor.visit::<u16>(),
        ScalarType::I16 => visitor.visit::<i16>(),
        ScalarType::U32 => visitor.visit::<u32>(),
        ScalarType::I32 => visitor.visit::<i32>(),
        ScalarType::F32 => visitor.visit::<f32>(),
        ScalarType::F64 => visitor.visit::<f64>(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_of_a_grid_are_its_samples_in_order() {
        let data: Vec<u16> = (0..2 * 3 * 4 * 2).collect();
        let shape = GridShape { dims: [2, 3, 4], spacing: [1.0; 3], origin: [0.0; 3] };
        let g = Grid::new(Samples::U16(&data), shape, 2, Some(1)).unwrap();
        let planes = GridPlanes(g).read_planes(1..3).unwrap();
        let want: Vec<u16> = (6..18).map(|p| data[p * 2 + 1]).collect();
        assert_eq!(into_vec::<u16>(planes.clone()), Some(want));
        assert_eq!(into_vec::<u8>(planes), None);
        assert!(GridPlanes(g).read_planes(3..5).is_err());
    }
}
