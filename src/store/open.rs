//! Opening a store: its metadata, its levels, its octree, and reading boxes
//! of samples from it.
//!
//! A store written here (the root's `hybrid_octree` attribute) has every
//! level of [`super::pyramid`] and the octree's arrays. Any other OME-Zarr
//! image (NGFF 0.4 or 0.5, e.g. from `ome-zarr` or `zarr` in Python) is read
//! through its full-resolution dataset alone: time and channel axes are
//! taken at index 0 (with a warning), its own lower levels are not read
//! (their downsampling is unknown), and a level `p` box is the stride-`2^p`
//! subsampling of the full-resolution box.

use super::metadata::{Metadata, ATTRIBUTE};
use super::octree_arrays::read_octree;
use super::pyramid::{level_count, level_dims, level_position};
use super::subchunks::{self, SubchunkCache};
use super::zarr::{open_array, scalar_type_of, typed_samples, zarr_error, Storage};
use crate::base::error::{Error, Result};
use crate::base::limits::{check_memory, escape_controls};
use crate::data::grid::{GridShape, ScalarType};
use crate::data::planes::PlaneSource;
use crate::data::volume::{SampleBuf, Volume};
use crate::octree::layout::Layout;
use crate::octree::{BuildOptions, VolumeOctree};
use std::path::Path;
use std::sync::{Arc, OnceLock};
use zarrs::array::CodecOptions;
use zarrs::array::{Array, ArrayShardedExt, ArrayShardedReadableExt, ArrayShardedReadableExtCache, ArraySubset};
use zarrs::group::Group;

/// Bytes of decoded subchunks a store keeps for the next read.
pub const DEFAULT_CACHE_BYTES: usize = 256 << 20;

/// Bytes `zarrs` holds per chunk while it reads a region: the chunk's
/// indices, listed before any is decoded (bounded above by a small vector
/// of `u64` and its bookkeeping).
const CHUNK_LIST_BYTES: u128 = 64;

/// The most chunks a pass over a whole foreign store (its streaming octree
/// build, `convert`) visits: one key lookup each, a file-system call for a
/// chunk written or missing, so a store of 1-sample chunks over 1000^3 would
/// take hours before the first picture. 2^24 is 256^3 chunks: 16384^3
/// samples at chunks of 64^3.
pub const MAX_STREAMED_CHUNKS: u64 = 1 << 24;

/// An open OME-Zarr image.
pub struct Store {
    label: String,
    storage: Arc<Storage>,
    /// Samples per axis, spacing and origin of the full resolution.
    pub shape: GridShape,
    /// The samples' type.
    pub scalar_type: ScalarType,
    /// The image's name.
    pub name: String,
    /// The NGFF version the metadata declares.
    pub version: String,
    /// What the reader left out or assumed, for the user.
    pub warnings: Vec<String>,
    levels: Vec<Array<Storage>>,
    /// Per level, the shard indexes read so far (a few bytes per subchunk of a shard touched).
    shard_indexes: Vec<ArrayShardedReadableExtCache>,
    /// Decoded subchunks of a store written here (16^3-sample subchunks), for the next read.
    subchunks: Option<SubchunkCache>,
    leading: usize,
    own: Option<Metadata>,
    /// The octree of a store written elsewhere, built once (and its leaf size).
    built: OnceLock<(usize, VolumeOctree)>,
}

impl Store {
    /// Opens the OME-Zarr image in the folder `path`.
    ///
    /// # Errors
    ///
    /// [`Error::Format`] naming the store and what is wrong: not a folder,
    /// no NGFF metadata, an unsupported data type or axis layout, levels or
    /// an octree that do not match the metadata.
    pub fn open(path: &Path) -> Result<Store> {
        let label = escape_controls(&path.display().to_string());
        let err = |m: String| Error::Format { path: label.clone(), message: m };
        if !path.is_dir() {
            return Err(err(
                "not a folder: an OME-Zarr image is a folder (e.g. image.ome.zarr) holding zarr.json or .zattrs".into(),
            ));
        }
        let storage = Arc::new(Storage::new(path).map_err(|e| zarr_error(&label, "opening the store", &e))?);
        let group = Group::open(storage.clone(), "/").map_err(|e| zarr_error(&label, "opening the root group", &e))?;
        let attributes = group.attributes();
        let multiscale = super::ngff::parse(&label, attributes)?;
        let own: Option<Metadata> = match attributes.get(ATTRIBUTE) {
            Some(v) => Some(
                serde_json::from_value(v.clone())
                    .map_err(|e| err(format!("the '{ATTRIBUTE}' attribute is not one this version writes: {e}")))?,
            ),
            None => None,
        };
        let mut warnings = Vec::new();
        let first = open_array(&storage, &label, &format!("/{}", multiscale.paths[0]))?;
        let shape = first.shape().to_vec();
        let leading = multiscale.leading_axes.len();
        if shape.len() != leading + 3 {
            return Err(err(format!(
                "dataset '{}' has {} dimensions, the axes metadata names {}",
                escape_controls(&multiscale.paths[0]),
                shape.len(),
                leading + 3
            )));
        }
        if leading > 0 {
            warnings.push(format!(
                "the image has {} axes before z, y, x ({}): index 0 of each is read",
                leading,
                multiscale.leading_axes.join(", ")
            ));
        }
        let dims =
            [shape[leading + 2], shape[leading + 1], shape[leading]].map(|n| usize::try_from(n).unwrap_or(usize::MAX));
        if dims.iter().any(|&n| n < 2) {
            return Err(err(format!("the image has {dims:?} samples: a volume needs at least 2 per axis")));
        }
        let shape = GridShape { dims, spacing: multiscale.spacing, origin: multiscale.origin };
        shape.check(1)?;
        let scalar_type = scalar_type_of(&label, first.data_type())?;
        let levels = match &own {
            Some(meta) => {
                if meta.format != 1 || meta.dims != dims || meta.scalar_type != scalar_type.name() {
                    return Err(err(format!(
                        "the '{ATTRIBUTE}' attribute (format {}, dims {:?}, type {}) does not describe level 0 \
                         ({dims:?}, {}): write the store again with `hybrid-octree convert`",
                        meta.format,
                        meta.dims,
                        escape_controls(&meta.scalar_type),
                        scalar_type.name()
                    )));
                }
                let layout = Layout::new(dims, meta.leaf_size)?;
                let count = level_count(layout.root_size());
                if meta.levels != count || multiscale.paths.len() != count {
                    return Err(err(format!(
                        "the store lists {} levels ({} datasets), the octree needs {count}: write it again",
                        meta.levels,
                        multiscale.paths.len()
                    )));
                }
                let mut levels = vec![first];
                for p in 1..count {
                    let a = open_array(&storage, &label, &format!("/{}", multiscale.paths[p]))?;
                    let m = level_dims(dims, p);
                    if a.shape() != [m[2] as u64, m[1] as u64, m[0] as u64]
                        || scalar_type_of(&label, a.data_type())? != scalar_type
                    {
                        return Err(err(format!(
                            "level {p} has shape {:?}, the stride-{} level of {dims:?} samples is {:?}",
                            a.shape(),
                            1usize << p,
                            [m[2], m[1], m[0]]
                        )));
                    }
                    levels.push(a);
                }
                levels
            }
            None => vec![first],
        };
        let name = own.as_ref().map_or_else(|| "image".to_string(), |m| m.name.clone());
        let shard_indexes = levels.iter().map(ArrayShardedReadableExtCache::new).collect();
        let edge =
            |a: &Array<Storage>| a.effective_subchunk_shape().map(|s| s.iter().map(|n| n.get()).collect::<Vec<_>>());
        let subchunks = (own.is_some() && levels.iter().all(|a| edge(a) == Some(vec![subchunks::EDGE as u64; 3])))
            .then(|| SubchunkCache::new(DEFAULT_CACHE_BYTES, scalar_type));
        Ok(Store {
            label,
            storage,
            shard_indexes,
            subchunks,
            shape,
            scalar_type,
            name,
            version: multiscale.version,
            warnings,
            levels,
            leading,
            own,
            built: OnceLock::new(),
        })
    }

    /// The store as named in messages.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// True when this project wrote the store: its levels are the exact
    /// strides and it holds the Volume Octree.
    pub fn has_octree(&self) -> bool {
        self.own.is_some()
    }

    /// The metadata of a store written here.
    pub fn metadata(&self) -> Option<&Metadata> {
        self.own.as_ref()
    }

    /// The stored Volume Octree (validated), `None` for a store written elsewhere.
    ///
    /// # Errors
    ///
    /// [`Error::Format`] when the stored arrays are missing or damaged.
    pub fn octree(&self) -> Result<Option<VolumeOctree>> {
        match &self.own {
            Some(meta) => {
                let layout = Layout::new(self.shape.dims, meta.leaf_size)?;
                read_octree(&self.storage, &self.label, layout).map(Some)
            }
            None => Ok(None),
        }
    }

    /// The Volume Octree to select bricks with: the stored one of a store
    /// written here (its own leaf size), else the octree of leaf size
    /// `leaf_size` built by one streaming pass over the full resolution
    /// ([`VolumeOctree::build_streaming`], a few planes in memory at a
    /// time), once: it is kept on the store for the next call.
    ///
    /// # Errors
    ///
    /// As [`Self::octree`] and [`VolumeOctree::build_streaming`].
    pub fn volume_octree(&self, leaf_size: usize) -> Result<VolumeOctree> {
        if let Some(octree) = self.octree()? {
            return Ok(octree);
        }
        if let Some((leaf, octree)) = self.built.get() {
            if *leaf == leaf_size {
                return Ok(octree.clone());
            }
        }
        self.check_streamable()?;
        let built = VolumeOctree::build_streaming(self, &BuildOptions { leaf_size }, &mut |_| true)?.octree;
        let _ = self.built.set((leaf_size, built.clone()));
        Ok(built)
    }

    /// The samples of level `p` (stride `2^p`) in the closed index box
    /// `lo ..= hi` of that level, as a volume whose spacing is the level's
    /// and whose origin is the box's first sample (both nominal: the last
    /// plane of a level may sit nearer, see [`super::pyramid`]).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a box outside the level or more
    /// memory than the process may use; [`Error::Format`] for a read failure.
    pub fn read_level_box(&self, p: usize, lo: [usize; 3], hi: [usize; 3]) -> Result<Volume> {
        let dims = self.shape.dims;
        let m = level_dims(dims, p);
        if p >= 63 || (0..3).any(|a| lo[a] > hi[a] || hi[a] >= m[a]) {
            return Err(Error::InvalidArgument(format!(
                "box {lo:?}..={hi:?} is not inside level {p} ({m:?} samples) of '{}'",
                self.label
            )));
        }
        let n = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
        let count = n[0] * n[1] * n[2];
        check_memory(
            (count * self.scalar_type.size()) as u128,
            &format!("a {n:?} box of '{}'", self.label),
            "read a smaller region (a lower --budget-mb) or a coarser level",
        )?;
        let samples = match self.levels.get(p) {
            Some(_) => self.read_box(p, lo, hi)?,
            None => self.read_subsampled(p, lo, hi)?,
        };
        let spacing = self.shape.spacing.map(|s| s * (1u64 << p) as f64);
        let origin =
            [0, 1, 2].map(|a| self.shape.origin[a] + level_position(dims[a], p, lo[a]) as f64 * self.shape.spacing[a]);
        let mut volume = Volume::new(samples, n, self.name.clone());
        volume.shape.spacing = spacing;
        volume.shape.origin = origin;
        Ok(volume)
    }

    /// The whole full-resolution volume, if it fits in memory.
    ///
    /// # Errors
    ///
    /// As [`Self::read_level_box`].
    pub fn read_volume(&self) -> Result<Volume> {
        let d = self.shape.dims;
        let mut v = self.read_level_box(0, [0; 3], d.map(|n| n - 1))?;
        v.shape = self.shape;
        Ok(v)
    }

    /// The box `lo ..= hi` (x, y, z order) of the array of level `p`, the
    /// leading axes at index 0, each shard's index read once.
    ///
    /// Reading lists the chunks the box touches, about [`CHUNK_LIST_BYTES`]
    /// each: a store with tiny chunks is refused before that list is made.
    fn read_box(&self, p: usize, lo: [usize; 3], hi: [usize; 3]) -> Result<SampleBuf> {
        let (array, cache) = (&self.levels[p], &self.shard_indexes[p]);
        if let Some(subchunks) = &self.subchunks {
            let n = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
            let mut out = SampleBuf::zeroed(self.scalar_type, n[0] * n[1] * n[2]);
            let e = subchunks::EDGE;
            for z in lo[2] / e..=hi[2] / e {
                for y in lo[1] / e..=hi[1] / e {
                    for x in lo[0] / e..=hi[0] / e {
                        let index = [z as u64, y as u64, x as u64];
                        let sub = subchunks.get(&self.label, (p, array, cache), self.scalar_type, index)?;
                        if !subchunks::copy_into(&sub, index, lo, hi, &mut out) {
                            return Err(zarr_error(&self.label, "reading samples", &"a subchunk of another type"));
                        }
                    }
                }
            }
            return Ok(out);
        }
        let mut ranges: Vec<std::ops::Range<u64>> = vec![0..1; self.leading];
        ranges.extend((0..3).rev().map(|a| lo[a] as u64..hi[a] as u64 + 1));
        let subset = ArraySubset::new_with_ranges(&ranges);
        let chunks = array
            .chunks_in_array_subset(&subset)
            .map_err(|e| zarr_error(&self.label, "listing chunks", &e))?
            .map_or(0, |c| c.num_elements());
        check_memory(
            u128::from(chunks) * CHUNK_LIST_BYTES,
            &format!("listing the {chunks} chunks of array '{}' of '{}'", array.path().as_str(), self.label),
            "its chunks are too small: write the image again with larger chunks (e.g. `hybrid-octree convert`)",
        )?;
        let options = CodecOptions::default();
        let err = |e: zarrs::array::ArrayError| zarr_error(&self.label, "reading samples", &e);
        Ok(typed_samples!(
            self.scalar_type,
            array.retrieve_array_subset_sharded_opt(cache, &subset, &options).map_err(err)?
        ))
    }

    /// Level `p`'s box of a store without that level: the full-resolution
    /// box read, then its samples at the level's positions.
    fn read_subsampled(&self, p: usize, lo: [usize; 3], hi: [usize; 3]) -> Result<SampleBuf> {
        let dims = self.shape.dims;
        let first = [0, 1, 2].map(|a| level_position(dims[a], p, lo[a]));
        let last = [0, 1, 2].map(|a| level_position(dims[a], p, hi[a]));
        let n = [0, 1, 2].map(|a| last[a] - first[a] + 1);
        check_memory(
            (n[0] * n[1] * n[2] * self.scalar_type.size()) as u128,
            &format!("a full-resolution {n:?} box of '{}' (it has no stride-{} level)", self.label, 1u64 << p),
            "write the store with `hybrid-octree convert`, which keeps every stride as a level",
        )?;
        let full = self.read_box(0, first, last)?;
        let index = |a: usize| (lo[a]..=hi[a]).map(|i| level_position(dims[a], p, i) - first[a]).collect::<Vec<_>>();
        Ok(gather(&full, n, [index(0), index(1), index(2)]))
    }

    /// The texels of a brick of stride `stride` (a power of two) whose box
    /// starts at level-0 index `lo` (a multiple of the stride), `n` texels
    /// per axis and `border` more on each side: level `log2 stride` from
    /// index `lo / stride - border`, clamped to the level ([`Self::read_clamped`]).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a stride that is not a power of two,
    /// and as [`Self::read_clamped`].
    pub fn read_texels(&self, stride: usize, lo: [usize; 3], n: [usize; 3], border: usize) -> Result<Volume> {
        let p = super::pyramid::level_of_stride(stride)
            .ok_or_else(|| Error::InvalidArgument(format!("brick stride {stride} is not a power of two")))?;
        let first = [0, 1, 2].map(|a| (lo[a] / stride) as i64 - border as i64);
        self.read_clamped(p, first, n.map(|n| n + 2 * border))
    }

    /// The `n` samples per axis of level `p` starting at index `first`
    /// (which may lie outside the level), each index clamped to the level:
    /// a brick texture with its gradient border repeats the volume's last
    /// sample beyond its faces.
    ///
    /// # Errors
    ///
    /// As [`Self::read_level_box`].
    pub fn read_clamped(&self, p: usize, first: [i64; 3], n: [usize; 3]) -> Result<Volume> {
        let m = level_dims(self.shape.dims, p);
        let clamp = |a: usize, i: i64| i.clamp(0, m[a] as i64 - 1) as usize;
        let lo = [0, 1, 2].map(|a| clamp(a, first[a]));
        let hi = [0, 1, 2].map(|a| clamp(a, first[a] + n[a] as i64 - 1));
        let inner = self.read_level_box(p, lo, hi)?;
        if (0..3).all(|a| first[a] == lo[a] as i64 && hi[a] - lo[a] + 1 == n[a]) {
            return Ok(inner);
        }
        let index = |a: usize| (0..n[a]).map(|i| clamp(a, first[a] + i as i64) - lo[a]).collect::<Vec<_>>();
        let got = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
        let samples = gather(&inner.samples, got, [index(0), index(1), index(2)]);
        let mut v = Volume::new(samples, n, inner.name);
        v.shape.spacing = inner.shape.spacing;
        v.shape.origin = inner.shape.origin;
        Ok(v)
    }
}

/// The samples of `buf` (dims `n`, x fastest) at the index lists per axis.
fn gather(buf: &SampleBuf, n: [usize; 3], index: [Vec<usize>; 3]) -> SampleBuf {
    fn take<T: Copy>(v: &[T], n: [usize; 3], index: &[Vec<usize>; 3]) -> Vec<T> {
        let mut out = Vec::with_capacity(index[0].len() * index[1].len() * index[2].len());
        for &k in &index[2] {
            for &j in &index[1] {
                let row = n[0] * (j + n[1] * k);
                out.extend(index[0].iter().map(|&i| v[row + i]));
            }
        }
        out
    }
    match buf {
        SampleBuf::U8(v) => SampleBuf::U8(take(v, n, &index)),
        SampleBuf::I8(v) => SampleBuf::I8(take(v, n, &index)),
        SampleBuf::U16(v) => SampleBuf::U16(take(v, n, &index)),
        SampleBuf::I16(v) => SampleBuf::I16(take(v, n, &index)),
        SampleBuf::U32(v) => SampleBuf::U32(take(v, n, &index)),
        SampleBuf::I32(v) => SampleBuf::I32(take(v, n, &index)),
        SampleBuf::F32(v) => SampleBuf::F32(take(v, n, &index)),
        SampleBuf::F64(v) => SampleBuf::F64(take(v, n, &index)),
    }
}

impl PlaneSource for Store {
    fn shape(&self) -> GridShape {
        self.shape
    }
    fn scalar_type(&self) -> ScalarType {
        self.scalar_type
    }
    /// The full-resolution planes `z`, read as one box; refused for a store
    /// of more than [`MAX_STREAMED_CHUNKS`] chunks (a pass over its planes
    /// visits every one).
    fn read_planes(&self, z: std::ops::Range<usize>) -> Result<SampleBuf> {
        let [nx, ny, nz] = self.shape.dims;
        if z.is_empty() || z.end > nz {
            return Err(Error::InvalidArgument(format!("planes {z:?} are not inside the {nz} of '{}'", self.label)));
        }
        self.check_streamable()?;
        Ok(self.read_level_box(0, [0, 0, z.start], [nx - 1, ny - 1, z.end - 1])?.samples)
    }
}

impl Store {
    /// The chunks of the full resolution's spatial axes (the first time
    /// point and channel): what a pass over every plane visits.
    pub fn spatial_chunks(&self) -> u64 {
        let grid = self.levels[0].chunk_grid_shape();
        grid.iter().skip(grid.len().saturating_sub(3)).fold(1u64, |n, &c| n.saturating_mul(c))
    }

    /// Ok when a pass over every plane visits at most [`MAX_STREAMED_CHUNKS`]
    /// chunks (a store written here reads its own subchunks: always Ok).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] naming the count, the limit and the fix.
    pub fn check_streamable(&self) -> Result<()> {
        let chunks = self.spatial_chunks();
        if self.subchunks.is_none() && chunks > MAX_STREAMED_CHUNKS {
            return Err(Error::InvalidArgument(format!(
                "'{}' has {chunks} chunks, more than the {MAX_STREAMED_CHUNKS} a pass over its samples may visit: its \
                 chunks are too small; write the image again with chunks of 64^3 samples or more (zarr-python: \
                 chunks=(64, 64, 64)), or, if it fits in memory, read it whole (the CLI's --in-memory)",
                self.label
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
impl Store {
    /// The storage, for tests that damage a store.
    pub(crate) fn storage_for_tests(&self) -> Arc<Storage> {
        self.storage.clone()
    }
}
