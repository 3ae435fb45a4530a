//! The Hybrid Octree the host holds ([`HybridOctreeHandle`]): built from a
//! borrowed image (volume data integration), its summary and its cuts. The
//! surface and the points are integrated into it in `surface.rs` and
//! `points.rs`.

use super::grid::grid_of;
use super::guard::{guarded, Bridged};
use super::{BuildProgress, CutBoxes, GridDesc, OctreeSummary};
use crate::grid::GridShape;
use crate::hybrid::HybridOctree;
use crate::octree::{BuildOptions, VolumeOctree};
use std::sync::atomic::{AtomicU64, Ordering};

/// A Hybrid Octree with the geometry needed to place its boxes.
#[derive(Debug)]
pub struct HybridOctreeHandle {
    pub(crate) hybrid: HybridOctree,
    /// The image the octree was built from (dims, spacing, origin).
    pub(crate) shape: GridShape,
    pub(crate) input_bytes: usize,
    pub(crate) nan_samples: usize,
    /// The image's scalar type (what the texel format resolves for).
    pub(crate) scalar_type: crate::data::grid::ScalarType,
    /// Two dependent fields (see `dependent.rs`): the combined tree the
    /// selections refine; `hybrid.volume` is then the colour field's.
    pub(crate) dependent: Option<VolumeOctree>,
    /// An RGBA volume (see `rgba.rs`; `dependent` its combined tree,
    /// `hybrid.volume` component 0's): VTK's reading of its components.
    pub(crate) rgba: Option<crate::transfer::direct_colour::RgbaScale>,
    /// Unique per build: a selection remembers the octree it was made from.
    pub(crate) id: u64,
    /// Unique per integrated surface (0: none): a selection's kept
    /// SlabPolygons remember the surface they were made for.
    pub(crate) surface_id: u64,
    /// The last selection's forms and steps, for the next one (`reselect`).
    pub(crate) selector: std::sync::Mutex<super::reselect::KeptSelector>,
    /// The visibility estimate's medium of the last `prepare_view` (`view`).
    pub(crate) medium: std::sync::Mutex<super::view::KeptMedium>,
}

/// The next unique id of an octree or a surface.
pub(crate) fn next_id() -> u64 {
    static NEXT_ID: AtomicU64 = AtomicU64::new(1);
    NEXT_ID.fetch_add(1, Ordering::Relaxed)
}

pub(crate) fn build_hybrid_octree(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &BuildProgress,
) -> Bridged<Box<HybridOctreeHandle>> {
    build_with(bytes, desc, leaf_size, &mut |fraction| progress.report(fraction))
}

/// Builds through [`VolumeOctree::build_with_progress`]: `progress(fraction)`
/// between chunks of leaf bricks, `false` cancels.
pub(crate) fn build_with(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Bridged<Box<HybridOctreeHandle>> {
    guarded(|| {
        let grid = grid_of(bytes, desc)?;
        let options = BuildOptions { leaf_size: leaf_size as usize };
        let volume = VolumeOctree::build_with_progress(&grid, &options, progress)?;
        Ok(Box::new(HybridOctreeHandle {
            hybrid: HybridOctree::volume_only(volume),
            shape: *grid.shape(),
            input_bytes: grid.input_bytes(),
            nan_samples: grid.nan_count(),
            scalar_type: grid.samples().scalar_type(),
            dependent: None,
            rgba: None,
            id: next_id(),
            surface_id: 0,
            selector: Default::default(),
            medium: Default::default(),
        }))
    })
}

impl HybridOctreeHandle {
    /// The Volume Octree.
    pub(crate) fn volume(&self) -> &VolumeOctree {
        &self.hybrid.volume
    }

    pub(crate) fn summary(&self) -> Bridged<OctreeSummary> {
        guarded(|| {
            let s = self.volume().stats();
            Ok(OctreeSummary {
                node_count: s.node_count,
                terminal_count: s.terminal_count,
                homogeneous_count: s.homogeneous_count,
                levels: s.levels as u32,
                leaf_size: s.leaf_size as u32,
                root_size: s.root_size as u32,
                octree_bytes: s.octree_bytes + self.dependent.as_ref().map_or(0, |d| d.octree_bytes()),
                input_bytes: self.input_bytes,
                build_ms: s.build_ms,
                value_min: s.value_range.0,
                value_max: s.value_range.1,
                nan_samples: self.nan_samples,
            })
        })
    }

    pub(crate) fn cut_boxes(&self, tolerance: f64) -> Bridged<CutBoxes> {
        guarded(|| {
            let octree = self.volume();
            let cut = octree.cut(tolerance)?;
            let mut out = CutBoxes {
                bounds: Vec::with_capacity(cut.len() * 6),
                node_id: Vec::with_capacity(cut.len()),
                level: Vec::with_capacity(cut.len()),
                nodal_error: Vec::with_capacity(cut.len()),
                min: Vec::with_capacity(cut.len()),
                max: Vec::with_capacity(cut.len()),
            };
            for id in cut {
                let node = octree.node(id);
                let lo = self.shape.world(node.lo.map(|v| v as f64));
                let hi = self.shape.world(node.hi.map(|v| v as f64));
                out.bounds.extend_from_slice(&[lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]);
                out.node_id.push(id.0);
                out.level.push(node.level as u32);
                out.nodal_error.push(node.errors.first().copied().unwrap_or(0.0));
                let empty = node.min > node.max; // a box of NaN only: (+inf, -inf)
                out.min.push(if empty { f64::NAN } else { node.min });
                out.max.push(if empty { f64::NAN } else { node.max });
            }
            Ok(out)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{as_bytes, build_volume_octree, f32_desc};
    use super::super::ScalarType;
    use super::*;

    #[test]
    fn bridge_builds_and_cuts() {
        let data: Vec<f32> = (0..27).map(|i| (i * i) as f32).collect();
        let desc = GridDesc {
            scalar_type: ScalarType::F32,
            dims: [3, 3, 3],
            spacing: [1.0, 2.0, 3.0],
            origin: [0.0; 3],
            components: 1,
            component: -1,
        };
        let h = build_volume_octree(as_bytes(&data), &desc, 2).unwrap();
        h.volume().validate().unwrap();
        assert!(h.hybrid.surface.is_none() && h.hybrid.points.is_none(), "the volume alone at first");
        let s = h.summary().unwrap();
        assert_eq!(s.input_bytes, 27 * 4);
        let cut = h.cut_boxes(0.0).unwrap();
        assert_eq!(cut.bounds.len(), cut.level.len() * 6);
        assert_eq!(cut.bounds[..6], [0.0, 2.0, 0.0, 4.0, 0.0, 6.0]);
        let bad = GridDesc { component: 3, ..desc };
        assert!(build_volume_octree(as_bytes(&data), &bad, 2).unwrap_err().contains("component 3"));
    }

    /// A 64^3 ramp (4096 leaf bricks of 4: 16 progress chunks of 256).
    fn ramp64() -> (Vec<f32>, GridDesc) {
        let data: Vec<f32> = (0..64 * 64 * 64).map(|i| (i % 977) as f32).collect();
        (data, f32_desc([64; 3]))
    }

    #[test]
    fn progress_increases_to_one_and_the_build_is_unchanged() {
        let (data, desc) = ramp64();
        let mut seen = Vec::new();
        let h = build_with(as_bytes(&data), &desc, 4, &mut |f| {
            seen.push(f);
            true
        })
        .unwrap();
        assert_eq!(seen.len(), 16, "one report per chunk of 256 leaves: {seen:?}");
        assert!(seen.windows(2).all(|w| w[0] < w[1]) && seen[0] > 0.0, "{seen:?}");
        assert_eq!(*seen.last().unwrap(), 1.0);
        let plain = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        assert_eq!(h.summary().unwrap().node_count, plain.summary().unwrap().node_count);
        assert_eq!(h.cut_boxes(0.0).unwrap().bounds, plain.cut_boxes(0.0).unwrap().bounds);
    }

    #[test]
    fn a_false_report_cancels_at_once_with_a_clear_error() {
        let (data, desc) = ramp64();
        let mut calls = 0;
        let err = build_with(as_bytes(&data), &desc, 4, &mut |_| {
            calls += 1;
            calls < 3
        })
        .expect_err("a cancelled build returns no octree");
        assert_eq!(calls, 3, "no report after the one that said stop");
        assert!(err.contains("cancelled") && err.contains("nothing was produced"), "{err}");
    }
}
