//! Which part of a brick the transfer function leaves visible.
//!
//! A slice fragment whose value maps to opacity 0 adds nothing, but a
//! software rasteriser pays for it all the same. A brick's texels (`dims`
//! per axis, x fastest) are cut into blocks of `B = 4` cells a side, and
//! each block keeps the range `[min, max]` of its texels (measured once,
//! when the texels are made):
//!
//! ```text
//! blocks_a = (dims_a - 2) / B + 1   (1 when dims_a <= 1)
//! block b covers cells B b .. B b + B - 1, its texels B b ..= min(B b + B, dims_a - 1)
//! ```
//!
//! NaN texels are no data and stay out of the ranges (a block of NaN only
//! has the empty range `(+inf, -inf)`). Trilinear interpolation inside a
//! cell stays within its corners' range, so a block is invisible when the
//! opacity is 0 over its whole range. With the transfer function's table of
//! `n` cells over `[lo, hi]` (cell `k` at `lo + (hi - lo) k / (n - 1)`,
//! linear between cells, clamped at the ends, as the shader samples it),
//! the opacity is 0 over `[a, b]` exactly when every cell from
//!
//! ```text
//! k_a = clamp(floor((a - lo) s), 0, n - 1)   to   k_b = clamp(ceil((b - lo) s), 0, n - 1),   s = (n - 1) / (hi - lo)
//! ```
//!
//! has opacity 0 (a prefix count of the cells above 0 answers in O(1)). The
//! brick's slices are clipped to the box of its visible blocks, in texels
//! `[B first_a, min(B (last_a + 1), dims_a - 1)]`, in world coordinates
//! (texel `t` at `min_a + t stride spacing_a`)
//!
//! ```text
//! [max(min_a, min_a + lo_a step_a), min(max_a, min_a + hi_a step_a)],   step_a = stride spacing_a
//! ```
//!
//! and a brick with no visible block is not drawn. The picture is unchanged:
//! only transparent samples go.

use crate::base::error::{Error, Result};
use std::cmp::Ordering;

/// Cells per block edge.
pub const BLOCK_CELLS: usize = 4;

/// Blocks per axis of a brick of `dims` texels (see the module documentation).
pub fn blocks(dims: [usize; 3]) -> [usize; 3] {
    dims.map(|d| if d > 1 { (d - 2) / BLOCK_CELLS + 1 } else { 1 })
}

/// Floats of the block ranges of a brick of `dims` texels: 2 a block.
pub fn ranges_len(dims: [usize; 3]) -> usize {
    2 * blocks(dims).iter().product::<usize>()
}

/// The texels of block `b` along an axis of `dim` texels.
fn block_texels(b: usize, dim: usize) -> std::ops::Range<usize> {
    let first = BLOCK_CELLS * b;
    first..(first + BLOCK_CELLS).min(dim.saturating_sub(1)) + 1
}

/// The block ranges of `texels` (`dims` texels per axis, x fastest): per
/// block, x fastest, its `[min, max]` without NaN (see the module
/// documentation), flattened: `2 * blocks` floats.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when `texels` does not hold `dims` texels.
pub fn measure(texels: &[f32], dims: [usize; 3]) -> Result<Vec<f32>> {
    let count = dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d));
    if count != Some(texels.len()) {
        return Err(Error::InvalidArgument(format!(
            "{} texels for a {}x{}x{} brick: the texels do not match the brick's texel box",
            texels.len(),
            dims[0],
            dims[1],
            dims[2]
        )));
    }
    let n = blocks(dims);
    let mut ranges = Vec::with_capacity(ranges_len(dims));
    for bz in 0..n[2] {
        for by in 0..n[1] {
            for bx in 0..n[0] {
                let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                for z in block_texels(bz, dims[2]) {
                    for y in block_texels(by, dims[1]) {
                        let row = dims[0] * (y + dims[1] * z);
                        for &v in &texels[row + BLOCK_CELLS * bx..row + block_texels(bx, dims[0]).end] {
                            // NaN compares false: left out.
                            if v < lo {
                                lo = v;
                            }
                            if v > hi {
                                hi = v;
                            }
                        }
                    }
                }
                ranges.extend([lo, hi]);
            }
        }
    }
    Ok(ranges)
}

/// The zero-opacity test of a transfer-function table (see the module
/// documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct OpacityTable {
    /// `non_zero[k]`: cells with opacity above 0 among the first `k`.
    non_zero: Vec<usize>,
    lo: f64,
    hi: f64,
}

impl OpacityTable {
    /// The table `rgba` (4 floats a cell) over `[lo, hi]`.
    pub fn new(rgba: &[f32], lo: f64, hi: f64) -> OpacityTable {
        let mut non_zero = Vec::with_capacity(rgba.len() / 4 + 1);
        non_zero.push(0);
        for cell in rgba.chunks_exact(4) {
            non_zero.push(non_zero[non_zero.len() - 1] + usize::from(cell[3] > 0.0));
        }
        OpacityTable { non_zero, lo, hi }
    }

    /// True when some value in `[a, b]` has opacity above 0; false for an
    /// empty range (`!(a <= b)`: a block of NaN only) and an empty table.
    pub fn any_visible(&self, a: f64, b: f64) -> bool {
        let n = self.non_zero.len() - 1;
        if n == 0 || !matches!(a.partial_cmp(&b), Some(Ordering::Less | Ordering::Equal)) {
            return false;
        }
        let scale = (n - 1) as f64 / (self.hi - self.lo);
        let last = (n - 1) as f64;
        // clamp(k, 0, last) as std::min(std::max(k, 0), last) did (NaN -> cell 0).
        let cell = |k: f64| {
            (if k < 0.0 {
                0.0
            } else if last < k {
                last
            } else {
                k
            }) as usize
        };
        let first = cell(((a - self.lo) * scale).floor());
        let end = cell(((b - self.lo) * scale).ceil()) + 1;
        end > first && self.non_zero[end] > self.non_zero[first]
    }
}

/// A brick's visible texels: `lo[a] ..= hi[a]` per axis, texel units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TexelBox {
    /// First visible texel coordinate per axis.
    pub lo: [f64; 3],
    /// Last visible texel coordinate per axis.
    pub hi: [f64; 3],
}

/// The box of the blocks of `ranges` (from [`measure`] for `dims`) that
/// `table` leaves visible, in texels (see the module documentation); `None`
/// when none is.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when `ranges` is not the length [`measure`]
/// gives for `dims`.
pub fn visible_box(ranges: &[f32], dims: [usize; 3], table: &OpacityTable) -> Result<Option<TexelBox>> {
    if ranges.len() != ranges_len(dims) {
        return Err(Error::InvalidArgument(format!(
            "{} block range values for a {}x{}x{} brick, which has {}: measure them again for this brick",
            ranges.len(),
            dims[0],
            dims[1],
            dims[2],
            ranges_len(dims)
        )));
    }
    let n = blocks(dims);
    let (mut first, mut last) = (n, [0usize; 3]);
    let mut any = false;
    let mut pairs = ranges.chunks_exact(2);
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                let r = pairs.next().expect("length checked");
                if !table.any_visible(r[0] as f64, r[1] as f64) {
                    continue;
                }
                any = true;
                for (a, at) in [x, y, z].into_iter().enumerate() {
                    first[a] = first[a].min(at);
                    last[a] = last[a].max(at);
                }
            }
        }
    }
    Ok(any.then(|| TexelBox {
        lo: first.map(|f| (f * BLOCK_CELLS) as f64),
        hi: [0, 1, 2].map(|a| {
            let top = dims[a].saturating_sub(1) as f64;
            top.min(((last[a] + 1) * BLOCK_CELLS) as f64)
        }),
    }))
}

/// The world box of `visible` in a brick of world box `bounds` (VTK order)
/// whose texels are `step[a] = stride spacing_a` apart: per axis
/// `[max(min_a, min_a + lo_a step_a), min(max_a, min_a + hi_a step_a)]`.
pub fn visible_bounds(bounds: &[f64; 6], step: [f64; 3], visible: &TexelBox) -> [f64; 6] {
    let mut out = [0.0; 6];
    for a in 0..3 {
        let (lo, hi) = (bounds[2 * a], bounds[2 * a + 1]);
        let (from, to) = (lo + visible.lo[a] * step[a], lo + visible.hi[a] * step[a]);
        // std::max / std::min: the first argument unless the second is beyond it.
        out[2 * a] = if lo < from { from } else { lo };
        out[2 * a + 1] = if to < hi { to } else { hi };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The measurement as the OpenGL mapper made it: texel by texel, each
    /// into the blocks of the (one or two) cells per axis it is a corner of.
    fn measure_by_texel(texels: &[f32], dims: [usize; 3]) -> Vec<f32> {
        let n = blocks(dims);
        let mut lo = vec![f32::INFINITY; n.iter().product()];
        let mut hi = vec![f32::NEG_INFINITY; lo.len()];
        let blocks_of = |t: usize, dim: usize| -> Vec<usize> {
            if dim == 1 {
                return vec![0];
            }
            let mut out = Vec::new();
            if t > 0 {
                out.push((t - 1) / BLOCK_CELLS);
            }
            if t + 1 < dim && out.first() != Some(&(t / BLOCK_CELLS)) {
                out.push(t / BLOCK_CELLS);
            }
            out
        };
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let v = texels[x + dims[0] * (y + dims[1] * z)];
                    if v.is_nan() {
                        continue;
                    }
                    for &k in &blocks_of(z, dims[2]) {
                        for &j in &blocks_of(y, dims[1]) {
                            for &i in &blocks_of(x, dims[0]) {
                                let b = i + n[0] * (j + n[1] * k);
                                lo[b] = lo[b].min(v);
                                hi[b] = hi[b].max(v);
                            }
                        }
                    }
                }
            }
        }
        lo.into_iter().zip(hi).flat_map(|(a, b)| [a, b]).collect()
    }

    fn random_texels(seed: u64, dims: [usize; 3]) -> Vec<f32> {
        let mut s = seed;
        (0..dims.iter().product::<usize>())
            .map(|_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let r = (s >> 40) as f32 / (1u64 << 24) as f32;
                if r < 0.03 {
                    f32::NAN
                } else {
                    100.0 * r - 20.0
                }
            })
            .collect()
    }

    #[test]
    fn blocks_tile_the_cells() {
        assert_eq!(blocks([1, 2, 5]), [1, 1, 1]);
        assert_eq!(blocks([6, 9, 10]), [2, 2, 3]);
        assert_eq!(blocks([0, 65, 66]), [1, 16, 17]);
        assert_eq!(block_texels(0, 1), 0..1);
        assert_eq!(block_texels(1, 9), 4..9);
        assert_eq!(block_texels(1, 7), 4..7);
        assert_eq!(ranges_len([9, 9, 9]), 16);
    }

    #[test]
    fn measured_ranges_match_the_texel_by_texel_rule() {
        for (seed, dims) in
            [[1, 1, 1], [2, 3, 1], [5, 5, 5], [6, 7, 9], [9, 1, 13], [17, 10, 4], [33, 33, 33]].into_iter().enumerate()
        {
            let texels = random_texels(seed as u64, dims);
            assert_eq!(measure(&texels, dims).unwrap(), measure_by_texel(&texels, dims), "{dims:?}");
        }
        // NaN only: the empty range.
        assert_eq!(measure(&[f32::NAN; 8], [2, 2, 2]).unwrap(), vec![f32::INFINITY, f32::NEG_INFINITY]);
        let e = measure(&[0.0; 7], [2, 2, 2]).unwrap_err().to_string();
        assert!(e.contains("7 texels for a 2x2x2 brick"), "{e}");
    }

    #[test]
    fn the_opacity_table_test_by_hand() {
        // 5 cells over [0, 4]: cell k at value k; opacity only in cell 2.
        let mut rgba = vec![0.5f32; 20];
        for k in 0..5 {
            rgba[4 * k + 3] = if k == 2 { 0.3 } else { 0.0 };
        }
        let t = OpacityTable::new(&rgba, 0.0, 4.0);
        // Linear between cells: nonzero on (1, 3).
        assert!(t.any_visible(1.5, 1.5) && t.any_visible(2.0, 2.0) && t.any_visible(0.0, 4.0));
        assert!(t.any_visible(1.0, 1.2), "floor(1) = 1, ceil(1.2) = 2: cell 2 in reach");
        assert!(!t.any_visible(0.0, 1.0) && !t.any_visible(3.0, 4.0) && !t.any_visible(3.5, 9.0));
        // Clamped: below lo is cell 0, above hi cell 4.
        assert!(!t.any_visible(-10.0, -1.0) && !t.any_visible(7.0, 70.0));
        // Empty ranges and NaN: no data.
        assert!(!t.any_visible(f64::INFINITY, f64::NEG_INFINITY) && !t.any_visible(f64::NAN, 2.0));
        assert!(!OpacityTable::new(&[], 0.0, 1.0).any_visible(0.0, 1.0));
    }

    #[test]
    fn the_opacity_table_test_against_sampling() {
        // Random tables: the test says visible exactly when a fine sampling
        // of the linear interpolation between cells finds opacity above 0.
        let mut s = 11u64;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let n = 2 + (next() * 10.0) as usize;
            let rgba: Vec<f32> = (0..n).flat_map(|_| [0.0, 0.0, 0.0, if next() < 0.7 { 0.0 } else { 0.5 }]).collect();
            let (lo, hi) = (-3.0, 5.0);
            let t = OpacityTable::new(&rgba, lo, hi);
            let a = lo - 1.0 + 10.0 * next();
            let b = a + 3.0 * next();
            let opacity = |v: f64| {
                let u = ((v - lo) * (n - 1) as f64 / (hi - lo)).clamp(0.0, (n - 1) as f64);
                let k = (u.floor() as usize).min(n - 2);
                let w = u - k as f64;
                (1.0 - w) * rgba[4 * k + 3] as f64 + w * rgba[4 * k + 7] as f64
            };
            let sampled = (0..=4000).any(|i| opacity(a + (b - a) * i as f64 / 4000.0) > 0.0);
            // The cell test is conservative at cell ends a sampling misses
            // (a range ending exactly on a zero cell next to a nonzero one).
            if sampled {
                assert!(t.any_visible(a, b), "[{a}, {b}] of {rgba:?}");
            } else if t.any_visible(a, b) {
                let cells = (a - lo) * (n - 1) as f64 / (hi - lo);
                let cells_b = (b - lo) * (n - 1) as f64 / (hi - lo);
                assert!(cells.fract().abs() < 1e-3 || cells_b.fract().abs() < 1e-3 || b - a < 1e-3, "[{a}, {b}]");
            }
        }
    }

    #[test]
    fn the_visible_box_is_the_box_of_the_visible_blocks() {
        // 13 x 9 x 5 texels: blocks 3 x 2 x 1. Zero everywhere but a 3 in
        // texel (9, 2, 1), a corner of cells 8 and 9 in x (block 2), 1 and 2 in
        // y (block 0), 0 and 1 in z (block 0).
        let dims = [13, 9, 5];
        let mut texels = vec![0.0f32; 13 * 9 * 5];
        texels[9 + 13 * (2 + 9)] = 3.0;
        let ranges = measure(&texels, dims).unwrap();
        let mut rgba = vec![0.0f32; 4 * 11];
        rgba[4 * 10 + 3] = 1.0; // opacity only at the top of [0, 10]: values near 10.
        let t = OpacityTable::new(&rgba, 0.0, 3.0);
        let b = visible_box(&ranges, dims, &t).unwrap().unwrap();
        assert_eq!(b, TexelBox { lo: [8.0, 0.0, 0.0], hi: [12.0, 4.0, 4.0] });
        // Clipped to the last texel.
        texels[12 + 13 * (8 + 9 * 4)] = 3.0;
        let b = visible_box(&measure(&texels, dims).unwrap(), dims, &t).unwrap().unwrap();
        assert_eq!(b, TexelBox { lo: [8.0, 0.0, 0.0], hi: [12.0, 8.0, 4.0] });
        // Nothing visible: None. All visible: the whole brick.
        assert_eq!(visible_box(&ranges, dims, &OpacityTable::new(&[0.0; 8], 0.0, 1.0)).unwrap(), None);
        let all = OpacityTable::new(&[1.0; 8], 0.0, 1.0);
        assert_eq!(visible_box(&ranges, dims, &all).unwrap(), Some(TexelBox { lo: [0.0; 3], hi: [12.0, 8.0, 4.0] }));
        let e = visible_box(&ranges[1..], dims, &all).unwrap_err().to_string();
        assert!(e.contains("block range values"), "{e}");
        // World: texel t at min + t step, within the brick.
        let w = visible_bounds(&[1.0, 25.0, 0.0, 8.0, -2.0, 2.0], [2.0, 1.0, 1.0], &b);
        assert_eq!(w, [17.0, 25.0, 0.0, 8.0, -2.0, 2.0]);
    }

    #[test]
    fn a_brick_of_no_data_is_not_drawn() {
        let dims = [5, 5, 5];
        let ranges = measure(&[f32::NAN; 125], dims).unwrap();
        assert_eq!(visible_box(&ranges, dims, &OpacityTable::new(&[1.0; 8], 0.0, 1.0)).unwrap(), None);
    }
}
