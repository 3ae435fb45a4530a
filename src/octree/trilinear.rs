//! T_p: the trilinear approximation of a node from its samples taken every
//! `s = 2^(L-k-p)` cells (paper 1, section 2.1).
//!
//! Because node boxes at every level start at multiples of their size, the
//! same stride gives the same approximation in every node: T_s is one field
//! over the whole grid. For a sample `v = (x, y, z)`:
//!
//! ```text
//! x0 = floor(x / s) * s,  x1 = min(x0 + s, nx - 1),  tx = (x - x0) / s     (same for y, z)
//! v(xa, yb) = f(xa, yb, z0) + (f(xa, yb, z1) - f(xa, yb, z0)) * tz
//! w(xa)     = v(xa, y0) + (v(xa, y1) - v(xa, y0)) * ty
//! T_s(v)    = w(x0) + (w(x1) - w(x0)) * tx
//! ```
//!
//! The clamp `min(x0 + s, n - 1)` is the virtual padding: samples beyond the
//! grid repeat the last one (as `GL_CLAMP_TO_EDGE` does for a texture brick
//! that sticks out of the volume). The evaluation order above is part of the
//! definition: the fast kernel and the brute-force reference both call the
//! functions of this file, so their results are equal bit for bit.

use super::lattice::Lattice;

/// `a + (b - a) * t`, the one interpolation formula used everywhere; when
/// `b - a` overflows (samples of opposite sign near `f64::MAX`), the same
/// value as `a (1 - t) + b t`, which does not.
#[inline(always)]
pub fn lerp(a: f64, b: f64, t: f64) -> f64 {
    let d = b - a;
    if d.is_finite() {
        a + d * t
    } else {
        wide_lerp(a, b, t)
    }
}

/// `a + (b - a) * t` without the overflow test of [`lerp`], for the leaf
/// kernel's samples, which [`kernel_scale`] keeps below `2^401` in magnitude
/// (so `b - a` is finite); branch-free, so the kernel's rows vectorise.
#[inline(always)]
pub fn lerp_scaled(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

#[cold]
fn wide_lerp(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

/// The kernels' scale `k` for data whose largest magnitude is `m`: 1 for
/// `2^-400 <= m <= 2^400`, else the power of two that brings `m` into
/// `[0.5, 2)` (clamped to `2^-1022 ..= 2^1000`). The nodal errors are computed
/// on `k f`: exact (a power of two), and differences, squares and sums of
/// squares of `k f` neither overflow (`f` near `f64::MAX`) nor underflow
/// (subnormal `f`); errors relative to the range are unchanged.
pub fn kernel_scale(min: f64, max: f64) -> f64 {
    let m = min.abs().max(max.abs());
    if !(m.is_finite() && m > 0.0) || (2f64.powi(-400)..=2f64.powi(400)).contains(&m) {
        return 1.0;
    }
    // m = 2^e x with x in [1, 2) (subnormals: e from the leading bit).
    let e = if m.is_normal() {
        ((m.to_bits() >> 52) as i32) - 1023
    } else {
        -1023 - (m.to_bits().leading_zeros() as i32 - 12)
    };
    let k = (-e).clamp(-1022, 1000);
    f64::from_bits(((1023 + k) as u64) << 52)
}

/// The bracketing coarse coordinates of `x` for stride `s` on an axis of `n`
/// samples: `(x0, x1, t)`.
#[inline(always)]
pub fn bracket(x: usize, s: usize, n: usize) -> (usize, usize, f64) {
    let x0 = x / s * s;
    (x0, (x0 + s).min(n - 1), (x - x0) as f64 / s as f64)
}

/// The y, z bracket of a row: `(y0, y1, ty, z0, z1, tz)`.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)] // variants and fields are named by what they hold
pub struct RowBracket {
    pub y0: usize,
    pub y1: usize,
    pub ty: f64,
    pub z0: usize,
    pub z1: usize,
    pub tz: f64,
}

impl RowBracket {
    /// The bracket of row `(y, z)` for stride `s`.
    #[inline(always)]
    pub fn new(y: usize, z: usize, s: usize, dims: [usize; 3]) -> RowBracket {
        let (y0, y1, ty) = bracket(y, s, dims[1]);
        let (z0, z1, tz) = bracket(z, s, dims[2]);
        RowBracket { y0, y1, ty, z0, z1, tz }
    }

    /// `w(xa)`: the bilinear interpolation in y and z at coarse x position `xa`.
    #[inline(always)]
    pub fn w<G: Lattice>(&self, g: &G, xa: usize) -> f64 {
        let v0 = lerp(g.at(xa, self.y0, self.z0), g.at(xa, self.y0, self.z1), self.tz);
        let v1 = lerp(g.at(xa, self.y1, self.z0), g.at(xa, self.y1, self.z1), self.tz);
        lerp(v0, v1, self.ty)
    }
}

/// Coarse positions of stride `s` covering `[lo, hi]` on an axis of `n`
/// samples: multiples of s from `floor(lo / s) * s` to the first one past
/// `hi`, clamped to `n - 1` (the virtual padding), into `out`.
pub fn coarse_positions(lo: usize, hi: usize, s: usize, n: usize, out: &mut Vec<usize>) {
    out.clear();
    let mut xa = lo / s * s;
    loop {
        let clamped = xa.min(n - 1);
        out.push(clamped);
        if xa > hi || clamped == n - 1 {
            break;
        }
        xa += s;
    }
}

/// T_s at sample `(x, y, z)`, straight from the definition (the reference path).
pub fn eval<G: Lattice>(g: &G, s: usize, x: usize, y: usize, z: usize) -> f64 {
    let (x0, x1, tx) = bracket(x, s, g.dims()[0]);
    let row = RowBracket::new(y, z, s, g.dims());
    lerp(row.w(g, x0), row.w(g, x1), tx)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, GridVisitor, Sample, Samples, TypedGrid};

    struct At(usize, [usize; 3]);
    impl GridVisitor for At {
        type Output = f64;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> f64 {
            eval(&g, self.0, self.1[0], self.1[1], self.1[2])
        }
    }

    #[test]
    fn reproduces_corners_and_is_linear_between() {
        // f = x + 10 y + 100 z on 5^3: trilinear, so every stride reproduces it.
        let data: Vec<f64> = (0..125).map(|i| (i % 5 + 10 * ((i / 5) % 5) + 100 * (i / 25)) as f64).collect();
        let g = Grid::scalar(Samples::F64(&data), [5, 5, 5]).unwrap();
        for s in [1, 2, 4] {
            assert_eq!(g.visit(At(s, [3, 1, 2])), 213.0);
        }
    }

    #[test]
    fn padding_repeats_the_last_sample() {
        // 1D ramp 0..=5 along x, stride 4: the cell [4, 8] is clamped to [4, 5].
        let data: Vec<f32> = (0..6 * 2 * 2).map(|i| (i % 6) as f32).collect();
        let g = Grid::scalar(Samples::F32(&data), [6, 2, 2]).unwrap();
        assert_eq!(g.visit(At(4, [5, 0, 0])), 4.0 + (5.0 - 4.0) * 0.25);
    }
}
