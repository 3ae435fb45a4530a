//! The per-brick kernel: min, max and the raw stride errors of one leaf brick.
//!
//! For every stride `s = 2^j`, `j = 1 ..= L`, the raw stride error of a brick is
//!
//! ```text
//! r_j(brick) = max over the samples v of the brick's closed box of |f(v) - T_s(v)|
//! ```
//!
//! with T_s from [`super::trilinear`]. A node's nodal errors are maxima of
//! these over its leaves (see [`super::build`]). Strides up to the brick size
//! use coarse cells inside the brick; larger strides use the one coarse cell
//! that contains the whole brick.
//!
//! Work per sample: the brick is read once into a buffer of `f64`. For each
//! z-slice and stride, the z-interpolated values `v(xa, yb)` at the coarse
//! positions are computed once, each row's `w(xa) = lerp(v(xa, y0), v(xa, y1), ty)`
//! from them, then T along the row (`w0 + (w1 - w0) * tx`) and a max of
//! `|f - T|` over the row that the compiler vectorises. These are the same
//! operations, in the same order, as [`super::trilinear::eval`], so the
//! result equals the brute-force definition bit for bit.

use super::layout::Layout;
use super::trilinear::{bracket, lerp};
use crate::grid::{Sample, TypedGrid};

/// Statistics of one leaf brick.
#[derive(Debug, Clone, PartialEq)]
pub struct LeafStats {
    /// Smallest sample in the closed box.
    pub min: f64,
    /// Largest sample in the closed box.
    pub max: f64,
    /// `raw[j - 1]` = r_j, the raw error of stride `2^j`, `j = 1 ..= L`.
    pub raw: Vec<f64>,
}

/// Reusable buffers of the kernel (one per worker).
#[derive(Debug, Default)]
pub struct Scratch {
    brick: Vec<f64>,
    v: Vec<f64>,
    w: Vec<f64>,
    t: Vec<f64>,
    xs: Vec<usize>,
    ys: Vec<usize>,
    frac: Vec<f64>,
    cells: Vec<(usize, usize, usize, usize)>,
}

/// Coarse positions of stride `s` covering `[lo, hi]` on an axis of `n`
/// samples: multiples of s from `floor(lo / s) * s` to the first one past
/// `hi`, clamped to `n - 1` (the virtual padding), into `out`.
fn coarse_positions(lo: usize, hi: usize, s: usize, n: usize, out: &mut Vec<usize>) {
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

/// `max |a[i] - b[i]|` with four independent lanes so it vectorises
/// (`if d > m` is `maxpd`; all values are finite).
#[inline]
fn max_abs_diff(a: &[f64], b: &[f64], init: f64) -> f64 {
    let mut lanes = [init; 4];
    let mut ca = a.chunks_exact(4);
    let mut cb = b.chunks_exact(4);
    for (x, y) in (&mut ca).zip(&mut cb) {
        for k in 0..4 {
            let d = (x[k] - y[k]).abs();
            lanes[k] = if d > lanes[k] { d } else { lanes[k] };
        }
    }
    let mut m = lanes[0].max(lanes[1]).max(lanes[2].max(lanes[3]));
    for (x, y) in ca.remainder().iter().zip(cb.remainder()) {
        m = m.max((x - y).abs());
    }
    m
}

/// Computes the [`LeafStats`] of the brick with closed index box `[lo, hi]`.
pub fn leaf_stats<T: Sample>(
    g: &TypedGrid<'_, T>,
    layout: &Layout,
    lo: [usize; 3],
    hi: [usize; 3],
    scratch: &mut Scratch,
) -> LeafStats {
    let strides = layout.root_log2 as usize;
    let wx = hi[0] - lo[0] + 1;
    let wy = hi[1] - lo[1] + 1;
    let brick = &mut scratch.brick;
    brick.clear();
    let mut row = Vec::new();
    for z in lo[2]..=hi[2] {
        for y in lo[1]..=hi[1] {
            g.row_into(lo[0], hi[0], y, z, &mut row);
            brick.extend_from_slice(&row);
        }
    }
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in brick.iter() {
        min = if v < min { v } else { min };
        max = if v > max { v } else { max };
    }
    let mut raw = vec![0.0f64; strides];
    let first_coarse = layout.leaf_log2 as usize + 1;
    if min == max {
        // A constant brick: every in-brick stride reproduces it exactly. For a
        // stride larger than the brick, T_s is trilinear over the brick, so
        // |c - T_s| is largest at one of the brick's eight corners.
        for (j, r) in raw.iter_mut().enumerate().skip(first_coarse - 1) {
            let s = 1usize << (j + 1);
            for corner in 0..8usize {
                let x = if corner & 1 == 0 { lo[0] } else { hi[0] };
                let y = if corner & 2 == 0 { lo[1] } else { hi[1] };
                let z = if corner & 4 == 0 { lo[2] } else { hi[2] };
                *r = r.max((min - super::trilinear::eval(g, s, x, y, z)).abs());
            }
        }
        return LeafStats { min, max, raw };
    }
    let Scratch { brick, v, w, t, xs, ys, frac, cells } = scratch;
    t.resize(wx, 0.0);
    for (j, r) in raw.iter_mut().enumerate() {
        let s = 1usize << (j + 1);
        coarse_positions(lo[0], hi[0], s, g.dims[0], xs);
        coarse_positions(lo[1], hi[1], s, g.dims[1], ys);
        let (x_first, y_first) = (lo[0] / s * s, lo[1] / s * s);
        let (nxs, nys) = (xs.len(), ys.len());
        // tx = (x - x0) / s for x - x0 = 0 .. s-1 (exact: s is a power of two).
        frac.clear();
        frac.extend((0..s).map(|i| i as f64 / s as f64));
        // Row segments [a, b) lying in coarse cell xi, and where in `frac` they start.
        cells.clear();
        for xi in 0..nxs {
            let x0 = x_first + xi * s;
            let (a, b) = (x0.max(lo[0]), (x0 + s).min(hi[0] + 1));
            if a < b && x0 < g.dims[0] {
                cells.push((a - lo[0], b - lo[0], xi, a - x0));
            }
        }
        let mut err = 0.0f64;
        for z in lo[2]..=hi[2] {
            let (z0, z1, tz) = bracket(z, s, g.dims[2]);
            // v(xa, yb) for every coarse (xa, yb) of this slice.
            v.clear();
            for &yb in ys.iter() {
                for &xa in xs.iter() {
                    v.push(lerp(g.at(xa, yb, z0), g.at(xa, yb, z1), tz));
                }
            }
            for y in lo[1]..=hi[1] {
                let (y0, _, ty) = bracket(y, s, g.dims[1]);
                let yi0 = (y0 - y_first) / s;
                let yi1 = (yi0 + 1).min(nys - 1);
                w.clear();
                w.extend((0..nxs).map(|xi| lerp(v[yi0 * nxs + xi], v[yi1 * nxs + xi], ty)));
                // T along the row, cell by cell: w0 + (w1 - w0) * tx.
                for &(a, b, xi, off) in cells.iter() {
                    let (w0, w1) = (w[xi], w[(xi + 1).min(nxs - 1)]);
                    for (tv, &f) in t[a..b].iter_mut().zip(&frac[off..]) {
                        *tv = lerp(w0, w1, f);
                    }
                }
                let start = ((z - lo[2]) * wy + (y - lo[1])) * wx;
                err = max_abs_diff(&brick[start..start + wx], t, err);
            }
        }
        *r = err;
    }
    LeafStats { min, max, raw }
}
