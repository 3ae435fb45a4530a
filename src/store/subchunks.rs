//! Decoded subchunks kept for the next read, least recently used first out,
//! under a byte budget: neighbouring bricks share the subchunk planes of
//! their shared faces (a 17^3 brick of stride 1 touches eight 16^3
//! subchunks, one of them its own), so each subchunk a frame needs is
//! decoded about once instead of about eight times.

use super::zarr::{typed_samples, zarr_error, Storage};
use crate::base::error::Result;
use crate::data::grid::ScalarType;
use crate::data::volume::SampleBuf;
use lru::LruCache;
use std::sync::{Arc, Mutex};
use zarrs::array::{Array, ArrayShardedReadableExt, ArrayShardedReadableExtCache, CodecOptions};

/// Samples per axis of a subchunk (the writer's).
pub const EDGE: usize = 16;

/// A level's subchunk: (level, z, y, x index).
type Key = (usize, [u64; 3]);

/// The cache.
pub struct SubchunkCache {
    entries: Mutex<LruCache<Key, Arc<SampleBuf>>>,
}

impl SubchunkCache {
    /// A cache of at most `bytes` of decoded `scalar_type` subchunks (at least one).
    pub fn new(bytes: usize, scalar_type: ScalarType) -> SubchunkCache {
        let each = EDGE * EDGE * EDGE * scalar_type.size();
        let count = std::num::NonZeroUsize::new((bytes / each).max(1)).unwrap_or(std::num::NonZeroUsize::MIN);
        SubchunkCache { entries: Mutex::new(LruCache::new(count)) }
    }

    /// Subchunk `index` (z, y, x) of `array` (level `level`), decoded:
    /// from the cache, or read, decoded and kept.
    pub fn get(
        &self,
        label: &str,
        (level, array, shards): (usize, &Array<Storage>, &ArrayShardedReadableExtCache),
        scalar_type: ScalarType,
        index: [u64; 3],
    ) -> Result<Arc<SampleBuf>> {
        if let Some(hit) = self.lock().get(&(level, index)) {
            return Ok(hit.clone());
        }
        let options = CodecOptions::default();
        let err = |e: zarrs::array::ArrayError| zarr_error(label, "reading a subchunk", &e);
        let decoded =
            Arc::new(typed_samples!(scalar_type, array.retrieve_subchunk_opt(shards, &index, &options).map_err(err)?));
        if decoded.len() != EDGE * EDGE * EDGE {
            return Err(zarr_error(
                label,
                "reading a subchunk",
                &format!("subchunk {index:?} of level {level} holds {} samples, not {EDGE}^3", decoded.len()),
            ));
        }
        self.lock().put((level, index), decoded.clone());
        Ok(decoded)
    }

    /// The entries, whatever a panicking reader left (the cache holds no invariant a panic breaks).
    fn lock(&self) -> std::sync::MutexGuard<'_, LruCache<Key, Arc<SampleBuf>>> {
        self.entries.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// Copies the part of subchunk `index` (`EDGE^3` samples, x fastest) that
/// lies in the level box `lo ..= hi` (x, y, z) into `out` (the box's
/// samples, x fastest); false when their types differ (nothing copied).
pub fn copy_into(sub: &SampleBuf, index: [u64; 3], lo: [usize; 3], hi: [usize; 3], out: &mut SampleBuf) -> bool {
    fn copy<T: Copy>(src: &[T], index: [u64; 3], lo: [usize; 3], hi: [usize; 3], dst: &mut [T]) {
        // The subchunk's first sample, x y z.
        let base = [index[2] as usize * EDGE, index[1] as usize * EDGE, index[0] as usize * EDGE];
        let a = [0, 1, 2].map(|d| lo[d].max(base[d]));
        let b = [0, 1, 2].map(|d| hi[d].min(base[d] + EDGE - 1));
        if (0..3).any(|d| a[d] > b[d]) {
            return;
        }
        let n = [0, 1, 2].map(|d| hi[d] - lo[d] + 1);
        let w = b[0] - a[0] + 1;
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                let s = (a[0] - base[0]) + EDGE * ((y - base[1]) + EDGE * (z - base[2]));
                let d = (a[0] - lo[0]) + n[0] * ((y - lo[1]) + n[1] * (z - lo[2]));
                dst[d..d + w].copy_from_slice(&src[s..s + w]);
            }
        }
    }
    match (sub, out) {
        (SampleBuf::U8(s), SampleBuf::U8(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::I8(s), SampleBuf::I8(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::U16(s), SampleBuf::U16(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::I16(s), SampleBuf::I16(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::U32(s), SampleBuf::U32(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::I32(s), SampleBuf::I32(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::F32(s), SampleBuf::F32(d)) => copy(s, index, lo, hi, d),
        (SampleBuf::F64(s), SampleBuf::F64(d)) => copy(s, index, lo, hi, d),
        _ => return false,
    }
    true
}
