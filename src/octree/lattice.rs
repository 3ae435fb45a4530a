//! What the leaf kernel reads of a grid: samples by index, x-rows, the
//! grid's dimensions. A whole grid in memory ([`TypedGrid`]) and the
//! streaming build's stack of z-planes ([`super::plane_stack::PlaneStack`])
//! both provide it, so one kernel (with its AVX2 path) serves both builds.

use crate::data::grid::{Sample, TypedGrid};

/// Read access to the samples of a regular grid, as `f64`.
pub trait Lattice: Sync {
    /// Samples per axis of the whole grid.
    fn dims(&self) -> [usize; 3];
    /// Value of point `(i, j, k)`; indices must be in range (and, for a
    /// partial lattice, the plane `k` held).
    fn at(&self, i: usize, j: usize, k: usize) -> f64;
    /// The x-row `(i0..=i1, j, k)` as values, written into `out` (cleared first).
    fn row_into(&self, i0: usize, i1: usize, j: usize, k: usize, out: &mut Vec<f64>);
    /// Asks the CPU to bring the x-row `(i0..=i1, j, k)` into its caches (a
    /// hint with no effect on results).
    fn prefetch_row(&self, i0: usize, i1: usize, j: usize, k: usize);
}

impl<T: Sample> Lattice for TypedGrid<'_, T> {
    #[inline(always)]
    fn dims(&self) -> [usize; 3] {
        self.dims
    }
    #[inline(always)]
    fn at(&self, i: usize, j: usize, k: usize) -> f64 {
        TypedGrid::at(self, i, j, k)
    }
    #[inline(always)]
    fn row_into(&self, i0: usize, i1: usize, j: usize, k: usize, out: &mut Vec<f64>) {
        TypedGrid::row_into(self, i0, i1, j, k, out)
    }
    #[inline(always)]
    fn prefetch_row(&self, i0: usize, i1: usize, j: usize, k: usize) {
        TypedGrid::prefetch_row(self, i0, i1, j, k)
    }
}
