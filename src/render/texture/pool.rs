//! Peak-keeping texels for maximum and minimum intensity: a coarse brick
//! (stride `s > 1`) of a MIP holds at each texel position `p` the largest
//! grid value of the closed box `|q - p| <= s` per axis, clipped to the
//! brick's box (MinIP: the smallest):
//!
//! ```text
//! t(p) = max { f(q) : q in [lo, hi], |q_a - p_a| <= s for a = x, y, z }
//! ```
//!
//! Why a whole stride, not half: a point `x` of the brick lies in one coarse
//! cell; its eight texels are each within `s` of every grid point of that
//! closed cell, so each holds at least their max, and so does their
//! trilinear blend: `T(x) >= max of the 8 grid values around x >= f(x)`,
//! the fine trilinear field at `x`. A coarse brick's ray therefore never
//! shows a peak lower than the fine field at its samples (a half-stride
//! window keeps the peak only at the texel itself: the blend with lower
//! neighbours pulls it down between texels). The price is a dilation: a
//! peak shows up to one stride around its place. At stride 1 the texels are
//! the grid itself. NaN (no data) is skipped; a box of NaN only stays NaN.
//! The max over a box is separable: z, then y, then x, one texel layer at a
//! time (a plane of the brick's samples at once).

use crate::data::grid::{Sample, TypedGrid};
use crate::plan::select::Brick;

/// The pooled texels of `brick` (stride > 1) in the texture layout (x
/// fastest), each stored by `f`; `None` at the first value `f` refuses.
/// `largest`: max (MIP), else min (MinIP).
pub(super) fn pooled_values<T: Sample, S>(
    g: &TypedGrid<'_, T>,
    brick: &Brick,
    largest: bool,
    f: impl Fn(f64) -> Option<S>,
) -> Option<Vec<S>> {
    let pick = |a: f64, b: f64| if largest { a.max(b) } else { a.min(b) };
    let (lo, hi, s, n) = (brick.lo, brick.hi, brick.stride, brick.texels);
    // The window of texel i along axis a, as grid indices.
    let window = |a: usize, i: usize| {
        let p = (lo[a] + i * s).min(hi[a]);
        p.saturating_sub(s).max(lo[a])..=(p + s).min(hi[a])
    };
    let (nx, ny) = (hi[0] - lo[0] + 1, hi[1] - lo[1] + 1);
    let mut plane = vec![f64::NAN; nx * ny];
    let mut rows = vec![f64::NAN; nx * n[1]];
    let mut out = Vec::with_capacity(n.iter().product());
    for k in 0..n[2] {
        plane.fill(f64::NAN);
        for z in window(2, k) {
            for y in 0..ny {
                for x in 0..nx {
                    let v = &mut plane[x + nx * y];
                    *v = pick(*v, g.at(lo[0] + x, lo[1] + y, z));
                }
            }
        }
        rows.fill(f64::NAN);
        for j in 0..n[1] {
            for y in window(1, j) {
                for x in 0..nx {
                    let v = &mut rows[x + nx * j];
                    *v = pick(*v, plane[x + nx * (y - lo[1])]);
                }
            }
        }
        for j in 0..n[1] {
            for i in 0..n[0] {
                let v = window(0, i).fold(f64::NAN, |m, x| pick(m, rows[x - lo[0] + nx * j]));
                out.push(f(v)?);
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, GridVisitor, Samples};

    /// Against the definition, brute force, on a clipped brick; and the
    /// trilinear field of the pooled texels is at least the fine one everywhere.
    #[test]
    fn pooled_texels_are_the_window_extremes_and_bound_the_fine_field() {
        const DIMS: [usize; 3] = [13, 11, 9];
        let data: Vec<f64> = (0..13 * 11 * 9).map(|i| ((i * 7919) % 101) as f64).collect();
        let grid = Grid::scalar(Samples::F64(&data), DIMS).unwrap();
        struct Check;
        impl GridVisitor for Check {
            type Output = ();
            fn visit<T: Sample>(self, g: TypedGrid<'_, T>) {
                for (lo, hi, s) in [([0, 0, 0], [12, 10, 8], 4), ([2, 1, 0], [10, 10, 8], 2), ([0, 0, 0], [8, 8, 8], 8)]
                {
                    let b = crate::plan::select::test_brick(0, lo, hi, s);
                    for largest in [true, false] {
                        let t = pooled_values(&g, &b, largest, Some).unwrap();
                        let n = b.texels;
                        let pos = |a: usize, i: usize| (lo[a] + i * s).min(hi[a]);
                        for k in 0..n[2] {
                            for j in 0..n[1] {
                                for i in 0..n[0] {
                                    let p = [pos(0, i), pos(1, j), pos(2, k)];
                                    let mut e = if largest { f64::NEG_INFINITY } else { f64::INFINITY };
                                    for z in lo[2]..=hi[2] {
                                        for y in lo[1]..=hi[1] {
                                            for x in lo[0]..=hi[0] {
                                                let q = [x, y, z];
                                                if (0..3).all(|a| q[a].abs_diff(p[a]) <= s) {
                                                    let v = g.at(x, y, z);
                                                    e = if largest { e.max(v) } else { e.min(v) };
                                                }
                                            }
                                        }
                                    }
                                    assert_eq!(t[i + n[0] * (j + n[1] * k)], e, "{lo:?} s {s} texel {i} {j} {k}");
                                }
                            }
                        }
                        // T(x) >= f(x) (MIP) at grid points and between them.
                        let tex = |u: [f64; 3]| {
                            crate::render::sample::trilinear(n, u, |i, j, k| t[i + n[0] * (j + n[1] * k)])
                        };
                        let fine = |x: [f64; 3]| crate::render::sample::trilinear(DIMS, x, |i, j, k| g.at(i, j, k));
                        for q in 0..2000 {
                            let r = |m: usize| ((q * m) % 997) as f64 / 997.0;
                            let x = [0, 1, 2].map(|a| lo[a] as f64 + r(31 + 7 * a) * (hi[a] - lo[a]) as f64);
                            let u = [0, 1, 2].map(|a| (x[a] - lo[a] as f64) / s as f64);
                            let (c, f) = (tex(u), fine(x));
                            assert!(if largest { c >= f } else { c <= f }, "{lo:?} s {s} at {x:?}: {c} vs {f}");
                        }
                    }
                }
            }
        }
        grid.visit(Check);
    }
}
