//! The volume on disk through the bridge: an open OME-Zarr image
//! ([`StoreHandle`]), its summary, its levels read into the caller's
//! memory, the Hybrid Octree made from it, and a selection's brick texels
//! read from it (the texels the in-memory calls of `render.rs` give, bit for
//! bit: a brick of stride `2^p` reads exactly level `p`'s samples, see
//! [`crate::store::pyramid`]).

use super::grid::bridge_scalar_type;
use super::guard::{check_len, guarded, Bridged};
use super::octree::{next_id, HybridOctreeHandle};
use super::render::{check_f32_resolution, finite_texels, SelectionHandle};
use super::StoreSummary;
use crate::base::error::{Error, Result};
use crate::hybrid::HybridOctree;
use crate::octree::{BuildOptions, NodeRef, VolumeOctree};
use crate::plan::select::Brick;
use crate::render::texture::{
    brick_texels_f32_bordered_into, brick_texels_f32_into, encoded::brick_texels_encoded_into,
};
use crate::store::brick_loader::{BrickLoader, BrickRead};
use crate::store::pyramid::level_dims;
use crate::store::Store;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};

/// An open OME-Zarr image (see [`Store`]), with its background brick
/// reader once a frame has asked for one (`super::loading`).
pub struct StoreHandle {
    pub(crate) store: Arc<Store>,
    loader: OnceLock<std::result::Result<BrickLoader, String>>,
    /// Bytes of samples the frames' own reads took from the store.
    bytes_read: AtomicU64,
}

/// Opens the OME-Zarr image in the folder `path`.
pub(crate) fn open_store(path: &str) -> Bridged<Box<StoreHandle>> {
    guarded(|| {
        Ok(Box::new(StoreHandle {
            store: Arc::new(Store::open(Path::new(path))?),
            loader: OnceLock::new(),
            bytes_read: AtomicU64::new(0),
        }))
    })
}

/// The lattice a loaded brick is read as: always with its gradient border,
/// so that one read serves the frames with and without it.
pub(crate) fn loaded_read(b: &Brick) -> BrickRead {
    BrickRead { stride: b.stride, lo: b.lo, texels: b.texels, border: 1 }
}

/// The levels a store offers: its own for a store written here; for one
/// written elsewhere, every stride down to two samples per axis (read as
/// subsamplings of its full resolution, see [`Store::read_level_box`]).
fn level_count(store: &Store) -> usize {
    match store.metadata() {
        Some(meta) => meta.levels,
        None => (0..63).find(|&p| level_dims(store.shape.dims, p).iter().all(|&m| m <= 2)).unwrap_or(62) + 1,
    }
}

/// The Volume Octree of `store` with its NaN count: the stored one, or, for
/// an image written elsewhere, the one built by a streaming pass over its
/// full resolution (never whole in memory) with leaves of `leaf_size`
/// cells. The one place the bridge makes an octree from a store.
fn octree_of(store: &Store, leaf_size: usize) -> Result<(VolumeOctree, usize)> {
    if let (Some(octree), Some(meta)) = (store.octree()?, store.metadata()) {
        return Ok((octree, meta.nan_count));
    }
    let streamed = VolumeOctree::build_streaming(store, &BuildOptions { leaf_size }, &mut |_| true)?;
    Ok((streamed.octree, streamed.nan_count))
}

impl StoreHandle {
    /// The background reader, started at the first call.
    ///
    /// # Errors
    ///
    /// The thread could not be started.
    pub(crate) fn loader(&self) -> Result<&BrickLoader> {
        let started = self.loader.get_or_init(|| BrickLoader::start(Arc::clone(&self.store)));
        started.as_ref().map_err(|e| Error::InvalidArgument(e.clone()))
    }

    /// Bytes of samples read from the store: by the frames and by the background reader.
    pub(crate) fn bytes_read(&self) -> u64 {
        let loaded = self.loader.get().and_then(|l| l.as_ref().ok()).map_or(0, |l| l.status().bytes_read);
        self.bytes_read.load(Ordering::Relaxed) + loaded
    }

    /// The read volume of `read` if the background reader holds it (it gives it up).
    fn take_loaded(&self, read: &BrickRead) -> Option<crate::data::volume::Volume> {
        self.loader.get().and_then(|l| l.as_ref().ok()).and_then(|l| l.take(read))
    }

    pub(crate) fn summary(&self) -> Bridged<StoreSummary> {
        guarded(|| {
            let s = &self.store;
            let levels = level_count(s);
            Ok(StoreSummary {
                dims: s.shape.dims,
                spacing: s.shape.spacing,
                origin: s.shape.origin,
                scalar_type: bridge_scalar_type(s.scalar_type),
                levels,
                level_dims: (0..levels).flat_map(|p| level_dims(s.shape.dims, p)).collect(),
                has_octree: s.has_octree(),
                name: s.name.clone(),
                version: s.version.clone(),
                warnings: s.warnings.join("; "),
            })
        })
    }

    /// The closed box `lo ..= hi` of level `level` into `bytes` (x fastest,
    /// native byte order, the store's scalar type).
    pub(crate) fn read_level(&self, level: usize, lo: &[usize], hi: &[usize], bytes: &mut [u8]) -> Bridged<()> {
        guarded(|| {
            let s = &self.store;
            let corner = |v: &[usize]| -> Result<[usize; 3]> {
                v.try_into()
                    .map_err(|_| Error::InvalidArgument(format!("a box corner has {} indices, 3 expected", v.len())))
            };
            let (lo, hi) = (corner(lo)?, corner(hi)?);
            let m = level_dims(s.shape.dims, level.min(62));
            if level >= level_count(s) || (0..3).any(|a| lo[a] > hi[a] || hi[a] >= m[a]) {
                return Err(Error::InvalidArgument(format!(
                    "box {lo:?}..={hi:?} is not inside level {level} ({m:?} samples) of '{}', which has {} levels",
                    s.label(),
                    level_count(s)
                )));
            }
            let count = (0..3).map(|a| hi[a] - lo[a] + 1).product::<usize>() * s.scalar_type.size();
            check_len("the level's bytes", bytes, count)?;
            let volume = s.read_level_box(level, lo, hi)?;
            bytes.copy_from_slice(volume.samples.as_bytes());
            Ok(())
        })
    }
}

/// The Hybrid Octree of the store (see [`octree_of`]), its grid the store's
/// full resolution.
pub(crate) fn build_octree_from_store(store: &StoreHandle, leaf_size: u32) -> Bridged<Box<HybridOctreeHandle>> {
    guarded(|| {
        let s: &Store = &store.store;
        let (volume, nan_samples) = octree_of(s, leaf_size as usize)?;
        let count = s.shape.dims.iter().product::<usize>();
        Ok(Box::new(HybridOctreeHandle {
            hybrid: HybridOctree::volume_only(volume),
            shape: s.shape,
            input_bytes: count * s.scalar_type.size(),
            nan_samples,
            scalar_type: s.scalar_type,
            dependent: None,
            rgba: None,
            id: next_id(),
            surface_id: 0,
            selector: Default::default(),
            medium: Default::default(),
        }))
    })
}

/// The brick's own samples (the read volume's `grid` less its `border`)
/// against the range the octree holds for its node's closed box: at
/// stride 1 they are that box's samples, so their range is the node's
/// exactly; at a coarser stride a subset, inside it. A chunk missing from
/// the store (Zarr reads it as the fill value) or damaged shows as another
/// range. NaN is no data and not counted; the result says whether the
/// brick holds any.
fn check_against_octree(
    grid: &crate::data::grid::Grid<'_>,
    node: &NodeRef<'_>,
    b: &Brick,
    border: usize,
    store: &Store,
) -> Result<bool> {
    let (mut lo, mut hi, mut holes) = (f64::INFINITY, f64::NEG_INFINITY, false);
    for k in border..border + b.texels[2] {
        for j in border..border + b.texels[1] {
            for i in border..border + b.texels[0] {
                let v = grid.value(i, j, k);
                if v.is_nan() {
                    holes = true;
                } else {
                    (lo, hi) = (lo.min(v), hi.max(v));
                }
            }
        }
    }
    let exact = b.stride == 1;
    let empty = lo > hi;
    let fits = if exact {
        (lo == node.min && hi == node.max) || (empty && node.min > node.max)
    } else {
        empty || (lo >= node.min && hi <= node.max)
    };
    if fits {
        return Ok(holes);
    }
    Err(Error::Format {
        path: store.label().to_string(),
        message: format!(
            "level {} holds the range [{lo}, {hi}] in the box of node {}, whose stored range is [{}, {}]: a chunk of \
             that level is missing (Zarr reads it as the fill value) or damaged; write the store again with \
             `hybrid-octree convert`",
            b.stride.trailing_zeros(),
            b.node.0,
            node.min,
            node.max
        ),
    })
}

impl SelectionHandle {
    /// That the selection was made from `octree`, built from `store`, with one component.
    pub(crate) fn check_store(&self, octree: &HybridOctreeHandle, store: &StoreHandle) -> Result<()> {
        let s = &store.store;
        if s.shape != self.shape {
            return Err(Error::InvalidArgument(format!(
                "the store '{}' is not the volume this selection was made from (dims, spacing or origin differ): \
                 build the octree from it again",
                s.label()
            )));
        }
        if self.dependent || self.rgba.is_some() {
            return Err(Error::InvalidArgument(
                "dependent and RGBA components are not read from a store: it holds one component".into(),
            ));
        }
        if octree.id != self.octree_id {
            return Err(Error::InvalidArgument(
                "this selection was made from another octree: select again from this one".into(),
            ));
        }
        Ok(())
    }

    /// Brick `brick`'s texels read from `store`: with the gradient border
    /// when `bordered`; into `texels` as f32 when `encoded` is empty, else
    /// in the selection's texel format as `brick_texels_encoded` gives them.
    /// A brick the background reader has read (`super::loading`) is taken
    /// from it; any other is read here.
    pub(crate) fn brick_texels_from_store(
        &self,
        octree: &HybridOctreeHandle,
        store: &StoreHandle,
        brick: usize,
        bordered: bool,
        texels: &mut [f32],
        encoded: &mut [u8],
    ) -> Bridged<()> {
        guarded(|| {
            self.check_store(octree, store)?;
            let s: &Store = &store.store;
            let b = &self.selected_brick(brick)?;
            let border = usize::from(bordered);
            // A coarse brick of maximum or minimum intensity keeps each texel's
            // peak over its stride, which the levels do not hold, except for a
            // constant node (the selection's only exact coarse form): its
            // subsampled texels are its peaks, checked below.
            let node = octree.volume().node(b.node);
            let constant = node.min == node.max;
            let peaks_needed = self.blend.mode.is_extremum() && b.stride > 1 && border == 0;
            if peaks_needed && !constant {
                return Err(Error::InvalidArgument(
                    "maximum and minimum intensity need each coarse texel's peak over its stride, which a store's \
                     subsampled levels do not hold: raise the budget so that every brick is at full resolution, or \
                     read the volume into memory (the reader's MaximumMegabytes large enough for level 0)"
                        .into(),
                ));
            }
            let (read, read_border) = match store.take_loaded(&loaded_read(b)) {
                Some(loaded) => (loaded, 1),
                None => {
                    let read = s.read_texels(b.stride, b.lo, b.texels, border)?;
                    store.bytes_read.fetch_add(read.samples.as_bytes().len() as u64, Ordering::Relaxed);
                    (read, border)
                }
            };
            let grid = read.grid(None)?;
            // Within a constant node's range, its samples are all its value unless some are NaN.
            let holes = check_against_octree(&grid, &node, b, read_border, s)?;
            if peaks_needed && holes {
                return Err(Error::InvalidArgument(format!(
                    "maximum and minimum intensity: node {} of '{}' holds {} but samples of no data (NaN) at \
                     stride {}, whose peaks its levels do not hold: raise the budget so that every brick is at full \
                     resolution, or read the volume into memory",
                    b.node.0,
                    s.label(),
                    node.min,
                    b.stride
                )));
            }
            // The read volume is the brick's texel lattice (and `read_border`
            // more on each side): the brick is its stride-1 brick.
            let local = Brick { lo: [read_border; 3], hi: b.texels.map(|n| read_border + n - 1), stride: 1, ..*b };
            if encoded.is_empty() {
                if bordered {
                    brick_texels_f32_bordered_into(&grid, &local, texels)?;
                } else {
                    brick_texels_f32_into(&grid, &local, texels)?;
                }
            } else {
                brick_texels_encoded_into(&grid, &local, (border, self.blend.mode), &self.texel, texels, encoded)?;
            }
            check_f32_resolution(s.scalar_type, self.value_range)?;
            finite_texels(brick, s.scalar_type, texels)
        })
    }
}
