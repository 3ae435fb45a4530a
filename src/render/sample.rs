//! Trilinear reconstruction: of the full grid (the reference) and of a
//! brick's texture (T_p, what a GPU 3D texture of the brick gives; the
//! compositor reads its copy, [`super::texture`]).
//!
//! On a lattice of `n` points per axis with values `f`, at lattice
//! coordinates `u` (clamped to `[0, n - 1]`, as `GL_CLAMP_TO_EDGE`):
//!
//! ```text
//! i0 = floor(u),  i1 = min(i0 + 1, n - 1),  t = u - i0     (per axis)
//! v(ia, jb) = lerp(f(ia, jb, k0), f(ia, jb, k1), tz)
//! w(ia)     = lerp(v(ia, j0), v(ia, j1), ty)
//! value     = lerp(w(i0), w(i1), tx)
//! ```
//!
//! (the evaluation order of [`crate::octree::trilinear`]). The full grid is
//! the lattice of its points, `u = (p - origin) / spacing` for a world point
//! `p`. A brick's lattice is its texels: texel `i` holds the grid value at
//! `min(lo + i stride, hi)` (see [`crate::plan::select::Brick::texel_positions`]) and an index-space
//! point `x` is at `u = (x - lo) / stride`, so the last texel of a brick
//! clipped by the grid repeats the grid's last sample one stride away, as
//! T_p's virtual padding does.

use crate::data::grid::{GridShape, Sample, TypedGrid};
use crate::octree::trilinear::lerp;

/// Trilinear interpolation at lattice coordinates `u` of `n` points per axis
/// (see the module documentation).
#[inline]
pub(crate) fn trilinear(n: [usize; 3], u: [f64; 3], f: impl Fn(usize, usize, usize) -> f64) -> f64 {
    let mut i0 = [0; 3];
    let mut i1 = [0; 3];
    let mut t = [0.0; 3];
    for a in 0..3 {
        let x = u[a].clamp(0.0, (n[a] - 1) as f64);
        let i = x as usize;
        (i0[a], i1[a], t[a]) = (i, (i + 1).min(n[a] - 1), x - i as f64);
    }
    let w = |ia: usize| {
        let v0 = lerp(f(ia, i0[1], i0[2]), f(ia, i0[1], i1[2]), t[2]);
        let v1 = lerp(f(ia, i1[1], i0[2]), f(ia, i1[1], i1[2]), t[2]);
        lerp(v0, v1, t[1])
    };
    lerp(w(i0[0]), w(i1[0]), t[0])
}

/// Index-space position of world point `p`: `(p - origin) / spacing`.
#[inline]
pub(crate) fn to_index(shape: &GridShape, p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|a| (p[a] - shape.origin[a]) / shape.spacing[a])
}

/// The grid's trilinear value at index-space point `x` (clamped to the grid).
#[inline]
pub(crate) fn grid_value<T: Sample>(g: &TypedGrid<'_, T>, x: [f64; 3]) -> f64 {
    trilinear(g.dims, x, |i, j, k| g.at(i, j, k))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, GridVisitor, Samples};

    /// The full grid's reconstruction: linear between grid points, clamped outside.
    struct FullGrid;
    impl GridVisitor for FullGrid {
        type Output = ();
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
            // Between grid points the full-grid reconstruction is linear in each axis.
            let v = grid_value(&g, [2.25, 3.0, 4.0]);
            assert!((v - (0.75 * g.at(2, 3, 4) + 0.25 * g.at(3, 3, 4))).abs() < 1e-12);
            // Outside, it clamps to the edge.
            assert_eq!(grid_value(&g, [-3.0, 0.0, 0.0]), g.at(0, 0, 0));
            assert_eq!(grid_value(&g, [99.0, 10.0, 10.0]), g.at(10, 10, 10));
        }
    }

    #[test]
    fn grid_values_interpolate_and_clamp() {
        let data: Vec<f64> = (0..11 * 11 * 11).map(|i| ((i * 7919) % 101) as f64 / 100.0).collect();
        let g = Grid::scalar(Samples::F64(&data), [11, 11, 11]).unwrap();
        g.visit(FullGrid);
    }
}
