//! Trilinear reconstruction: of the full grid (the reference) and of a
//! brick's texture (T_p, what a GPU 3D texture of the brick gives).
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
//! `min(lo + i stride, hi)` (see [`Brick::texel_positions`]) and an index-space
//! point `x` is at `u = (x - lo) / stride`, so the last texel of a brick
//! clipped by the grid repeats the grid's last sample one stride away, as
//! T_p's virtual padding does.

use crate::grid::{GridShape, Sample, TypedGrid};
use crate::octree::trilinear::lerp;
use crate::select::Brick;

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

/// A brick's texture: the grid read at its texel positions, no copy.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BrickTexture {
    lo: [usize; 3],
    hi: [usize; 3],
    stride: usize,
    texels: [usize; 3],
}

impl BrickTexture {
    /// The texture of `brick` (checked by the caller: stride >= 1, texels >= 1, box inside the grid).
    pub(crate) fn new(brick: &Brick) -> BrickTexture {
        BrickTexture { lo: brick.lo, hi: brick.hi, stride: brick.stride, texels: brick.texels }
    }

    /// T_p at index-space point `x`: `u = (x - lo) / stride` on the texels.
    #[inline]
    pub(crate) fn value<T: Sample>(&self, g: &TypedGrid<'_, T>, x: [f64; 3]) -> f64 {
        let s = self.stride;
        let u = [0, 1, 2].map(|a| (x[a] - self.lo[a] as f64) / s as f64);
        let pos = |a: usize, i: usize| (self.lo[a] + i * s).min(self.hi[a]);
        trilinear(self.texels, u, |i, j, k| g.at(pos(0, i), pos(1, j), pos(2, k)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Grid, GridVisitor, Samples};
    use crate::octree::trilinear;
    use crate::octree::NodeId;

    fn brick(lo: [usize; 3], hi: [usize; 3], stride: usize) -> Brick {
        let texels = [0, 1, 2].map(|a| (hi[a] - lo[a]).div_ceil(stride) + 1);
        Brick { node: NodeId(0), level: 0, p: 0, lo, hi, stride, texels, bytes: 0, error: 0.0, importance: 1.0 }
    }

    /// The brick texture is T_p: equal, bit for bit, to the octree's
    /// definition at every grid point of the brick, clipped bricks included.
    struct SameAsTp;
    impl GridVisitor for SameAsTp {
        type Output = ();
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
            for (lo, hi, s) in [([0, 0, 0], [8, 8, 8], 4), ([8, 0, 8], [10, 8, 10], 4), ([4, 4, 4], [6, 6, 6], 1)] {
                let tex = BrickTexture::new(&brick(lo, hi, s));
                for z in lo[2]..=hi[2] {
                    for y in lo[1]..=hi[1] {
                        for x in lo[0]..=hi[0] {
                            let p = [x as f64, y as f64, z as f64];
                            assert_eq!(tex.value(&g, p), trilinear::eval(&g, s, x, y, z), "{lo:?} s {s} at {p:?}");
                        }
                    }
                }
            }
            // Between grid points the full-grid reconstruction is linear in each axis.
            let v = grid_value(&g, [2.25, 3.0, 4.0]);
            assert!((v - (0.75 * g.at(2, 3, 4) + 0.25 * g.at(3, 3, 4))).abs() < 1e-12);
            // Outside, it clamps to the edge.
            assert_eq!(grid_value(&g, [-3.0, 0.0, 0.0]), g.at(0, 0, 0));
            assert_eq!(grid_value(&g, [99.0, 10.0, 10.0]), g.at(10, 10, 10));
        }
    }

    #[test]
    fn brick_texture_is_t_p() {
        let data: Vec<f64> = (0..11 * 11 * 11).map(|i| ((i * 7919) % 101) as f64 / 100.0).collect();
        let g = Grid::scalar(Samples::F64(&data), [11, 11, 11]).unwrap();
        g.visit(SameAsTp);
    }
}
