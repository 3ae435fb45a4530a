//! The per-brick kernel: min, max and the raw stride errors of one leaf brick.
//!
//! For every stride `s = 2^j`, `j = 1 ..= L`, the raw stride error of a brick is
//!
//! ```text
//! r_j(brick) = max over the samples v of the brick's closed box of |f(v) - T_s(v)|
//! ```
//!
//! with T_s from [`super::trilinear`], and the squared stride error
//!
//! ```text
//! q_j(brick) = sum over the samples v of the brick's half-open box of (f(v) - T_s(v))^2
//! ```
//!
//! (half-open: a face shared with the next brick belongs to that brick; the
//! grid's last samples belong to the last brick), so the bricks partition the
//! samples and a node's `q_j` is the sum over its leaves.
//!
//! NaN is no data (see [`crate::data::grid`]): min and max skip it (a brick of NaN
//! only has the empty range `(+inf, -inf)`), and the error of a sample is
//!
//! ```text
//! d(v) = 0            f(v) and T_s(v) both NaN
//! d(v) = HOLE         exactly one of them NaN  (r_j = HOLE; counted in h_j, not in q_j)
//! d(v) = f(v) - T_s   otherwise
//! ```
//!
//! where `T_s(v)` is NaN when any of its 8 lattice corners is. `h_j` counts the
//! hole samples of the half-open box; [`super::build`] weighs each as the full
//! value range. A node's nodal
//! errors are maxima of `r_j` over its leaves (see [`super::build`]). Strides up to the brick size
//! use coarse cells inside the brick; larger strides use the one coarse cell
//! that contains the whole brick.
//!
//! A brick whose samples and coarse samples are finite takes the fast path
//! of [`super::finite_brick`] (same results, bit for bit); the general
//! kernel below takes the rest.
//!
//! Work per sample: the brick is read once into a buffer of `f64`. For each
//! z-slice and stride, the z-interpolated values `v(xa, yb)` at the coarse
//! positions are computed once, each row's `w(xa) = lerp(v(xa, y0), v(xa, y1), ty)`
//! from them, then T along the row (`w0 + (w1 - w0) * tx`) and a max of
//! `|f - T|` over the row that the compiler vectorises. These are the same
//! operations, in the same order, as [`super::trilinear::eval`], so the
//! result equals the brute-force definition bit for bit.

use super::finite_brick::FiniteScratch;
#[cfg(target_arch = "x86_64")]
use super::finite_brick::{finite_brick_errors, Brick};
use super::lattice::Lattice;
use super::layout::Layout;
use super::trilinear::{bracket, coarse_positions, lerp_scaled};

/// The raw error of a sample that is no data in exactly one of the fine and
/// the coarse picture: larger than any finite error, and kept by every max.
pub const HOLE: f64 = f64::INFINITY;

/// Statistics of one leaf brick.
#[derive(Debug, Clone, PartialEq)]
pub struct LeafStats {
    /// Smallest sample in the closed box.
    pub min: f64,
    /// Largest sample in the closed box.
    pub max: f64,
    /// `raw[j - 1]` = r_j, the raw error of stride `2^j`, `j = 1 ..= L`.
    pub raw: Vec<f64>,
    /// `squared[j - 1]` = q_j, the squared error of stride `2^j` over the
    /// samples where the fine and coarse values are both finite.
    pub squared: Vec<f64>,
    /// `holes[j - 1]` = h_j, the samples of the half-open box where exactly one
    /// of `f` and `T_(2^j)` is NaN.
    pub holes: Vec<f64>,
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
    row: Vec<f64>,
    finite: FiniteScratch,
}

impl Scratch {
    /// The longest of the buffers after a [`leaf_stats`] call: bounded by the
    /// brick (its samples, rows and coarse positions), whatever the stride,
    /// so a leaf's work does not grow with the grid's length.
    pub fn longest_buffer(&self) -> usize {
        [self.brick.len(), self.v.len(), self.w.len(), self.t.len(), self.xs.len(), self.ys.len(), self.frac.len()]
            .into_iter()
            .chain([self.cells.len(), self.finite.longest_buffer()])
            .max()
            .unwrap_or(0)
    }
}

/// `(max |a[i] - b[i]|, sum over i < summed of (a[i] - b[i])^2)` with four
/// independent lanes so it vectorises (`if d > m` is `maxpd`; all values are
/// finite). The max starts from `init`.
#[inline(always)]
fn diff_stats(a: &[f64], b: &[f64], summed: usize, init: f64) -> (f64, f64) {
    let mut lanes = [init; 4];
    let mut sq = [0.0f64; 4];
    let n4 = summed / 4 * 4;
    for (x, y) in a[..n4].chunks_exact(4).zip(b[..n4].chunks_exact(4)) {
        for k in 0..4 {
            let d = x[k] - y[k];
            let m = d.abs();
            lanes[k] = if m > lanes[k] { m } else { lanes[k] };
            sq[k] += d * d;
        }
    }
    let max = |a: f64, b: f64| if b > a { b } else { a };
    let mut m = max(max(lanes[0], lanes[1]), max(lanes[2], lanes[3]));
    let mut total = (sq[0] + sq[1]) + (sq[2] + sq[3]);
    for (i, (x, y)) in a.iter().zip(b).enumerate().skip(n4) {
        let d = x - y;
        m = max(m, d.abs());
        if i < summed {
            total += d * d;
        }
    }
    (m, total)
}

/// [`diff_stats`] for rows holding NaN: `(max |a - b|, sum of (a - b)^2, holes)`
/// with the no-data rule of the module docs (the max is [`HOLE`] when the
/// closed row has a hole; the sum and the hole count cover `i < summed`).
fn hole_stats(a: &[f64], b: &[f64], summed: usize, init: f64) -> (f64, f64, f64) {
    let (mut m, mut total, mut holes) = (init, 0.0, 0.0);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        match (x.is_nan(), y.is_nan()) {
            (true, true) => {}
            (false, false) => {
                let d = x - y;
                m = m.max(d.abs());
                if i < summed {
                    total += d * d;
                }
            }
            _ => {
                m = HOLE;
                if i < summed {
                    holes += 1.0;
                }
            }
        }
    }
    (m, total, holes)
}

/// `(min, max, some NaN)` of `values`, as the scan
///
/// ```text
/// min = if v < min { v } else { min },  max = if v > max { v } else { max }
/// ```
///
/// in order from `(+inf, -inf)` (false for NaN: min and max skip it) would
/// give. Four lanes at a time; exact, since the minimum and maximum are
/// values of the data, except for the sign of a zero (the scan keeps the
/// first of `-0` and `+0`), so a zero result is taken from the scan itself.
#[inline(always)]
fn value_range(values: &[f64]) -> (f64, f64, bool) {
    let scan = |values: &[f64]| {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut nan = false;
        for &v in values {
            min = if v < min { v } else { min };
            max = if v > max { v } else { max };
            nan |= v.is_nan();
        }
        (min, max, nan)
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 4], [f64::NEG_INFINITY; 4]);
    let chunks = values.chunks_exact(4);
    let rest = scan(chunks.remainder());
    for c in chunks {
        for k in 0..4 {
            lo[k] = if c[k] < lo[k] { c[k] } else { lo[k] };
            hi[k] = if c[k] > hi[k] { c[k] } else { hi[k] };
        }
    }
    let nan = [values.iter().fold(false, |n, v| n | v.is_nan())];
    let pick = |a: f64, b: f64, less: bool| if (b < a) == less && b != a { b } else { a };
    let min = [lo[1], lo[2], lo[3], rest.0].into_iter().fold(lo[0], |a, b| pick(a, b, true));
    let max = [hi[1], hi[2], hi[3], rest.1].into_iter().fold(hi[0], |a, b| pick(a, b, false));
    let has_nan = nan.iter().any(|&n| n) || rest.2;
    if min == 0.0 || max == 0.0 {
        return scan(values);
    }
    (min, max, has_nan)
}

/// Half-open extent along an axis: the samples `lo .. hi` of the closed box,
/// plus `hi` itself when it is the grid's last sample.
fn summed_count(lo: usize, hi: usize, n: usize) -> usize {
    hi - lo + usize::from(hi == n - 1)
}

/// `sum over the half-open box of e^2` for `e` trilinear over the closed box
/// `[lo, hi]` with corner values `e[corner]` (corner bit a: hi on axis a).
/// Per axis, with hats `b0 = 1 - t`, `b1 = t`, `t = (x - lo) / (hi - lo)`,
/// `M_a[i][j] = sum over x of b_i(t) b_j(t)`, and
///
/// ```text
/// sum e^2 = sum over corners k, l of e_k e_l  M_x[k_x][l_x] M_y[k_y][l_y] M_z[k_z][l_z]
/// ```
fn trilinear_squared_sum(e: [f64; 8], lo: [usize; 3], hi: [usize; 3], dims: [usize; 3]) -> f64 {
    let m = [0, 1, 2].map(|a| {
        let mut m = [[0.0f64; 2]; 2];
        let span = (hi[a] - lo[a]).max(1) as f64;
        for x in lo[a]..lo[a] + summed_count(lo[a], hi[a], dims[a]) {
            let t = (x - lo[a]) as f64 / span;
            let b = [1.0 - t, t];
            for i in 0..2 {
                for j in 0..2 {
                    m[i][j] += b[i] * b[j];
                }
            }
        }
        m
    });
    let mut total = 0.0;
    for k in 0..8usize {
        for l in 0..8usize {
            let w: f64 = (0..3).map(|a| m[a][(k >> a) & 1][(l >> a) & 1]).product();
            total += e[k] * e[l] * w;
        }
    }
    total.max(0.0)
}

/// `(raw, squared)` of `scale` times a brick of constant value `c` with closed box `[lo, hi]`:
/// every in-brick stride reproduces it exactly. For a stride larger than the
/// brick, T_s is trilinear over the brick, so `|c - T_s|` is largest at one of
/// the brick's eight corners. `None` when a corner's T_s is NaN: the lattice
/// cells the brick's samples interpolate are those its corners do (per axis
/// the cell of `lo`, and of `hi` when `hi` is on the coarse lattice), but not
/// every sample touches the NaN one, so the caller takes the general path.
fn constant_brick<G: Lattice>(
    g: &G,
    layout: &Layout,
    c: f64,
    scale: f64,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Option<(Vec<f64>, Vec<f64>)> {
    let strides = layout.root_log2 as usize;
    let mut raw = vec![0.0f64; strides];
    let mut squared = vec![0.0f64; strides];
    let first_coarse = layout.leaf_log2 as usize + 1;
    for (j, (r, q)) in raw.iter_mut().zip(squared.iter_mut()).enumerate().skip(first_coarse - 1) {
        let s = 1usize << (j + 1);
        let mut e = [0.0f64; 8];
        for (corner, ec) in e.iter_mut().enumerate() {
            let x = if corner & 1 == 0 { lo[0] } else { hi[0] };
            let y = if corner & 2 == 0 { lo[1] } else { hi[1] };
            let z = if corner & 4 == 0 { lo[2] } else { hi[2] };
            *ec = c * scale - super::trilinear::eval(g, s, x, y, z) * scale;
            if ec.is_nan() {
                return None;
            }
            *r = r.max(ec.abs());
        }
        *q = trilinear_squared_sum(e, lo, hi, g.dims());
    }
    Some((raw, squared))
}

/// Which code computes the errors of a brick that is not constant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelPath {
    /// [`super::finite_brick`] when the brick and its coarse samples are
    /// finite, else the general kernel: the build's choice.
    Fast,
    /// The general kernel (stride by stride, with the no-data rule) for
    /// every brick: the reference the fast path is tested against.
    General,
}

/// Computes the [`LeafStats`] of the brick with closed index box `[lo, hi]`:
/// min and max of the samples `f`, and the errors of `k f`, `k` =
/// [`super::trilinear::kernel_scale`] of the grid's range (1 unless its
/// values are extreme).
///
/// On x86-64 CPUs with AVX2 the same code runs compiled for AVX2 (four f64
/// lanes instead of two). Only additions, subtractions, multiplications
/// and comparisons are used, never a fused multiply-add, so the results are
/// the same bit for bit on every CPU.
pub fn leaf_stats<G: Lattice>(
    g: &G,
    layout: &Layout,
    lo: [usize; 3],
    hi: [usize; 3],
    scale: f64,
    path: KernelPath,
    scratch: &mut Scratch,
) -> LeafStats {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { leaf_stats_avx2(g, layout, lo, hi, scale, path, scratch) };
    }
    leaf_stats_inline(g, layout, lo, hi, scale, path, scratch)
}

/// [`leaf_stats_inline`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn leaf_stats_avx2<G: Lattice>(
    g: &G,
    layout: &Layout,
    lo: [usize; 3],
    hi: [usize; 3],
    scale: f64,
    path: KernelPath,
    scratch: &mut Scratch,
) -> LeafStats {
    leaf_stats_inline(g, layout, lo, hi, scale, path, scratch)
}

/// The kernel's body, inlined into each instruction-set variant.
#[inline(always)]
fn leaf_stats_inline<G: Lattice>(
    g: &G,
    layout: &Layout,
    lo: [usize; 3],
    hi: [usize; 3],
    scale: f64,
    path: KernelPath,
    scratch: &mut Scratch,
) -> LeafStats {
    let strides = layout.root_log2 as usize;
    let wx = hi[0] - lo[0] + 1;
    let wy = hi[1] - lo[1] + 1;
    let brick = &mut scratch.brick;
    brick.clear();
    let mut row = std::mem::take(&mut scratch.row);
    for z in lo[2]..=hi[2] {
        for y in lo[1]..=hi[1] {
            g.row_into(lo[0], hi[0], y, z, &mut row);
            brick.extend_from_slice(&row);
        }
    }
    scratch.row = row;
    let (min, max, has_nan) = value_range(brick);
    if scale != 1.0 {
        brick.iter_mut().for_each(|v| *v *= scale);
    }
    let mut raw = vec![0.0f64; strides];
    let mut squared = vec![0.0f64; strides];
    let mut holes = vec![0.0f64; strides];
    let summed = [0, 1, 2].map(|a| summed_count(lo[a], hi[a], g.dims()[a]));
    if min == max && !has_nan {
        if let Some((raw, squared)) = constant_brick(g, layout, min, scale, lo, hi) {
            let holes = vec![0.0f64; strides];
            return LeafStats { min, max, raw, squared, holes };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = path;
    #[cfg(target_arch = "x86_64")]
    if path == KernelPath::Fast && !has_nan && std::arch::is_x86_feature_detected!("avx2") {
        let b = Brick { lo, hi, samples: brick, summed };
        // SAFETY: the CPU supports AVX2, checked just above.
        if unsafe { finite_brick_errors(g, &b, scale, &mut raw, &mut squared, &mut scratch.finite) } {
            return LeafStats { min, max, raw, squared, holes };
        }
    }
    let Scratch { brick, v, w, t, xs, ys, frac, cells, .. } = scratch;
    t.resize(wx, 0.0);
    for (j, ((r, q), h)) in raw.iter_mut().zip(squared.iter_mut()).zip(holes.iter_mut()).enumerate() {
        let s = 1usize << (j + 1);
        coarse_positions(lo[0], hi[0], s, g.dims()[0], xs);
        coarse_positions(lo[1], hi[1], s, g.dims()[1], ys);
        let (x_first, y_first) = (lo[0] / s * s, lo[1] / s * s);
        let (nxs, nys) = (xs.len(), ys.len());
        // tx = (x - x0) / s = (x mod s) / s for the brick's x = lo .. hi (exact:
        // s is a power of two); one entry per sample of the row, not per
        // stride, so a large stride costs no more than a small one.
        frac.clear();
        frac.extend((lo[0]..=hi[0]).map(|x| (x % s) as f64 / s as f64));
        // Row segments [a, b) lying in coarse cell xi (`frac` is indexed like the row).
        cells.clear();
        for xi in 0..nxs {
            let x0 = x_first + xi * s;
            let (a, b) = (x0.max(lo[0]), (x0 + s).min(hi[0] + 1));
            if a < b && x0 < g.dims()[0] {
                cells.push((a - lo[0], b - lo[0], xi, a - lo[0]));
            }
        }
        let mut err = 0.0f64;
        let mut sq = 0.0f64;
        let mut hole_count = 0.0f64;
        for z in lo[2]..=hi[2] {
            let (z0, z1, tz) = bracket(z, s, g.dims()[2]);
            // v(xa, yb) for every coarse (xa, yb) of this slice.
            v.clear();
            for &yb in ys.iter() {
                for &xa in xs.iter() {
                    v.push(lerp_scaled(g.at(xa, yb, z0) * scale, g.at(xa, yb, z1) * scale, tz));
                }
            }
            // NaN in the fine samples or in this slice's coarse values: the rows take the no-data path.
            let nan_rows = has_nan || v.iter().any(|x| x.is_nan());
            for y in lo[1]..=hi[1] {
                let (y0, _, ty) = bracket(y, s, g.dims()[1]);
                let yi0 = (y0 - y_first) / s;
                let yi1 = (yi0 + 1).min(nys - 1);
                w.clear();
                w.extend((0..nxs).map(|xi| lerp_scaled(v[yi0 * nxs + xi], v[yi1 * nxs + xi], ty)));
                // T along the row, cell by cell: w0 + (w1 - w0) * tx.
                for &(a, b, xi, off) in cells.iter() {
                    let (w0, w1) = (w[xi], w[(xi + 1).min(nxs - 1)]);
                    for (tv, &f) in t[a..b].iter_mut().zip(&frac[off..]) {
                        *tv = lerp_scaled(w0, w1, f);
                    }
                }
                let start = ((z - lo[2]) * wy + (y - lo[1])) * wx;
                let in_sum = y - lo[1] < summed[1] && z - lo[2] < summed[2];
                let (row, row_summed) = (&brick[start..start + wx], if in_sum { summed[0] } else { 0 });
                let (m, row_sq, row_holes) = if nan_rows {
                    hole_stats(row, t, row_summed, err)
                } else {
                    let (m, row_sq) = diff_stats(row, t, row_summed, err);
                    (m, row_sq, 0.0)
                };
                err = m;
                sq += row_sq;
                hole_count += row_holes;
            }
        }
        *r = err;
        *q = sq;
        *h = hole_count;
    }
    LeafStats { min, max, raw, squared, holes }
}

#[cfg(test)]
mod tests {
    use super::value_range;

    /// The in-order scan `value_range` must equal, bit for bit.
    fn scan(values: &[f64]) -> (u64, u64, bool) {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut nan = false;
        for &v in values {
            min = if v < min { v } else { min };
            max = if v > max { v } else { max };
            nan |= v.is_nan();
        }
        (min.to_bits(), max.to_bits(), nan)
    }

    #[test]
    fn value_range_equals_the_in_order_scan() {
        let pool = [0.0, -0.0, 1.5, -2.0, f64::NAN, 3.0, -0.0, 0.0, 7.25, -7.25, f64::MIN_POSITIVE];
        // Every length up to 13 and many orders, with zeros of both signs first or later.
        for len in 1..=13 {
            for seed in 0..200usize {
                let v: Vec<f64> =
                    (0..len).map(|i| pool[(i * 7 + seed * 13 + (seed >> 3) * i * i) % pool.len()]).collect();
                let (min, max, nan) = value_range(&v);
                assert_eq!((min.to_bits(), max.to_bits(), nan), scan(&v), "{v:?}");
            }
        }
    }
}
