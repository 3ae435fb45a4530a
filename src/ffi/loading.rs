//! A store's bricks loaded in the background while frames are drawn
//! ([`crate::store::brick_loader`]): each frame asks for the bricks of its
//! selection it does not hold, most important first, and draws the ones
//! still loading by stand-ins ([`crate::plan::select::merged_stand_ins`]),
//! the same nodes at a coarser stride read at once, merged up the octree
//! where they tile a node, so the picture never has a hole and refines
//! over the next frames.

use super::guard::{check_len, guarded, Bridged};
use super::octree::HybridOctreeHandle;
use super::render::SelectionHandle;
use super::store::{loaded_read, StoreHandle};
use super::LoadingSummary;
use crate::base::error::Error;
use crate::plan::select::merged_stand_ins;
use std::collections::HashSet;
use std::sync::Arc;

/// How many levels coarser a stand-in is, `c`: 1/64 of its brick's
/// texels, so the stand-ins of a whole frame cost about 1/64 of its reads
/// (at most 1/32 merged; neighbouring stand-ins share the subchunks they
/// decode), and the frame reads them at once. A brick at `p = 0` has no
/// coarser form: the frame reads it itself.
pub const STAND_IN_LEVELS: usize = 2;

/// The largest merged stand-in, `p_max`: `2^5 + 1 = 33` texels a side, so
/// that a first frame's stand-ins merge by up to three levels of the
/// octree (each merge takes up to eight) into far fewer draws than one
/// per brick ([`crate::plan::select::merged_stand_ins`]).
pub const MERGED_STAND_IN_LOG2: usize = 5;

/// A frame uploads at most `1/UPLOAD_SHARE` of its selection's texture
/// bytes of read bricks, most important first; the other read bricks stand
/// in one more frame (the reader keeps them), so a frame's time stays
/// bounded however many bricks arrived since the last one, and the picture
/// refines over at least this many frames. The first read brick of a frame
/// uploads whatever its size, so that every frame refines.
pub const UPLOAD_SHARE: usize = 4;

impl SelectionHandle {
    /// Plans this frame's loading from `store`: the bricks whose textures
    /// are not resident (`resident_nodes[i]`, `resident_strides[i]`: the
    /// frame's resident textures) and not read yet are asked of the
    /// background reader, whose read bricks waiting for upload may hold
    /// `memory_bytes`; until read, each is drawn by its stand-in (the
    /// DrawLists and brick texels made after this call). Maximum and
    /// minimum intensity have none: a coarse stand-in would need each
    /// texel's peak over its stride, which the store's levels do not hold,
    /// so their frames read their bricks themselves.
    pub(crate) fn plan_loading(
        &self,
        octree: &HybridOctreeHandle,
        store: &StoreHandle,
        resident_nodes: &[u32],
        resident_strides: &[usize],
        memory_bytes: usize,
    ) -> Bridged<LoadingSummary> {
        guarded(|| {
            self.check_store(octree, store)?;
            check_len("the resident textures' strides", resident_strides, resident_nodes.len())?;
            if self.blend.mode.is_extremum() {
                self.draw_selected();
                return Ok(LoadingSummary {
                    stand_ins: 0,
                    loaded: 0,
                    queued: 0,
                    waiting_bytes: 0,
                    bytes_read: store.bytes_read(),
                });
            }
            let loader = store.loader()?;
            if let Some(failure) = loader.failure() {
                // The reader's own message, which names the store.
                return Err(Error::InvalidArgument(failure));
            }
            let resident: HashSet<(u32, usize)> =
                resident_nodes.iter().copied().zip(resident_strides.iter().copied()).collect();
            let bricks = &self.selection.bricks;
            // Most important first; ties in the selection's order.
            let mut order: Vec<usize> = (0..bricks.len()).collect();
            order.sort_by(|&a, &b| bricks[b].importance.total_cmp(&bricks[a].importance).then(a.cmp(&b)));
            let mut wanted = Vec::new();
            let mut standing = Vec::new();
            let mut uploads = self.selection.texture_bytes / UPLOAD_SHARE;
            let mut uploading = false;
            for i in order {
                let b = &bricks[i];
                if b.p == 0 || resident.contains(&(b.node.0, b.stride)) {
                    continue;
                }
                let read = loaded_read(b);
                // The first read brick uploads whatever its size: every frame refines.
                if loader.is_ready(&read) && (b.bytes <= uploads || !uploading) {
                    uploads = uploads.saturating_sub(b.bytes);
                    uploading = true;
                } else {
                    standing.push(i);
                }
                wanted.push(read);
            }
            loader.request(&wanted, memory_bytes);
            standing.sort_unstable();
            let drawn = (!standing.is_empty()).then(|| {
                Arc::new(merged_stand_ins(
                    octree.volume(),
                    &self.selection,
                    &standing,
                    STAND_IN_LEVELS,
                    self.texel.bytes(),
                    MERGED_STAND_IN_LOG2,
                ))
            });
            *self.stand_ins.lock().unwrap_or_else(|e| e.into_inner()) = drawn;
            let status = loader.status();
            Ok(LoadingSummary {
                stand_ins: standing.len(),
                loaded: wanted.len() - standing.len(),
                queued: status.pending,
                waiting_bytes: status.ready_bytes,
                bytes_read: store.bytes_read(),
            })
        })
    }

    /// Draws the selection's own bricks again (no stand-ins): loading done
    /// by the frames themselves.
    pub(crate) fn draw_selected(&self) {
        *self.stand_ins.lock().unwrap_or_else(|e| e.into_inner()) = None;
    }
}
