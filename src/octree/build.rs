//! Building the Volume Octree: the leaf kernel in parallel, then a reduction
//! up the tree, then the nodal error lists.
//!
//! For a node n at level k and subsampling level p (stride `s = 2^(L-k-p)`),
//! the raw nodal error is `e_p(n) = max over v in n of |f(v) - T_s(v)|`. The
//! closed box of n is the union of its leaves' closed boxes, so
//! `e_p(n) = max over leaves l of n of r_(L-k-p)(l)`: one kernel pass over the
//! leaves gives every error of every node.
//!
//! Raw errors need not decrease with p (1D: samples 0, -1, 1, 0, 0 have error 1
//! at stride 4 and 1.5 at stride 2). The octree stores the monotone envelope
//!
//! ```text
//! E_p(n) = max over q >= p of e_q(n) / (max f - min f)
//! ```
//!
//! normalised by the data range and rounded up to `f32`: a bound on the error
//! of drawing n at level p or finer, non-increasing in p, with `E_(L-k) = 0`
//! (not stored). A node with `E_0 = 0` is homogeneous (the data is trilinear
//! over it) and terminal. Because rounding up is monotone, the stored values
//! satisfy `E_p(parent) = max over children c of E_(p-1)(c)` exactly, which
//! [`super::validate`] checks.
//!
//! For ranking refinements by what they buy (see [`crate::plan::select`]) the
//! octree also stores the squared error of every node and level,
//!
//! ```text
//! Q_p(n) = sum over v in n of (f(v) - T_s(v))^2 / (max f - min f)^2
//! ```
//!
//! summed over the half-open boxes of n's leaves (each sample counted once).
//!
//! NaN is no data (see [`crate::data::grid`]). Min and max skip it (a node of NaN
//! only keeps the empty range `(+inf, -inf)`). A sample that is NaN in exactly
//! one of `f` and `T_s` is a hole one picture has and the other has not: the
//! coarse picture shows a hole where data exists, or data where there is none.
//! It counts as the full value range, so that the selection refines there:
//!
//! ```text
//! E_p(n) = 1                        some sample of n is a hole at a stride of level >= p
//! Q_p(n) = (sum of finite (f - T_s)^2) / (max f - min f)^2 + (hole samples of n at stride s)
//! ```
//!
//! and a sample NaN in both counts nothing. A node whose coarse picture has
//! the same holes as its data and is trilinear elsewhere is homogeneous.
//!
//! Extreme values: when the data's largest magnitude is beyond `2^400` or
//! below `2^-400`, differences `f - T` (near `f64::MAX`) or their squares
//! would over- or underflow; the leaves are then computed on `k f`, `k` a
//! power of two ([`super::trilinear::kernel_scale`]), and normalised by the
//! range of `k f`: the same relative errors, computed without overflow.
//!
//! Determinism: each leaf is computed alone and maxima are exact, so the
//! result is bit-identical on any number of threads.

use super::layout::Layout;
use super::leaf_stats::{leaf_stats, KernelPath, LeafStats, Scratch, HOLE};
use super::trilinear::kernel_scale;
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use rayon::prelude::*;
use std::time::Instant;

/// Default leaf brick size in cells per axis; see `docs/BENCHMARKS.md` for the
/// build-time and memory measurements behind it.
pub const DEFAULT_LEAF_SIZE: usize = 16;

/// Options of [`VolumeOctree::build`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BuildOptions {
    /// Cells per axis of a leaf brick: a power of two from 2 to 256.
    pub leaf_size: usize,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions { leaf_size: DEFAULT_LEAF_SIZE }
    }
}

/// Leaves per progress step (and per cancellation check).
const CHUNK_LEAVES: usize = 256;

struct LeafPass<'p> {
    layout: &'p Layout,
    scale: f64,
    path: KernelPath,
    progress: &'p mut dyn FnMut(f64) -> bool,
}

impl GridVisitor for LeafPass<'_> {
    type Output = Result<Vec<LeafStats>>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Self::Output {
        let layout = self.layout;
        let leaf = layout.leaf_level();
        let d = layout.level_dims(leaf);
        let count = d[0] * d[1] * d[2];
        let mut out = Vec::with_capacity(count);
        let mut start = 0;
        while start < count {
            let end = (start + CHUNK_LEAVES).min(count);
            let chunk: Vec<LeafStats> = (start..end)
                .into_par_iter()
                .map_init(Scratch::default, |scratch, i| {
                    let c = [i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1])];
                    let (lo, hi) = layout.node_box(leaf, c);
                    if i + 1 < count {
                        // The next leaf's rows load while this one computes (workers take runs of leaves).
                        let n = [(i + 1) % d[0], ((i + 1) / d[0]) % d[1], (i + 1) / (d[0] * d[1])];
                        let (nlo, nhi) = layout.node_box(leaf, n);
                        for z in nlo[2]..=nhi[2] {
                            for y in nlo[1]..=nhi[1] {
                                g.prefetch_row(nlo[0], nhi[0], y, z);
                            }
                        }
                    }
                    leaf_stats(&g, layout, lo, hi, self.scale, self.path, scratch)
                })
                .collect();
            out.extend(chunk);
            start = end;
            if !(self.progress)(start as f64 / count as f64) {
                return Err(Error::Cancelled);
            }
        }
        Ok(out)
    }
}

impl VolumeOctree {
    /// Builds the Volume Octree of `grid`.
    pub fn build(grid: &Grid<'_>, options: &BuildOptions) -> Result<VolumeOctree> {
        Self::build_with_progress(grid, options, &mut |_| true)
    }

    /// Builds the Volume Octree, calling `progress(fraction)` between chunks
    /// of leaf bricks; returning `false` cancels the build with
    /// [`Error::Cancelled`] (nothing half-built is returned).
    pub fn build_with_progress(
        grid: &Grid<'_>,
        options: &BuildOptions,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<VolumeOctree> {
        Self::build_with_kernel(grid, options, KernelPath::Fast, progress)
    }

    /// [`VolumeOctree::build_with_progress`] with the leaf kernel's path
    /// chosen: [`KernelPath::General`] is the reference the fast path is
    /// tested and benchmarked against (the same octree, bit for bit).
    pub fn build_with_kernel(
        grid: &Grid<'_>,
        options: &BuildOptions,
        path: KernelPath,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<VolumeOctree> {
        let started = Instant::now();
        let layout = Layout::new(grid.dims(), options.leaf_size)?;
        let mut leaves = grid.visit(LeafPass { layout: &layout, scale: 1.0, path, progress: &mut *progress })?;
        // Extreme values (beyond 2^400 or below 2^-400 in magnitude): their
        // differences or squares over- or underflowed; again on k f.
        let (lo, hi) = leaves.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s.min), b.max(s.max)));
        let scale = kernel_scale(lo, hi);
        if scale != 1.0 {
            leaves = grid.visit(LeafPass { layout: &layout, scale, path, progress })?;
        }
        let octree = reduce(layout, leaves, scale, started);
        debug_assert_eq!(octree.validate(), Ok(()));
        Ok(octree)
    }
}

/// Reduces the leaf statistics up the tree and stores min, max and the
/// normalised error envelopes of every node.
fn reduce(layout: Layout, leaves: Vec<LeafStats>, scale: f64, started: Instant) -> VolumeOctree {
    let strides = layout.root_log2 as usize;
    let slots = layout.node_slots();
    let mut min = vec![0.0f64; slots];
    let mut max = vec![0.0f64; slots];
    // raw[id * strides + j - 1]: raw error of stride 2^j over the node's box.
    let mut raw = vec![0.0f64; slots * strides];
    // squared[id * strides + j - 1]: squared error of stride 2^j, summed over the node's leaves.
    let mut squared = vec![0.0f64; slots * strides];
    // holes[id * strides + j - 1]: hole samples of stride 2^j, summed over the node's leaves.
    let mut holes = vec![0.0f64; slots * strides];
    let leaf = layout.leaf_level();
    let off = layout.level_offset(leaf);
    for (i, s) in leaves.into_iter().enumerate() {
        min[off + i] = s.min;
        max[off + i] = s.max;
        raw[(off + i) * strides..(off + i + 1) * strides].copy_from_slice(&s.raw);
        squared[(off + i) * strides..(off + i + 1) * strides].copy_from_slice(&s.squared);
        holes[(off + i) * strides..(off + i + 1) * strides].copy_from_slice(&s.holes);
    }
    for level in (0..leaf).rev() {
        let d = layout.level_dims(level);
        for z in 0..d[2] {
            for y in 0..d[1] {
                for x in 0..d[0] {
                    let id = layout.id(level, [x, y, z]).0 as usize;
                    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                    let mut acc = vec![0.0f64; strides];
                    let mut sum = vec![0.0f64; strides];
                    let mut hole_sum = vec![0.0f64; strides];
                    for (cl, cc) in layout.children(level, [x, y, z]) {
                        let c = layout.id(cl, cc).0 as usize;
                        lo = lo.min(min[c]);
                        hi = hi.max(max[c]);
                        for (a, &r) in acc.iter_mut().zip(&raw[c * strides..(c + 1) * strides]) {
                            *a = a.max(r);
                        }
                        for (a, &q) in sum.iter_mut().zip(&squared[c * strides..(c + 1) * strides]) {
                            *a += q;
                        }
                        for (a, &h) in hole_sum.iter_mut().zip(&holes[c * strides..(c + 1) * strides]) {
                            *a += h;
                        }
                    }
                    min[id] = lo;
                    max[id] = hi;
                    raw[id * strides..(id + 1) * strides].copy_from_slice(&acc);
                    squared[id * strides..(id + 1) * strides].copy_from_slice(&sum);
                    holes[id * strides..(id + 1) * strides].copy_from_slice(&hole_sum);
                }
            }
        }
    }
    // The range of k f, in the units of the raw and squared errors.
    let range = max[0] * scale - min[0] * scale;
    let error_offset = layout.error_offsets();
    let total = error_offset[layout.levels()];
    let mut errors = vec![0.0f32; total];
    let mut squared_errors = vec![0.0f32; total];
    let range2 = if range > 0.0 { range * range } else { 1.0 };
    for level in 0..layout.levels() {
        let n = layout.error_count(level);
        let first = layout.level_offset(level);
        let count = layout.level_offset(level + 1) - first;
        for local in 0..count {
            let r = &raw[(first + local) * strides..(first + local + 1) * strides];
            let q = &squared[(first + local) * strides..(first + local + 1) * strides];
            let h = &holes[(first + local) * strides..(first + local + 1) * strides];
            let at = error_offset[level] + local * n;
            for (p, e2) in squared_errors[at..at + n].iter_mut().enumerate() {
                *e2 = squared_error(q[n - p - 1], h[n - p - 1], range2);
            }
            let e = &mut errors[error_offset[level] + local * n..error_offset[level] + (local + 1) * n];
            // E_p = max over strides 2^1 ..= 2^(L-k-p), walking p from fine to coarse.
            let mut envelope = 0.0f64;
            for p in (0..n).rev() {
                envelope = envelope.max(r[n - p - 1]);
                e[p] = if envelope == HOLE { 1.0 } else { normalise(envelope, range) };
            }
        }
    }
    VolumeOctree::from_parts(
        layout,
        min,
        max,
        errors,
        squared_errors,
        error_offset,
        started.elapsed().as_secs_f64() * 1e3,
    )
}

/// `Q = q / range2 + holes`: the squared error of the finite samples
/// normalised, plus 1 (the full range, squared and normalised) per hole sample.
pub fn squared_error(q: f64, holes: f64, range2: f64) -> f32 {
    (q / range2 + holes) as f32
}

/// `e / range` rounded up to the next `f32` (0 when the range is 0).
pub fn normalise(e: f64, range: f64) -> f32 {
    if range <= 0.0 || e <= 0.0 {
        return 0.0;
    }
    let x = e / range;
    let f = x as f32;
    if (f as f64) < x {
        f.next_up()
    } else {
        f
    }
}
