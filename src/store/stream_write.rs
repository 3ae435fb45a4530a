//! Writing a store in one pass over z from a [`PlaneSource`]: every level
//! and the Volume Octree, holding a few planes and one slab per level,
//! never the volume. The store is byte for byte what [`super::write_store`]
//! writes for the same samples, options and leaf size.
//!
//! The streaming octree build ([`crate::octree::stream_build`]) reads the
//! planes and hands each one on once, in z order. Level `p`'s plane `k` is
//! the level-0 plane `x_p(k)` ([`super::pyramid`]) subsampled in x and y; it
//! goes into the level's slab, and a slab whose shard depth is full (or
//! which ends the level) is encoded and stored. The octree's arrays and
//! the metadata are written at the end. Memory: the writer's slabs (under
//! [`WriteOptions::memory_limit`], as [`super::write_store`]), the build's
//! planes and its node arrays.

use super::metadata::Metadata;
use super::octree_arrays::write_octree;
use super::pyramid::{level_count, level_dims, level_position};
use super::write::{create_level, level_samples, slab_planes, store_group, WriteOptions, WriteSummary};
use super::zarr::{bytes_of, zarr_error, Storage};
use crate::base::error::{Error, Result};
use crate::base::limits::escape_controls;
use crate::data::grid::Sample;
use crate::data::planes::{for_type, PlaneSource, TypeVisitor};
use crate::octree::layout::Layout;
use crate::octree::plane_stack::PlaneStack;
use crate::octree::stream_build::{build_streaming_into, Streamed};
use crate::octree::BuildOptions;
use std::path::Path;
use std::sync::Arc;
use zarrs::array::{Array, ArrayBytes, ArraySubset};

/// What [`write_store_streaming`] wrote and built.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamWritten {
    /// Levels, samples and slab depth written.
    pub summary: WriteSummary,
    /// The Volume Octree stored with them, and the NaN count.
    pub streamed: Streamed,
}

/// Writes the volume `source` hands out as a new store at `path`, its
/// Volume Octree built with `build` in the same pass, calling
/// `progress(done, total)` with the samples written so far.
///
/// # Errors
///
/// As [`super::write_store`], and as
/// [`crate::octree::VolumeOctree::build_streaming`]. A store left half
/// written by an error is removed.
pub fn write_store_streaming(
    path: &Path,
    source: &dyn PlaneSource,
    build: &BuildOptions,
    options: &WriteOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<StreamWritten> {
    let label = escape_controls(&path.display().to_string());
    if path.exists() {
        return Err(Error::InvalidArgument(format!(
            "'{label}' already exists: choose a new --output path, or remove it first (nothing is overwritten)"
        )));
    }
    let run = Run { path, label: &label, source, build, options, progress };
    let written = for_type(source.scalar_type(), run);
    if written.is_err() && path.exists() {
        let _ = std::fs::remove_dir_all(path);
    }
    written
}

struct Run<'a> {
    path: &'a Path,
    label: &'a str,
    source: &'a dyn PlaneSource,
    build: &'a BuildOptions,
    options: &'a WriteOptions,
    progress: &'a mut dyn FnMut(u64, u64),
}

impl TypeVisitor for Run<'_> {
    type Output = Result<StreamWritten>;
    fn visit<T: Sample>(self) -> Result<StreamWritten> {
        let Run { path, label, source, build, options, progress } = self;
        let shape = source.shape();
        shape.check(1)?;
        let dims = shape.dims;
        let scalar_type = source.scalar_type();
        let layout = Layout::new(dims, build.leaf_size)?;
        let planes = slab_planes(dims, scalar_type.size(), options.memory_limit)?;
        let levels = level_count(layout.root_size());
        let store = Arc::new(Storage::new(path).map_err(|e| zarr_error(label, "creating the store", &e))?);
        let mut slabs = Vec::with_capacity(levels);
        for p in 0..levels {
            let (array, depth) = create_level(&store, label, dims, p, planes, scalar_type)?;
            slabs.push(LevelSlab::<T> {
                p,
                m: level_dims(dims, p),
                array,
                depth,
                start: 0,
                next: 0,
                values: Vec::new(),
            });
        }
        let total = level_samples(dims, levels);
        let mut done = 0u64;
        progress(done, total);
        let streamed = build_streaming_into::<T>(source, build, &mut |_| true, &mut |z, stack| {
            for z in z {
                for slab in slabs.iter_mut() {
                    done += slab.take(z, dims, stack, label)?;
                }
                progress(done, total);
            }
            Ok(())
        })?;
        let octree = &streamed.octree;
        write_octree(&store, label, octree)?;
        let metadata = Metadata {
            format: 1,
            dims,
            leaf_size: layout.leaf_size(),
            scalar_type: scalar_type.name().to_string(),
            nan_count: streamed.nan_count,
            value_range: octree.value_range(),
            levels,
            name: options.name.clone(),
        };
        store_group(&store, label, &shape, &metadata)?;
        Ok(StreamWritten { summary: WriteSummary { levels, samples: total, slab_planes: planes }, streamed })
    }
}

/// The slab of one level being filled.
struct LevelSlab<T: Sample> {
    p: usize,
    m: [usize; 3],
    array: Array<Storage>,
    /// Shard depth along z.
    depth: usize,
    /// First level plane of the slab.
    start: usize,
    /// The next level plane to fill.
    next: usize,
    values: Vec<T>,
}

impl<T: Sample> LevelSlab<T> {
    /// Takes level-0 plane `z` if it is this level's next plane (subsampled
    /// in x and y); stores the slab when it is full. Returns the samples stored.
    fn take(&mut self, z: usize, dims: [usize; 3], stack: &PlaneStack<T>, label: &str) -> Result<u64> {
        let (p, m) = (self.p, self.m);
        if self.next >= m[2] || level_position(dims[2], p, self.next) != z {
            return Ok(0);
        }
        let plane = stack.plane(z);
        if self.values.is_empty() {
            self.values.reserve_exact(self.depth.min(m[2] - self.start) * m[0] * m[1]);
        }
        if p == 0 {
            self.values.extend_from_slice(plane);
        } else {
            for j in 0..m[1] {
                let row = &plane[level_position(dims[1], p, j) * dims[0]..];
                self.values.extend((0..m[0]).map(|i| row[level_position(dims[0], p, i)]));
            }
        }
        self.next += 1;
        if self.next - self.start < self.depth && self.next < m[2] {
            return Ok(0);
        }
        let subset =
            ArraySubset::new_with_ranges(&[self.start as u64..self.next as u64, 0..m[1] as u64, 0..m[0] as u64]);
        self.array
            .store_array_subset(&subset, ArrayBytes::new_flen(bytes_of(&self.values)))
            .map_err(|e| zarr_error(label, &format!("writing level {p}"), &e))?;
        let stored = self.values.len() as u64;
        self.values = Vec::new();
        self.start = self.next;
        Ok(stored)
    }
}
