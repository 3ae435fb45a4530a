//! Writing a Hybrid Octree store: the resolution levels of [`super::pyramid`]
//! as sharded Zarr v3 arrays, the Volume Octree's arrays, and the NGFF 0.5
//! metadata, in slabs of whole shards so that memory beside the input stays
//! under a limit.
//!
//! Each level `p` is an array `"p"` of shape `(m_z, m_y, m_x)` (C order: x
//! fastest, as the grid), in shards of `(d, 256, 256)` samples (`d` the
//! slab depth, at most 64) made of 16^3 subchunks: one subchunk is one
//! leaf brick's cells at stride 1 (the default leaf size), and a brick's
//! shared far face is the first sample plane of the neighbouring subchunk,
//! which the sharded read decodes with it. Subchunks are zstd-compressed.

use super::metadata::Metadata;
use super::ngff::ome_attribute;
use super::octree_arrays::write_octree;
use super::pyramid::{level_count, level_dims, level_position};
use super::zarr::{bytes_of, data_type_of, zarr_error, zstd, Storage};
use crate::base::error::{Error, Result};
use crate::base::limits::check_memory;
use crate::data::grid::{Grid, GridShape, GridVisitor, Sample, ScalarType, TypedGrid};
use crate::octree::VolumeOctree;
use rayon::prelude::*;
use std::path::Path;
use std::sync::Arc;
use zarrs::array::codec::{ShardingCodecOptions, SubchunkWriteOrder};
use zarrs::array::{Array, ArrayBuilder, ArrayBytes, ArraySubset, CodecSpecificOptions};
use zarrs::group::GroupBuilder;

/// Samples per axis of a subchunk.
pub const SUBCHUNK: u64 = super::subchunks::EDGE as u64;
/// Samples along x and y of a shard.
const SHARD_XY: u64 = 256;
/// The deepest slab (shard depth along z).
const MAX_SLAB: u64 = 64;

/// Options of [`write_store`].
#[derive(Debug, Clone, PartialEq)]
pub struct WriteOptions {
    /// Bytes the writer may hold beside the input: one slab of a level and
    /// its encoded shards. At least one 16-plane slab of level 0 must fit.
    pub memory_limit: usize,
    /// The image's name in the NGFF metadata.
    pub name: String,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions { memory_limit: 1 << 30, name: "image".into() }
    }
}

/// What [`write_store`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct WriteSummary {
    /// Resolution levels written.
    pub levels: usize,
    /// Samples written over all levels.
    pub samples: u64,
    /// The slab depth (planes per shard) used.
    pub slab_planes: u64,
}

/// The slab depth for `dims` of `bytes_per_sample` under `limit`: the
/// deepest multiple of 16 planes, at most 64, whose slab of level 0 and its
/// encoded copy (twice the slab) fit, checked against the memory the
/// process may use.
pub fn slab_planes(dims: [usize; 3], bytes_per_sample: usize, limit: usize) -> Result<u64> {
    let plane = (dims[0] * dims[1] * bytes_per_sample) as u64 * 2;
    let planes = (limit as u64 / plane.max(1)) / SUBCHUNK * SUBCHUNK;
    if planes == 0 {
        return Err(Error::InvalidArgument(format!(
            "a memory limit of {limit} bytes cannot hold one 16-plane slab of the {}x{} planes ({} bytes): \
             raise --memory-mb",
            dims[0],
            dims[1],
            plane * SUBCHUNK
        )));
    }
    let planes = planes.min(MAX_SLAB);
    check_memory(u128::from(planes) * plane as u128, "the store writer's slab", "lower --memory-mb")?;
    Ok(planes)
}

/// Writes `grid` (one component) and its `octree` as a new store at `path`,
/// calling `progress(done, total)` with the samples written so far.
///
/// # Errors
///
/// [`Error::InvalidArgument`] if `path` exists (nothing is overwritten), if
/// the octree is not `grid`'s, or if the memory limit cannot hold a slab;
/// [`Error::Format`] for a failure to write.
pub fn write_store(
    path: &Path,
    grid: &Grid<'_>,
    octree: &VolumeOctree,
    options: &WriteOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<WriteSummary> {
    let label = crate::base::limits::escape_controls(&path.display().to_string());
    if path.exists() {
        return Err(Error::InvalidArgument(format!(
            "'{label}' already exists: choose a new --output path, or remove it first (nothing is overwritten)"
        )));
    }
    let dims = grid.dims();
    if octree.layout().dims != dims {
        return Err(Error::InvalidArgument(format!(
            "the octree was built for {:?} samples, the grid has {dims:?}",
            octree.layout().dims
        )));
    }
    let scalar_type = grid.samples().scalar_type();
    let planes = slab_planes(dims, scalar_type.size(), options.memory_limit)?;
    let levels = level_count(octree.layout().root_size());
    let store = Arc::new(Storage::new(path).map_err(|e| zarr_error(&label, "creating the store", &e))?);
    let metadata = Metadata {
        format: 1,
        dims,
        leaf_size: octree.layout().leaf_size(),
        scalar_type: scalar_type.name().to_string(),
        nan_count: grid.nan_count(),
        value_range: octree.value_range(),
        levels,
        name: options.name.clone(),
    };
    let total = level_samples(dims, levels);
    let mut done = 0u64;
    progress(done, total);
    for p in 0..levels {
        let m = level_dims(dims, p);
        let (array, depth) = create_level(&store, &label, dims, p, planes, scalar_type)?;
        let mut z0 = 0usize;
        while z0 < m[2] {
            let z1 = (z0 + depth).min(m[2]);
            let subset = ArraySubset::new_with_ranges(&[z0 as u64..z1 as u64, 0..m[1] as u64, 0..m[0] as u64]);
            grid.visit(Slab { p, m, z: z0..z1, array: &array, subset: &subset })
                .map_err(|e| zarr_error(&label, &format!("writing level {p}"), &e))?;
            done += ((z1 - z0) * m[1] * m[0]) as u64;
            progress(done, total);
            z0 = z1;
        }
    }
    write_octree(&store, &label, octree)?;
    store_group(&store, &label, grid.shape(), &metadata)?;
    Ok(WriteSummary { levels, samples: total, slab_planes: planes })
}

/// Samples of all `levels` levels of a volume of `dims`.
pub(super) fn level_samples(dims: [usize; 3], levels: usize) -> u64 {
    (0..levels).map(|p| level_dims(dims, p).iter().map(|&m| m as u64).product::<u64>()).sum()
}

/// Creates level `p`'s array (its metadata stored) for a volume of `dims`
/// with slabs of `planes`; returns it and its shard depth along z.
pub(super) fn create_level(
    store: &Arc<Storage>,
    label: &str,
    dims: [usize; 3],
    p: usize,
    planes: u64,
    scalar_type: ScalarType,
) -> Result<(Array<Storage>, usize)> {
    let m = level_dims(dims, p);
    let shard = [planes, SHARD_XY, SHARD_XY]
        .iter()
        .zip([m[2], m[1], m[0]])
        .map(|(&s, n)| s.min((n as u64).div_ceil(SUBCHUNK) * SUBCHUNK))
        .collect::<Vec<u64>>();
    let array = ArrayBuilder::new(
        vec![m[2] as u64, m[1] as u64, m[0] as u64],
        shard.clone(),
        data_type_of(scalar_type),
        zarrs::array::FillValue::new(vec![0u8; scalar_type.size()]),
    )
    .subchunk_shape(vec![SUBCHUNK; 3])
    // Subchunks laid out in C order, not in the order parallel encoding
    // finishes them: the same samples give the same shard bytes.
    .codec_specific_options(
        CodecSpecificOptions::default()
            .with_option(ShardingCodecOptions::default().with_subchunk_write_order(SubchunkWriteOrder::C)),
    )
    .bytes_to_bytes_codecs(vec![zstd()])
    .dimension_names(["z", "y", "x"].into())
    .build(store.clone(), &format!("/{p}"))
    .map_err(|e| zarr_error(label, &format!("creating level {p}"), &e))?;
    array.store_metadata().map_err(|e| zarr_error(label, &format!("writing level {p}'s metadata"), &e))?;
    Ok((array, shard[0] as usize))
}

/// Stores the root group's metadata: the NGFF attribute and `metadata`.
pub(super) fn store_group(store: &Arc<Storage>, label: &str, shape: &GridShape, metadata: &Metadata) -> Result<()> {
    let mut root =
        GroupBuilder::new().build(store.clone(), "/").map_err(|e| zarr_error(label, "creating the group", &e))?;
    let attributes = root.attributes_mut();
    attributes.insert("ome".into(), ome_attribute(shape, metadata.levels, &metadata.name));
    attributes.insert(
        super::metadata::ATTRIBUTE.into(),
        serde_json::to_value(metadata).map_err(|e| zarr_error(label, "writing the metadata", &e))?,
    );
    root.store_metadata().map_err(|e| zarr_error(label, "writing the group's metadata", &e))
}

/// Planes `z` of level `p` (dims `m`) gathered from the grid and stored
/// into `array` at `subset`.
struct Slab<'a> {
    p: usize,
    m: [usize; 3],
    z: std::ops::Range<usize>,
    array: &'a Array<Storage>,
    subset: &'a ArraySubset,
}

impl GridVisitor for Slab<'_> {
    type Output = std::result::Result<(), zarrs::array::ArrayError>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Self::Output {
        let Slab { p, m, z, array, subset } = self;
        let plane = m[0] * m[1];
        // Every value is overwritten below before it is stored.
        let mut values: Vec<T> = vec![g.get(0, 0, 0); plane * z.len()];
        values.par_chunks_mut(plane).zip(z).for_each(|(out, k)| {
            let gz = level_position(g.dims[2], p, k);
            for (j, row) in out.chunks_mut(m[0]).enumerate() {
                let gy = level_position(g.dims[1], p, j);
                for (i, v) in row.iter_mut().enumerate() {
                    *v = g.get(level_position(g.dims[0], p, i), gy, gz);
                }
            }
        });
        array.store_array_subset(subset, ArrayBytes::new_flen(bytes_of(&values)))
    }
}
