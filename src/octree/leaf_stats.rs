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
//! that contains the whole brick, so T_s is a single trilinear function there.
//!
//! Work per sample: rows along x are read once into a buffer and every stride
//! is evaluated on that row; along a coarse cell T is `w0 + (w1 - w0) * tx`,
//! so the inner loop is a multiply, two subtractions and a max.

use super::layout::Layout;
use super::trilinear::{lerp, RowBracket};
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
    row: Vec<f64>,
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
    let brick = layout.leaf_size();
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for z in lo[2]..=hi[2] {
        for y in lo[1]..=hi[1] {
            g.row_into(lo[0], hi[0], y, z, &mut scratch.row);
            for &v in &scratch.row {
                min = min.min(v);
                max = max.max(v);
            }
        }
    }
    let mut raw = vec![0.0f64; strides];
    if min == max {
        // A constant brick: every in-brick stride reproduces it exactly. For a
        // stride larger than the brick, T_s is trilinear over the brick, so
        // |c - T_s| is largest at one of the brick's eight corners.
        for j in (brick.trailing_zeros() as usize + 1)..=strides {
            let s = 1usize << j;
            let mut err = 0.0f64;
            for corner in 0..8usize {
                let x = if corner & 1 == 0 { lo[0] } else { hi[0] };
                let y = if corner & 2 == 0 { lo[1] } else { hi[1] };
                let z = if corner & 4 == 0 { lo[2] } else { hi[2] };
                err = err.max((min - super::trilinear::eval(g, s, x, y, z)).abs());
            }
            raw[j - 1] = err;
        }
        return LeafStats { min, max, raw };
    }
    // Coarse w values along the row, for one stride.
    let mut w: Vec<f64> = Vec::with_capacity(brick + 2);
    for z in lo[2]..=hi[2] {
        for y in lo[1]..=hi[1] {
            g.row_into(lo[0], hi[0], y, z, &mut scratch.row);
            let row = &scratch.row;
            for j in 1..=strides {
                let s = 1usize << j;
                let rb = RowBracket::new(y, z, s, g.dims);
                // Coarse x positions covering [lo.x, hi.x]: x0 of the first cell,
                // then every s, the last clamped to nx - 1.
                let first = lo[0] / s * s;
                w.clear();
                let mut xa = first;
                loop {
                    let xc = xa.min(g.dims[0] - 1);
                    w.push(rb.w(g, xc));
                    if xa > hi[0] || xc == g.dims[0] - 1 {
                        break;
                    }
                    xa += s;
                }
                let mut err = raw[j - 1];
                let inv = 1.0 / s as f64;
                for (c, pair) in w.windows(2).enumerate() {
                    let x0 = first + c * s;
                    let (w0, w1) = (pair[0], pair[1]);
                    let start = x0.max(lo[0]);
                    let end = (x0 + s - 1).min(hi[0]);
                    for x in start..=end {
                        let t = lerp(w0, w1, (x - x0) as f64 * inv);
                        err = err.max((row[x - lo[0]] - t).abs());
                    }
                }
                // The sample on the last coarse position, when it is inside the box
                // (a node is never one sample wide, so `w` has at least two entries).
                let last_x = first + (w.len() - 1) * s;
                if last_x <= hi[0] {
                    err = err.max((row[last_x - lo[0]] - w[w.len() - 1]).abs());
                }
                raw[j - 1] = err;
            }
        }
    }
    LeafStats { min, max, raw }
}
