//! A borrowed, typed view of a regular scalar grid: VTK image point scalars
//! without a copy.
//!
//! # Indexing
//!
//! Samples are stored x fastest, as VTK stores `vtkImageData` point data. The
//! value of component `c` of point `(i, j, k)` of a grid with dimensions
//! `(nx, ny, nz)` and `nc` components is
//!
//! ```text
//! samples[(i + nx * (j + ny * k)) * nc + c]
//! ```
//!
//! and its world position is `origin + (i, j, k) * spacing`.
//!
//! A [`Grid`] is checked once, when it is made: at least two samples per axis,
//! a sample count that fits `usize`, a buffer of exactly that length, a chosen
//! component for multi-component arrays, no infinity anywhere and at least one
//! sample that is not NaN.
//!
//! # NaN: no data
//!
//! A NaN sample is "no data" (a mask, a region outside the scanner's field of
//! view), not an error. The grid counts them ([`Grid::nan_count`]); every
//! algorithm after that treats them by one rule:
//!
//! - a sample point whose trilinear interpolation touches a NaN corner (any of
//!   the 8 lattice samples of its cell, whatever its weight) is no data: it is
//!   transparent in every renderer and outside every isosurface;
//! - NaN samples are left out of min/max; a box of NaN only has the empty range
//!   `(+inf, -inf)`;
//! - the error of approximating a sample is 0 when the fine sample and its
//!   coarse approximation are both NaN, the full value range when exactly one of
//!   them is NaN (a hole the other picture does not have), `|f - T|` otherwise
//!   (see [`crate::octree::build`]).
//!
//! Infinities stay an error ([`Error::NonFinite`]): they have no colour and no
//! place in a value range. A volume of NaN only is [`Error::NoData`].

use crate::base::error::{Error, Result};
use rayon::prelude::*;

/// A scalar type VTK images carry. `to_f64` is exact for every type here.
pub trait Sample: Copy + Send + Sync + 'static {
    /// Name used in messages and in the CLI's `--type`.
    const NAME: &'static str;
    /// The sample as `f64` (exact: every supported type fits in an `f64`).
    fn to_f64(self) -> f64;
    /// False for NaN and infinities; always true for integers.
    fn is_finite(self) -> bool;
    /// True for NaN; always false for integers.
    fn is_nan(self) -> bool;
}

macro_rules! int_sample {
    ($t:ty, $name:expr) => {
        impl Sample for $t {
            const NAME: &'static str = $name;
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                true
            }
            #[inline(always)]
            fn is_nan(self) -> bool {
                false
            }
        }
    };
}
int_sample!(u8, "u8");
int_sample!(i8, "i8");
int_sample!(u16, "u16");
int_sample!(i16, "i16");
int_sample!(u32, "u32");
int_sample!(i32, "i32");

impl Sample for f32 {
    const NAME: &'static str = "f32";
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        f32::is_nan(self)
    }
}
impl Sample for f64 {
    const NAME: &'static str = "f64";
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        f64::is_nan(self)
    }
}

/// The scalar types a grid can borrow, named as in the CLI (`--type`) and the bridge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // variants and fields are named by what they hold
pub enum ScalarType {
    U8,
    I8,
    U16,
    I16,
    U32,
    I32,
    F32,
    F64,
}

impl ScalarType {
    /// Bytes of one value.
    pub fn size(self) -> usize {
        match self {
            ScalarType::U8 | ScalarType::I8 => 1,
            ScalarType::U16 | ScalarType::I16 => 2,
            ScalarType::U32 | ScalarType::I32 | ScalarType::F32 => 4,
            ScalarType::F64 => 8,
        }
    }
    /// The name used by `--type` and in messages.
    pub fn name(self) -> &'static str {
        match self {
            ScalarType::U8 => "u8",
            ScalarType::I8 => "i8",
            ScalarType::U16 => "u16",
            ScalarType::I16 => "i16",
            ScalarType::U32 => "u32",
            ScalarType::I32 => "i32",
            ScalarType::F32 => "f32",
            ScalarType::F64 => "f64",
        }
    }
    /// Parses `u8`, `int16`, `float`, ... (also the VTK and numpy spellings).
    pub fn parse(name: &str) -> Result<ScalarType> {
        Ok(match name.to_ascii_lowercase().as_str() {
            "u8" | "uint8" | "unsigned_char" | "uchar" => ScalarType::U8,
            "i8" | "int8" | "char" | "signed_char" => ScalarType::I8,
            "u16" | "uint16" | "unsigned_short" | "ushort" => ScalarType::U16,
            "i16" | "int16" | "short" => ScalarType::I16,
            "u32" | "uint32" | "unsigned_int" | "uint" => ScalarType::U32,
            "i32" | "int32" | "int" => ScalarType::I32,
            "f32" | "float32" | "float" => ScalarType::F32,
            "f64" | "float64" | "double" => ScalarType::F64,
            other => {
                return Err(Error::InvalidArgument(format!(
                    "unknown scalar type '{other}': use one of u8, i8, u16, i16, u32, i32, f32, f64"
                )))
            }
        })
    }
}

/// A borrowed slice of samples of one of the supported types.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)] // variants and fields are named by what they hold
pub enum Samples<'a> {
    U8(&'a [u8]),
    I8(&'a [i8]),
    U16(&'a [u16]),
    I16(&'a [i16]),
    U32(&'a [u32]),
    I32(&'a [i32]),
    F32(&'a [f32]),
    F64(&'a [f64]),
}

impl<'a> Samples<'a> {
    /// Number of values (all components).
    pub fn len(&self) -> usize {
        match self {
            Samples::U8(s) => s.len(),
            Samples::I8(s) => s.len(),
            Samples::U16(s) => s.len(),
            Samples::I16(s) => s.len(),
            Samples::U32(s) => s.len(),
            Samples::I32(s) => s.len(),
            Samples::F32(s) => s.len(),
            Samples::F64(s) => s.len(),
        }
    }
    /// True when there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The scalar type of the slice.
    pub fn scalar_type(&self) -> ScalarType {
        match self {
            Samples::U8(_) => ScalarType::U8,
            Samples::I8(_) => ScalarType::I8,
            Samples::U16(_) => ScalarType::U16,
            Samples::I16(_) => ScalarType::I16,
            Samples::U32(_) => ScalarType::U32,
            Samples::I32(_) => ScalarType::I32,
            Samples::F32(_) => ScalarType::F32,
            Samples::F64(_) => ScalarType::F64,
        }
    }

    /// The values' bytes in native byte order: a view, not a copy.
    pub fn as_bytes(&self) -> &'a [u8] {
        fn view<T>(v: &[T]) -> &[u8] {
            // SAFETY: `T` is a plain number type without padding; the byte
            // slice covers exactly the values and borrows them for its lifetime.
            unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<u8>(), std::mem::size_of_val(v)) }
        }
        match *self {
            Samples::U8(v) => v,
            Samples::I8(v) => view(v),
            Samples::U16(v) => view(v),
            Samples::I16(v) => view(v),
            Samples::U32(v) => view(v),
            Samples::I32(v) => view(v),
            Samples::F32(v) => view(v),
            Samples::F64(v) => view(v),
        }
    }

    /// Reinterprets a byte buffer (VTK's `GetVoidPointer`) as typed samples,
    /// without copying. Fails if the length is not a multiple of the value size
    /// or the pointer is not aligned for the type.
    pub fn from_bytes(bytes: &'a [u8], scalar_type: ScalarType) -> Result<Samples<'a>> {
        fn cast<T: Sample>(bytes: &[u8]) -> Result<&[T]> {
            let size = std::mem::size_of::<T>();
            if !bytes.len().is_multiple_of(size) {
                return Err(Error::InvalidArgument(format!(
                    "the scalar buffer has {} bytes, not a multiple of the {}-byte {} type",
                    bytes.len(),
                    size,
                    T::NAME
                )));
            }
            if bytes.is_empty() {
                return Ok(&[]);
            }
            if !(bytes.as_ptr() as usize).is_multiple_of(std::mem::align_of::<T>()) {
                return Err(Error::Misaligned { type_name: T::NAME });
            }
            // SAFETY: the pointer is non-null (from a slice), aligned for T (checked
            // above), the byte length is an exact multiple of size_of::<T>() (checked
            // above), every bit pattern is a valid T for these plain number types, and
            // the returned slice borrows `bytes` for the same lifetime.
            Ok(unsafe { std::slice::from_raw_parts(bytes.as_ptr() as *const T, bytes.len() / size) })
        }
        Ok(match scalar_type {
            ScalarType::U8 => Samples::U8(cast(bytes)?),
            ScalarType::I8 => Samples::I8(cast(bytes)?),
            ScalarType::U16 => Samples::U16(cast(bytes)?),
            ScalarType::I16 => Samples::I16(cast(bytes)?),
            ScalarType::U32 => Samples::U32(cast(bytes)?),
            ScalarType::I32 => Samples::I32(cast(bytes)?),
            ScalarType::F32 => Samples::F32(cast(bytes)?),
            ScalarType::F64 => Samples::F64(cast(bytes)?),
        })
    }
}

/// Geometry and layout of a grid, shared by the borrowed [`Grid`] and the owned
/// [`crate::data::volume::Volume`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridShape {
    /// Samples per axis `(nx, ny, nz)`, each at least 2.
    pub dims: [usize; 3],
    /// Distance between samples per axis, finite and positive.
    pub spacing: [f64; 3],
    /// World position of sample `(0, 0, 0)`.
    pub origin: [f64; 3],
}

impl GridShape {
    /// Number of points `nx * ny * nz` (checked for overflow by [`Grid::new`]).
    pub fn point_count(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }
    /// Cells per axis: `dims - 1`.
    pub fn cells(&self) -> [usize; 3] {
        [self.dims[0] - 1, self.dims[1] - 1, self.dims[2] - 1]
    }
    /// `(i, j, k)` of linear point index `i + nx * (j + ny * k)`.
    pub fn ijk(&self, index: usize) -> [usize; 3] {
        let [nx, ny, _] = self.dims;
        [index % nx, (index / nx) % ny, index / (nx * ny)]
    }
    /// World position of index-space point `p` (may be fractional or outside).
    pub fn world(&self, p: [f64; 3]) -> [f64; 3] {
        [
            self.origin[0] + p[0] * self.spacing[0],
            self.origin[1] + p[1] * self.spacing[1],
            self.origin[2] + p[2] * self.spacing[2],
        ]
    }

    /// Checks dims, overflow and geometry; returns the number of values
    /// `nx * ny * nz * components`.
    pub fn check(&self, components: usize) -> Result<usize> {
        if self.dims.iter().any(|&d| d < 2) {
            return Err(Error::DimsTooSmall { dims: self.dims });
        }
        if components == 0 {
            return Err(Error::NoComponents);
        }
        let values = self.dims[0]
            .checked_mul(self.dims[1])
            .and_then(|v| v.checked_mul(self.dims[2]))
            .and_then(|v| v.checked_mul(components))
            // keep every index (and index + stride arithmetic) far from usize::MAX
            .filter(|&v| v <= isize::MAX as usize / 8)
            .ok_or(Error::DimsOverflow { dims: self.dims, components })?;
        for a in 0..3 {
            let s = self.spacing[a];
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::BadGeometry {
                    what: format!("spacing {:?} must be finite and positive on every axis", self.spacing),
                });
            }
            if !self.origin[a].is_finite() {
                return Err(Error::BadGeometry { what: format!("origin {:?} must be finite", self.origin) });
            }
            // A subnormal spacing leaves world positions a few bits; a far
            // corner beyond f64::MAX leaves none.
            if !s.is_normal() {
                return Err(Error::BadGeometry {
                    what: format!(
                        "spacing {:?} is below 2.2e-308 (a subnormal number, too few bits for positions): \
                         scale the geometry up",
                        self.spacing
                    ),
                });
            }
            if !(self.origin[a] + (self.dims[a] - 1) as f64 * s).is_finite() {
                return Err(Error::BadGeometry {
                    what: format!(
                        "origin {:?} + {} samples x spacing {:?} is beyond the largest f64: scale the geometry down",
                        self.origin,
                        self.dims[a] - 1,
                        self.spacing
                    ),
                });
            }
        }
        Ok(values)
    }
}

/// A checked, borrowed view of one component of a scalar grid.
#[derive(Debug, Clone, Copy)]
pub struct Grid<'a> {
    samples: Samples<'a>,
    shape: GridShape,
    components: usize,
    component: usize,
    nan_count: usize,
}

impl<'a> Grid<'a> {
    /// Borrows `samples` as a grid of `shape` with `components` values per
    /// point, reading component `component` (`None` is allowed only for
    /// single-component arrays).
    ///
    /// Checks everything listed in the module docs and counts the NaN
    /// samples; the scan is one parallel pass over float data and free for
    /// integer data.
    pub fn new(samples: Samples<'a>, shape: GridShape, components: usize, component: Option<usize>) -> Result<Self> {
        let mut grid = Grid::unscanned(samples, shape, components, component)?;
        grid.nan_count = grid.scan()?;
        Ok(grid)
    }

    /// [`Grid::new`] without the scan, for reading part of a grid already
    /// checked whole (a selected brick's texels, after the octree was built
    /// from the same samples): the caller checks the values it reads, and
    /// [`Grid::nan_count`] is 0 (not counted).
    pub fn unscanned(
        samples: Samples<'a>,
        shape: GridShape,
        components: usize,
        component: Option<usize>,
    ) -> Result<Self> {
        let values = shape.check(components)?;
        if samples.len() != values {
            return Err(Error::LengthMismatch { expected: values, actual: samples.len() });
        }
        let component = match component {
            Some(c) if c >= components => return Err(Error::ComponentOutOfRange { component: c, components }),
            Some(c) => c,
            None if components > 1 => return Err(Error::ComponentRequired { components }),
            None => 0,
        };
        Ok(Grid { samples, shape, components, component, nan_count: 0 })
    }

    /// A single-component grid over `samples` (convenience for tests and datasets).
    pub fn scalar(samples: Samples<'a>, dims: [usize; 3]) -> Result<Self> {
        Grid::new(samples, GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] }, 1, None)
    }

    /// Refuses infinities and a grid of NaN only; returns the NaN count.
    fn scan(&self) -> Result<usize> {
        let scan = match self.samples {
            Samples::F32(s) => scan_non_finite(s, self.components, self.component),
            Samples::F64(s) => scan_non_finite(s, self.components, self.component),
            _ => Scan::default(),
        };
        if scan.infinite > 0 {
            let first = scan.first_infinite;
            return Err(Error::NonFinite { count: scan.infinite, first, first_ijk: self.shape.ijk(first) });
        }
        if scan.nan == self.shape.point_count() {
            return Err(Error::NoData { count: scan.nan });
        }
        Ok(scan.nan)
    }

    /// Number of NaN samples ("no data", see the module docs) of the chosen
    /// component; 0 for integer types and for [`Grid::unscanned`] grids.
    pub fn nan_count(&self) -> usize {
        self.nan_count
    }

    /// Dimensions, spacing, origin.
    pub fn shape(&self) -> &GridShape {
        &self.shape
    }
    /// Samples per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.shape.dims
    }
    /// The borrowed samples (all components).
    pub fn samples(&self) -> Samples<'a> {
        self.samples
    }
    /// Components per point in the borrowed array.
    pub fn components(&self) -> usize {
        self.components
    }
    /// The component this grid reads.
    pub fn component(&self) -> usize {
        self.component
    }
    /// Bytes of the borrowed samples of the chosen component (the "input bytes"
    /// octree memory is compared against).
    pub fn input_bytes(&self) -> usize {
        self.shape.point_count() * self.samples.scalar_type().size()
    }

    /// Value of point `(i, j, k)` as `f64`. Panics if out of range (a caller bug).
    pub fn value(&self, i: usize, j: usize, k: usize) -> f64 {
        let [nx, ny, nz] = self.shape.dims;
        assert!(i < nx && j < ny && k < nz, "grid index ({i}, {j}, {k}) out of range");
        let index = (i + nx * (j + ny * k)) * self.components + self.component;
        match self.samples {
            Samples::U8(s) => s[index].to_f64(),
            Samples::I8(s) => s[index].to_f64(),
            Samples::U16(s) => s[index].to_f64(),
            Samples::I16(s) => s[index].to_f64(),
            Samples::U32(s) => s[index].to_f64(),
            Samples::I32(s) => s[index].to_f64(),
            Samples::F32(s) => s[index].to_f64(),
            Samples::F64(s) => s[index].to_f64(),
        }
    }

    /// Calls `visitor` with the typed view, so kernels are monomorphised per
    /// scalar type instead of matching per sample.
    pub fn visit<V: GridVisitor>(&self, visitor: V) -> V::Output {
        match self.samples {
            Samples::U8(s) => visitor.visit(self.typed(s)),
            Samples::I8(s) => visitor.visit(self.typed(s)),
            Samples::U16(s) => visitor.visit(self.typed(s)),
            Samples::I16(s) => visitor.visit(self.typed(s)),
            Samples::U32(s) => visitor.visit(self.typed(s)),
            Samples::I32(s) => visitor.visit(self.typed(s)),
            Samples::F32(s) => visitor.visit(self.typed(s)),
            Samples::F64(s) => visitor.visit(self.typed(s)),
        }
    }

    fn typed<T: Sample>(&self, data: &'a [T]) -> TypedGrid<'a, T> {
        TypedGrid { data, dims: self.shape.dims, components: self.components, component: self.component }
    }
}

/// A kernel generic over the sample type; see [`Grid::visit`].
pub trait GridVisitor {
    /// What the kernel returns.
    type Output;
    /// Runs the kernel on the typed grid.
    fn visit<T: Sample>(self, grid: TypedGrid<'_, T>) -> Self::Output;
}

/// The typed form of a [`Grid`] handed to a [`GridVisitor`].
#[derive(Debug, Clone, Copy)]
pub struct TypedGrid<'a, T: Sample> {
    data: &'a [T],
    /// Samples per axis.
    pub dims: [usize; 3],
    components: usize,
    component: usize,
}

impl<'a, T: Sample> TypedGrid<'a, T> {
    /// Value of point `(i, j, k)`; indices must be in range.
    #[inline(always)]
    pub fn at(&self, i: usize, j: usize, k: usize) -> f64 {
        self.data[(i + self.dims[0] * (j + self.dims[1] * k)) * self.components + self.component].to_f64()
    }

    /// Value of point `(i, j, k)` as stored (no conversion); indices must be in range.
    #[inline(always)]
    pub fn get(&self, i: usize, j: usize, k: usize) -> T {
        self.data[(i + self.dims[0] * (j + self.dims[1] * k)) * self.components + self.component]
    }

    /// Asks the CPU to bring the x-row `(i0..=i1, j, k)` into its caches (a
    /// hint with no effect on results; nothing on CPUs without the instruction).
    #[inline(always)]
    pub fn prefetch_row(&self, i0: usize, i1: usize, j: usize, k: usize) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            let base = self.dims[0] * (j + self.dims[1] * k);
            let (first, last) = ((base + i0) * self.components, (base + i1) * self.components + self.component);
            let row = &self.data[first..=last];
            let bytes = std::mem::size_of_val(row);
            let ptr = row.as_ptr() as *const i8;
            let mut at = 0;
            while at < bytes {
                // SAFETY: `at < bytes`, inside `row`; a prefetch reads nothing.
                unsafe { _mm_prefetch::<_MM_HINT_T0>(ptr.add(at)) };
                at += 64;
            }
            // SAFETY: the row's last byte; a prefetch reads nothing.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(ptr.add(bytes - 1)) };
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = (i0, i1, j, k);
    }

    /// The x-row `(i0..=i1, j, k)` as values, written into `out` (cleared first).
    #[inline]
    pub fn row_into(&self, i0: usize, i1: usize, j: usize, k: usize, out: &mut Vec<f64>) {
        out.clear();
        let base = self.dims[0] * (j + self.dims[1] * k);
        if self.components == 1 {
            out.extend(self.data[base + i0..=base + i1].iter().map(|v| v.to_f64()));
        } else {
            out.extend((i0..=i1).map(|i| self.data[(base + i) * self.components + self.component].to_f64()));
        }
    }
}

/// What the scan of one component found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Scan {
    nan: usize,
    infinite: usize,
    /// Point index of the first infinity (`usize::MAX` when there is none).
    first_infinite: usize,
}

impl Default for Scan {
    fn default() -> Self {
        Scan { nan: 0, infinite: 0, first_infinite: usize::MAX }
    }
}

/// Counts the NaN and infinite values of one component and finds the first infinity.
fn scan_non_finite<T: Sample>(s: &[T], components: usize, component: usize) -> Scan {
    const CHUNK: usize = 1 << 16;
    let points = s.len() / components;
    (0..points.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut scan = Scan::default();
            for p in c * CHUNK..((c + 1) * CHUNK).min(points) {
                let v = s[p * components + component];
                if v.is_nan() {
                    scan.nan += 1;
                } else if !v.is_finite() {
                    scan.infinite += 1;
                    scan.first_infinite = scan.first_infinite.min(p);
                }
            }
            scan
        })
        .reduce(Scan::default, |a, b| Scan {
            nan: a.nan + b.nan,
            infinite: a.infinite + b.infinite,
            first_infinite: a.first_infinite.min(b.first_infinite),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(dims: [usize; 3]) -> GridShape {
        GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] }
    }

    #[test]
    fn indexing_follows_vtk_order() {
        let data: Vec<u16> = (0..24).collect();
        let g = Grid::scalar(Samples::U16(&data), [2, 3, 4]).unwrap();
        assert_eq!(g.value(1, 2, 3), (1 + 2 * (2 + 3 * 3)) as f64);
        assert_eq!(g.shape().ijk(23), [1, 2, 3]);
    }

    #[test]
    fn one_wide_axis_is_refused() {
        let data = vec![0u8; 4];
        let e = Grid::scalar(Samples::U8(&data), [2, 2, 1]).unwrap_err();
        assert!(matches!(e, Error::DimsTooSmall { .. }));
        assert!(e.to_string().contains("at least 2 samples"));
    }

    #[test]
    fn overflowing_dims_are_refused() {
        let data = vec![0u8; 8];
        let e = Grid::new(Samples::U8(&data), shape([usize::MAX / 2, 4, 4]), 1, None).unwrap_err();
        assert!(matches!(e, Error::DimsOverflow { .. }), "{e}");
    }

    #[test]
    fn multi_component_needs_a_choice() {
        let data = vec![0f32; 8 * 3];
        let e = Grid::new(Samples::F32(&data), shape([2, 2, 2]), 3, None).unwrap_err();
        assert!(e.to_string().contains("component option"), "{e}");
        let e = Grid::new(Samples::F32(&data), shape([2, 2, 2]), 3, Some(3)).unwrap_err();
        assert!(matches!(e, Error::ComponentOutOfRange { .. }));
        let g = Grid::new(Samples::F32(&data), shape([2, 2, 2]), 3, Some(2)).unwrap();
        assert_eq!(g.component(), 2);
    }

    #[test]
    fn component_selects_the_right_values() {
        let data: Vec<i32> = (0..16).collect();
        let g = Grid::new(Samples::I32(&data), shape([2, 2, 2]), 2, Some(1)).unwrap();
        assert_eq!(g.value(1, 0, 0), 3.0);
    }

    #[test]
    fn infinities_are_counted_and_located_nan_is_not_an_error() {
        let mut data = vec![1f64; 27];
        data[3] = f64::NAN;
        data[5] = f64::NEG_INFINITY;
        data[20] = f64::INFINITY;
        let e = Grid::scalar(Samples::F64(&data), [3, 3, 3]).unwrap_err();
        assert_eq!(e, Error::NonFinite { count: 2, first: 5, first_ijk: [2, 1, 0] });
        assert!(e.to_string().contains("2 infinite sample(s)"), "{e}");
        data[5] = 1.0;
        data[20] = 1.0;
        assert_eq!(Grid::scalar(Samples::F64(&data), [3, 3, 3]).unwrap().nan_count(), 1);
    }

    #[test]
    fn a_grid_of_nan_only_has_no_data() {
        let data = vec![f32::NAN; 8];
        let e = Grid::scalar(Samples::F32(&data), [2, 2, 2]).unwrap_err();
        assert_eq!(e, Error::NoData { count: 8 });
        assert!(e.to_string().contains("all 8 samples are NaN"), "{e}");
    }

    #[test]
    fn nan_is_counted_in_the_chosen_component_only() {
        let mut data = vec![1f32; 16];
        data[1] = f32::NAN;
        assert_eq!(Grid::new(Samples::F32(&data), shape([2, 2, 2]), 2, Some(0)).unwrap().nan_count(), 0);
        assert_eq!(Grid::new(Samples::F32(&data), shape([2, 2, 2]), 2, Some(1)).unwrap().nan_count(), 1);
    }

    #[test]
    fn length_and_geometry_are_checked() {
        let data = vec![0u8; 7];
        assert!(matches!(Grid::scalar(Samples::U8(&data), [2, 2, 2]), Err(Error::LengthMismatch { .. })));
        let data = vec![0u8; 8];
        let bad = GridShape { dims: [2, 2, 2], spacing: [1.0, 0.0, 1.0], origin: [0.0; 3] };
        assert!(matches!(Grid::new(Samples::U8(&data), bad, 1, None), Err(Error::BadGeometry { .. })));
    }

    #[test]
    fn bytes_are_borrowed_not_copied() {
        let data = [1.5f32, 2.5];
        let bytes: &[u8] =
            // SAFETY: f32 has no padding; the byte view covers exactly the vector's storage.
            unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, 8) };
        match Samples::from_bytes(bytes, ScalarType::F32).unwrap() {
            Samples::F32(s) => {
                assert_eq!(s.as_ptr(), data.as_ptr());
                assert_eq!(s, &[1.5, 2.5]);
            }
            other => panic!("wrong type {other:?}"),
        }
        assert!(Samples::from_bytes(&bytes[..7], ScalarType::F32).is_err());
        assert!(matches!(Samples::from_bytes(&bytes[1..5], ScalarType::F32), Err(Error::Misaligned { .. })));
    }
}
