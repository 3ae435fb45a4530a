//! The leaf kernel's fast path: every stride's raw and squared error of a
//! brick whose samples, and the coarse samples its strides interpolate, are
//! all finite, from the brick's samples read once (see [`super::leaf_stats`]
//! for the definitions of `r_j` and `q_j`).
//!
//! The brick is held as `f64` in the worker's cache. Per stride `s = 2^j` the
//! coarse samples it interpolates (the lattice `C` of multiples of `s` that
//! bracket the brick, clamped to the grid) are gathered once; then, slice by
//! slice and row by row,
//!
//! ```text
//! v(xa, yb) = C(xa, yb, z0) + (C(xa, yb, z1) - C(xa, yb, z0)) * tz     per slice
//! w(xa)     = v(xa, y0) + (v(xa, y1) - v(xa, y0)) * ty                 per row
//! T(x)      = w(x0) + (w(x1) - w(x0)) * tx                             per sample
//! ```
//!
//! are the operations of [`super::trilinear::eval`] in its order, so `T` is
//! the same number. Along a row, `w(x0)` and `w(x1) - w(x0)` are the same for
//! the `s` samples of a coarse cell: a stride of 2 interleaves `w` with the
//! cell midpoints `w + dw * 0.5`, a larger stride broadcasts them over four
//! samples at a time. A sample on the coarse lattice (`tx = 0`) has
//! `T = w(x0) + dw * 0`, which equals `w(x0)` up to the sign of zero; `|f - T|`
//! and `(f - T)^2` do not see that sign, so the 2-stride path takes `w(x0)`.
//!
//! The squared error of a row is summed as the general kernel sums it: four
//! lanes over `x ≡ k (mod 4)` up to the last multiple of four of the row's
//! half-open extent, the lanes combined as `(l0 + l1) + (l2 + l3)`, then the
//! remaining samples in order; the rows are added in z, y order. Maxima are
//! exact in any order. The result is therefore bit-identical to the general
//! kernel's.

// The path is compiled for x86-64 with AVX2; elsewhere the general kernel takes every brick.
#![cfg_attr(not(target_arch = "x86_64"), allow(dead_code, unused_imports))]

use super::lattice::Lattice;
use super::trilinear::{coarse_positions, lerp_scaled};
#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// Reusable buffers of the fast path (one per worker).
#[derive(Debug, Default)]
pub struct FiniteScratch {
    xs: Vec<usize>,
    ys: Vec<usize>,
    zs: Vec<usize>,
    coarse: Vec<f64>,
    v: Vec<f64>,
    w: Vec<f64>,
    dw: Vec<f64>,
    t: Vec<f64>,
    d: Vec<f64>,
    frac: Vec<f64>,
    cell: Vec<usize>,
    rows: Vec<(usize, usize, f64)>,
}

impl FiniteScratch {
    /// The longest buffer: bounded by the brick's rows and coarse lattice.
    pub fn longest_buffer(&self) -> usize {
        [self.xs.len(), self.ys.len(), self.zs.len(), self.coarse.len(), self.v.len(), self.w.len()]
            .into_iter()
            .chain([self.dw.len(), self.t.len(), self.d.len(), self.frac.len(), self.cell.len(), self.rows.len()])
            .max()
            .unwrap_or(0)
    }
}

/// The brick being measured: its closed box, samples (`k f`, x fastest) and
/// the half-open extent summed per axis.
pub struct Brick<'b> {
    /// Closed index box.
    pub lo: [usize; 3],
    /// Closed index box.
    pub hi: [usize; 3],
    /// The samples of the closed box times the kernel scale, x fastest.
    pub samples: &'b [f64],
    /// Samples per axis counted in the squared error (the half-open box).
    pub summed: [usize; 3],
}

/// Writes `r_j` into `raw[j - 1]` and `q_j` into `squared[j - 1]` for every
/// stride `2^j`, `j = 1 ..= L`, and returns true; returns false (leaving
/// partial results) when a coarse sample is not finite, for the general
/// kernel to take the brick. The brick's own samples must be finite.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub unsafe fn finite_brick_errors<G: Lattice>(
    g: &G,
    brick: &Brick<'_>,
    scale: f64,
    raw: &mut [f64],
    squared: &mut [f64],
    scratch: &mut FiniteScratch,
) -> bool {
    for (j, (r, q)) in raw.iter_mut().zip(squared.iter_mut()).enumerate() {
        if !gather_coarse(g, brick, 1 << (j + 1), scale, scratch) {
            return false;
        }
        let j = j as u32 + 1;
        // Four samples [4c, 4c + 4) share a cell when the row starts on a multiple of 4 and s >= 4.
        let lo = brick.lo[0];
        // SAFETY: AVX2 is enabled on this function.
        let (m, sq) = unsafe {
            match j {
                1 if lo.is_multiple_of(2) => stride_errors::<PAIRS>(brick, j, scratch),
                2.. if lo.is_multiple_of(4) => stride_errors::<BROADCAST>(brick, j, scratch),
                _ => stride_errors::<PER_SAMPLE>(brick, j, scratch),
            }
        };
        *r = m;
        *q = sq;
    }
    true
}

/// Fills the coarse positions and `C` of stride `s`; false when a value is not finite.
#[inline(always)]
fn gather_coarse<G: Lattice>(g: &G, brick: &Brick<'_>, s: usize, scale: f64, sc: &mut FiniteScratch) -> bool {
    let (lo, hi) = (brick.lo, brick.hi);
    coarse_positions(lo[0], hi[0], s, g.dims()[0], &mut sc.xs);
    coarse_positions(lo[1], hi[1], s, g.dims()[1], &mut sc.ys);
    coarse_positions(lo[2], hi[2], s, g.dims()[2], &mut sc.zs);
    let wx = hi[0] - lo[0] + 1;
    let wy = hi[1] - lo[1] + 1;
    let inside = |p: usize, a: usize| p >= lo[a] && p <= hi[a];
    sc.coarse.clear();
    let mut finite = true;
    for &zc in &sc.zs {
        for &yc in &sc.ys {
            let row_inside = inside(zc, 2) && inside(yc, 1);
            // The row's start in the brick's samples (read only inside it).
            let base = if row_inside { ((zc - lo[2]) * wy + yc - lo[1]) * wx } else { 0 };
            for &xc in &sc.xs {
                let c = if row_inside && inside(xc, 0) {
                    brick.samples[base + xc - lo[0]]
                } else {
                    g.at(xc, yc, zc) * scale
                };
                finite &= c.is_finite();
                sc.coarse.push(c);
            }
        }
    }
    finite
}

/// `(x0, t)` of `x` for stride `2^j`: `x0 = floor(x / s) s`, `t = (x - x0) / s`, as [`super::trilinear::bracket`].
#[inline(always)]
fn bracket_pow2(x: usize, j: u32) -> (usize, f64) {
    let x0 = (x >> j) << j;
    (x0, (x - x0) as f64 / (1usize << j) as f64)
}

/// `out[i] = a[i] + (b[i] - a[i]) * t`, four lanes at a time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn lerp_slices(out: &mut [f64], a: &[f64], b: &[f64], t: f64) {
    let n = out.len().min(a.len()).min(b.len());
    let tv = _mm256_set1_pd(t);
    let mut i = 0;
    while i + 4 <= n {
        // SAFETY: i + 4 <= n, the length of all three slices.
        unsafe {
            let (av, bv) = (_mm256_loadu_pd(a.as_ptr().add(i)), _mm256_loadu_pd(b.as_ptr().add(i)));
            _mm256_storeu_pd(out.as_mut_ptr().add(i), _mm256_add_pd(av, _mm256_mul_pd(_mm256_sub_pd(bv, av), tv)));
        }
        i += 4;
    }
    for i in i..n {
        out[i] = lerp_scaled(a[i], b[i], t);
    }
}

/// How `T` is formed along a row: stride 2 interleaves `w` and the cell midpoints.
const PAIRS: u8 = 0;
/// Four samples at a time in one coarse cell: `w` and `dw` broadcast.
const BROADCAST: u8 = 1;
/// Sample by sample from the cell table.
const PER_SAMPLE: u8 = 2;

/// `(r, q)` of stride `s = 2^j` over the brick, from the coarse lattice in
/// `sc`, `T` formed along rows as `MODE` says ([`PAIRS`], [`BROADCAST`] or [`PER_SAMPLE`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn stride_errors<const MODE: u8>(brick: &Brick<'_>, j: u32, sc: &mut FiniteScratch) -> (f64, f64) {
    let (lo, hi) = (brick.lo, brick.hi);
    let wx = hi[0] - lo[0] + 1;
    let wy = hi[1] - lo[1] + 1;
    let (nxs, nys, nzs) = (sc.xs.len(), sc.ys.len(), sc.zs.len());
    let (x_first, y_first, z_first) = ((lo[0] >> j) << j, (lo[1] >> j) << j, (lo[2] >> j) << j);
    // tx = (x mod s) / s and the coarse cell of each sample of a row.
    sc.frac.clear();
    sc.frac.extend((lo[0]..=hi[0]).map(|x| bracket_pow2(x, j).1));
    sc.cell.clear();
    sc.cell.extend((lo[0]..=hi[0]).map(|x| (x - x_first) >> j));
    let (pairs, broadcast) = (MODE == PAIRS, MODE == BROADCAST);
    sc.t.resize(wx, 0.0);
    sc.d.resize(wx, 0.0);
    sc.w.resize(nxs, 0.0);
    sc.dw.resize(nxs, 0.0);
    sc.v.resize(nxs * nys, 0.0);
    // Per row y: the offsets of v(., y0) and v(., y1) and ty.
    sc.rows.clear();
    sc.rows.extend((lo[1]..=hi[1]).map(|y| {
        let (y0, ty) = bracket_pow2(y, j);
        let yi0 = (y0 - y_first) >> j;
        (yi0 * nxs, (yi0 + 1).min(nys - 1) * nxs, ty)
    }));
    let FiniteScratch { coarse, v, w, dw, t, d, frac, cell, rows, .. } = sc;
    let chunks = wx / 4;
    let abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX));
    let half = _mm_set1_pd(0.5);
    let mut lanes = _mm256_setzero_pd();
    let mut err = 0.0f64;
    let mut sq = 0.0f64;
    let plane = nxs * nys;
    for z in lo[2]..=hi[2] {
        let (z0, tz) = bracket_pow2(z, j);
        let zi0 = (z0 - z_first) >> j;
        let zi1 = (zi0 + 1).min(nzs - 1);
        // SAFETY: AVX2 is enabled on this function.
        unsafe { lerp_slices(v, &coarse[zi0 * plane..(zi0 + 1) * plane], &coarse[zi1 * plane..(zi1 + 1) * plane], tz) };
        let z_summed = z - lo[2] < brick.summed[2];
        for (y, &(v0, v1, ty)) in (lo[1]..=hi[1]).zip(rows.iter()) {
            // SAFETY: AVX2 is enabled on this function.
            unsafe { lerp_slices(w, &v[v0..v0 + nxs], &v[v1..v1 + nxs], ty) };
            // dw(xi) = w(min(xi + 1, nxs - 1)) - w(xi).
            let mut xi = 0;
            while xi + 5 <= nxs {
                // SAFETY: xi + 5 <= nxs, the length of w and dw.
                unsafe {
                    let (a, b) = (_mm256_loadu_pd(w.as_ptr().add(xi)), _mm256_loadu_pd(w.as_ptr().add(xi + 1)));
                    _mm256_storeu_pd(dw.as_mut_ptr().add(xi), _mm256_sub_pd(b, a));
                }
                xi += 4;
            }
            for xi in xi..nxs - 1 {
                dw[xi] = w[xi + 1] - w[xi];
            }
            // w(nxs - 1) - w(nxs - 1), finite.
            dw[nxs - 1] = 0.0;
            if !pairs && !broadcast {
                for x in 0..wx {
                    t[x] = w[cell[x]] + dw[cell[x]] * frac[x];
                }
            }
            let start = ((z - lo[2]) * wy + (y - lo[1])) * wx;
            let row = &brick.samples[start..start + wx];
            let summed = if z_summed && y - lo[1] < brick.summed[1] { brick.summed[0] } else { 0 };
            let n4 = summed / 4 * 4;
            // d = f - T; lanes keep max |d|; acc the four-lane sum of d^2 over x < n4.
            let mut acc = _mm256_setzero_pd();
            for c in 0..chunks {
                let x = 4 * c;
                // SAFETY: x + 4 <= wx, the length of row, t, d, frac and cell;
                // pairs: cells 2c + 1 <= cell[wx - 1] < nxs, the length of w and dw.
                unsafe {
                    let tv = if pairs {
                        let (wv, dv) = (_mm_loadu_pd(w.as_ptr().add(2 * c)), _mm_loadu_pd(dw.as_ptr().add(2 * c)));
                        let mv = _mm_add_pd(wv, _mm_mul_pd(dv, half));
                        _mm256_set_m128d(_mm_unpackhi_pd(wv, mv), _mm_unpacklo_pd(wv, mv))
                    } else if broadcast {
                        let k = *cell.get_unchecked(x);
                        let (a, b) = (_mm256_set1_pd(*w.get_unchecked(k)), _mm256_set1_pd(*dw.get_unchecked(k)));
                        _mm256_add_pd(a, _mm256_mul_pd(b, _mm256_loadu_pd(frac.as_ptr().add(x))))
                    } else {
                        _mm256_loadu_pd(t.as_ptr().add(x))
                    };
                    let dv = _mm256_sub_pd(_mm256_loadu_pd(row.as_ptr().add(x)), tv);
                    _mm256_storeu_pd(d.as_mut_ptr().add(x), dv);
                    lanes = _mm256_max_pd(_mm256_and_pd(dv, abs_mask), lanes);
                    if x < n4 {
                        acc = _mm256_add_pd(acc, _mm256_mul_pd(dv, dv));
                    }
                }
            }
            for x in chunks * 4..wx {
                let tx = w[cell[x]] + dw[cell[x]] * frac[x];
                d[x] = row[x] - tx;
                let a = d[x].abs();
                err = if a > err { a } else { err };
            }
            if summed > 0 {
                let mut l = [0.0f64; 4];
                // SAFETY: l holds four f64.
                unsafe { _mm256_storeu_pd(l.as_mut_ptr(), acc) };
                let mut total = (l[0] + l[1]) + (l[2] + l[3]);
                for &dx in &d[n4..summed] {
                    total += dx * dx;
                }
                sq += total;
            }
        }
    }
    let mut l = [0.0f64; 4];
    // SAFETY: l holds four f64.
    unsafe { _mm256_storeu_pd(l.as_mut_ptr(), lanes) };
    let max = |a: f64, b: f64| if b > a { b } else { a };
    (max(err, max(max(l[0], l[1]), max(l[2], l[3]))), sq)
}
