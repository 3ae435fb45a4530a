//! The Volume Octree built in one pass over z from a [`PlaneSource`],
//! holding a few planes, never the volume: the same octree as
//! [`VolumeOctree::build`], bit for bit.
//!
//! Leaf rows (the leaves of one z index) are computed in z order. The leaf
//! kernel ([`super::leaf_stats`]) of a row whose leaves span planes
//! `lo ..= hi` reads those planes and, for every stride `s = 2^j`, the
//! coarse planes [`coarse_positions`]`(lo, hi, s)`: multiples of `s` from
//! `floor(lo / s) s` to the first one past `hi`, clamped to `n - 1` (the
//! brackets of [`super::trilinear::bracket`]). Those planes are kept in a
//! [`PlaneStack`] as z advances, each plane dropped when the row no longer
//! reads it and read from the source when a row first needs it (a coarse
//! plane ahead of the pass comes from the source's random access), so the
//! pass holds about `B + 1 + log2 B + 3 log2(root / B)` planes. The leaf
//! statistics go to [`StreamReduce`] row by row.
//!
//! Each plane of the volume passes once through the row that owns it
//! (`lo ..` the next row's `lo`): there it is checked (no infinity, NaN
//! counted) and handed to the caller's sink (the store writer), in z order.
//!
//! Extreme values ([`super::trilinear::kernel_scale`] not 1, f64 data
//! only): as in core, the leaves are computed again on `k f` in a second
//! pass over the source (without the sink).

use super::build::BuildOptions;
use super::layout::Layout;
use super::leaf_stats::{leaf_stats, KernelPath, Scratch};
use super::plane_stack::PlaneStack;
use super::stream_reduce::StreamReduce;
use super::trilinear::{coarse_positions, kernel_scale};
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};
use crate::base::limits::check_memory;
use crate::data::grid::Sample;
use crate::data::planes::{into_vec, PlaneSource};
use rayon::prelude::*;
use std::ops::Range;
use std::time::Instant;

/// What a streaming build returns.
#[derive(Debug, Clone, PartialEq)]
pub struct Streamed {
    /// The Volume Octree.
    pub octree: VolumeOctree,
    /// NaN samples ("no data") of the volume.
    pub nan_count: usize,
}

/// Receives each plane range of the pass, in z order, with the stack that holds them.
pub type PlaneSink<'a, T> = dyn FnMut(Range<usize>, &PlaneStack<T>) -> Result<()> + 'a;

/// The planes the leaf row spanning `lo ..= hi` reads, sorted.
pub fn row_planes(layout: &Layout, lo: usize, hi: usize) -> Vec<usize> {
    let n = layout.dims[2];
    let mut planes: Vec<usize> = (lo..=hi).collect();
    let mut coarse = Vec::new();
    for j in 1..=layout.root_log2 as usize {
        coarse_positions(lo, hi, 1 << j, n, &mut coarse);
        planes.extend_from_slice(&coarse);
    }
    planes.sort_unstable();
    planes.dedup();
    planes
}

/// The `lo ..= hi` plane span of leaf row `cz`.
fn row_span(layout: &Layout, cz: usize) -> (usize, usize) {
    let b = layout.leaf_size();
    (cz * b, (cz * b + b).min(layout.dims[2] - 1))
}

impl VolumeOctree {
    /// Builds the Volume Octree of `source` in one pass over z (see the
    /// module docs), calling `progress(fraction)` after each leaf row;
    /// returning `false` cancels with [`Error::Cancelled`].
    ///
    /// # Errors
    ///
    /// As [`VolumeOctree::build`] (bad leaf size, infinite samples, no data),
    /// the source's read errors, and more memory than the process may use.
    pub fn build_streaming(
        source: &dyn PlaneSource,
        options: &BuildOptions,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Streamed> {
        struct Run<'a> {
            source: &'a dyn PlaneSource,
            options: &'a BuildOptions,
            progress: &'a mut dyn FnMut(f64) -> bool,
        }
        impl crate::data::planes::TypeVisitor for Run<'_> {
            type Output = Result<Streamed>;
            fn visit<T: Sample>(self) -> Result<Streamed> {
                build_streaming_into::<T>(self.source, self.options, self.progress, &mut |_, _| Ok(()))
            }
        }
        crate::data::planes::for_type(source.scalar_type(), Run { source, options, progress })
    }
}

/// [`VolumeOctree::build_streaming`] for samples of type `T` (the source's),
/// handing each plane range of the pass to `sink` in z order.
///
/// # Errors
///
/// As [`VolumeOctree::build_streaming`], and `sink`'s first error.
pub fn build_streaming_into<T: Sample>(
    source: &dyn PlaneSource,
    options: &BuildOptions,
    progress: &mut dyn FnMut(f64) -> bool,
    sink: &mut PlaneSink<'_, T>,
) -> Result<Streamed> {
    let started = Instant::now();
    if source.scalar_type().name() != T::NAME {
        return Err(Error::Internal(format!(
            "a {} plane source read as {} samples",
            source.scalar_type().name(),
            T::NAME
        )));
    }
    let shape = source.shape();
    shape.check(1)?;
    let layout = Layout::new(shape.dims, options.leaf_size)?;
    let mut reduce = StreamReduce::new(layout.clone())?;
    let mut scan = PlaneScan::default();
    pass::<T>(source, &layout, 1.0, &mut reduce, progress, Some((sink, &mut scan)))?;
    if scan.nan == shape.point_count() {
        return Err(Error::NoData { count: scan.nan });
    }
    let mut octree = reduce.finish(1.0, 0.0);
    let (lo, hi) = octree.value_range();
    let scale = kernel_scale(lo, hi);
    if scale != 1.0 {
        let mut reduce = StreamReduce::new(layout.clone())?;
        drop(octree);
        pass::<T>(source, &layout, scale, &mut reduce, progress, None)?;
        octree = reduce.finish(scale, 0.0);
    }
    octree.build_ms = started.elapsed().as_secs_f64() * 1e3;
    debug_assert_eq!(octree.validate(), Ok(()));
    Ok(Streamed { octree, nan_count: scan.nan })
}

/// NaN counted over the planes passed so far.
#[derive(Debug, Default)]
struct PlaneScan {
    nan: usize,
}

impl PlaneScan {
    /// Counts plane `z`'s NaN.
    fn plane<T: Sample>(&mut self, values: &[T]) {
        self.nan += values.iter().filter(|v| v.is_nan()).count();
    }
}

/// An infinity in plane `z` (of a grid of `dims`) is an error naming where it
/// is (the count is the plane's: the pass stops there).
fn check_finite<T: Sample>(values: &[T], dims: [usize; 3], z: usize) -> Result<()> {
    let infinite = |v: &T| !v.is_finite() && !v.is_nan();
    match values.iter().position(infinite) {
        Some(i) => Err(Error::NonFinite {
            count: values.iter().filter(|v| infinite(v)).count(),
            first: z * dims[0] * dims[1] + i,
            first_ijk: [i % dims[0], i / dims[0], z],
        }),
        None => Ok(()),
    }
}

/// One pass over the leaf rows: planes kept and read, leaves computed on
/// `scale` times the data and reduced; on the first pass (`sink` given)
/// each row's own planes are scanned and handed on.
fn pass<T: Sample>(
    source: &dyn PlaneSource,
    layout: &Layout,
    scale: f64,
    reduce: &mut StreamReduce,
    progress: &mut dyn FnMut(f64) -> bool,
    mut sink: Option<(&mut PlaneSink<'_, T>, &mut PlaneScan)>,
) -> Result<()> {
    let dims = layout.dims;
    let leaf = layout.leaf_level();
    let d = layout.level_dims(leaf);
    let most = (0..d[2]).map(|cz| row_planes(layout, row_span(layout, cz).0, row_span(layout, cz).1).len()).max();
    check_memory(
        most.unwrap_or(0) as u128 * (dims[0] * dims[1] * std::mem::size_of::<T>()) as u128,
        &format!("the streaming octree build's {} planes of {}x{}", most.unwrap_or(0), dims[0], dims[1]),
        "convert a volume with smaller planes, or use a smaller --leaf-size",
    )?;
    let mut stack = PlaneStack::<T>::new(dims);
    let plane = dims[0] * dims[1];
    for cz in 0..d[2] {
        let (lo, hi) = row_span(layout, cz);
        let need = row_planes(layout, lo, hi);
        stack.keep_only(&need);
        let missing: Vec<usize> = need.iter().copied().filter(|&z| !stack.holds(z)).collect();
        let mut at = 0;
        while at < missing.len() {
            let mut end = at + 1;
            while end < missing.len() && missing[end] == missing[end - 1] + 1 {
                end += 1;
            }
            let z = missing[at]..missing[end - 1] + 1;
            let values = into_vec::<T>(source.read_planes(z.clone())?)
                .filter(|v| v.len() == plane * z.len())
                .ok_or_else(|| Error::Internal(format!("a plane source returned other samples for planes {z:?}")))?;
            for (k, values) in z.zip(values.chunks_exact(plane)) {
                check_finite(values, dims, k)?;
                stack.insert(k, values);
            }
            at = end;
        }
        let stack_ref = &stack;
        let leaves = (0..d[0] * d[1])
            .into_par_iter()
            .map_init(Scratch::default, |scratch, i| {
                let (lo, hi) = layout.node_box(leaf, [i % d[0], i / d[0], cz]);
                leaf_stats(stack_ref, layout, lo, hi, scale, KernelPath::Fast, scratch)
            })
            .collect();
        reduce.push_leaves(cz, leaves);
        if let Some((sink, scan)) = sink.as_mut() {
            let own = lo..if cz + 1 == d[2] { dims[2] } else { hi };
            for z in own.clone() {
                scan.plane(stack.plane(z));
            }
            sink(own, &stack)?;
        }
        if !progress((cz + 1) as f64 / d[2] as f64) {
            return Err(Error::Cancelled);
        }
    }
    Ok(())
}
