//! The Hybrid Octree (paper 1, section 2.3): the Volume Octree and the
//! surface it contains, known node by node, and (paper 3) the points that
//! complete its low-resolution textures.
//!
//! Construction follows the paper: (1) volume data integration builds the
//! Volume Octree with min/max and nodal errors per node; (2) surface data
//! integration visits the terminal nodes whose `[min, max]` brackets the
//! isovalue and codes their surface (DiscMC facets merged into planar
//! polygons, or interpolated triangles). Each terminal node owns a contiguous
//! range of polygons, every polygon lies inside its node's box, so later
//! stages can take a node's volume and its surface together. Both steps after
//! the first are optional: a Hybrid Octree may hold the volume alone, and the
//! surface and points are integrated (or dropped) as the view asks.
//!
//! The renderers' entry points for a whole Hybrid Octree are here:
//! [`HybridOctree::draw_list`] and [`HybridOctree::slab_polygons`].

use crate::camera::Camera;
use crate::error::Result;
use crate::grid::{Grid, GridShape};
use crate::octree::{BuildOptions, NodeId, VolumeOctree};
use crate::plan::select::Selection;
use crate::plan::slab::SlabPolygons;
use crate::plan::{draw_list, DrawList, Scene};
use crate::points::mass::PointMass;
use crate::points::PointSet;
use crate::surface::{Surface, SurfaceMode, SurfaceOptions};
use std::sync::Arc;

/// A Volume Octree, the isosurface it holds node by node, and the points
/// completing its textures; the surface and the points are optional.
#[derive(Debug, Clone)]
pub struct HybridOctree {
    /// The Volume Octree.
    pub volume: VolumeOctree,
    /// The isosurface, polygons grouped by terminal node.
    pub surface: Option<Surface>,
    /// The points of the hybrid point/volume representation.
    pub points: Option<HybridPoints>,
}

/// The points of the hybrid representation (paper 3) as a Hybrid Octree
/// holds them: the set (shared with the selections that bought points) and
/// its per-block mass, what the selection weighs them by.
#[derive(Debug, Clone)]
pub struct HybridPoints {
    /// The points.
    pub set: Arc<PointSet>,
    /// Their error mass per leaf block.
    pub mass: PointMass,
}

impl HybridOctree {
    /// Builds both octrees from `grid`.
    pub fn build(grid: &Grid<'_>, build: &BuildOptions, surface: &SurfaceOptions) -> Result<HybridOctree> {
        let volume = VolumeOctree::build(grid, build)?;
        let surface = Surface::extract(grid, &volume, surface)?;
        Ok(HybridOctree { volume, surface: Some(surface), points: None })
    }

    /// The Volume Octree alone (surface and points integrated later).
    pub fn volume_only(volume: VolumeOctree) -> HybridOctree {
        HybridOctree { volume, surface: None, points: None }
    }

    /// The polygon index range of terminal node `id` (empty when it holds no surface).
    pub fn polygons_of(&self, id: NodeId) -> std::ops::Range<usize> {
        let Some(surface) = &self.surface else { return 0..0 };
        match surface.node_ranges.binary_search_by_key(&id, |r| r.0) {
            Ok(i) => surface.node_ranges[i].1 as usize..surface.node_ranges[i].2 as usize,
            Err(_) => 0..0,
        }
    }

    /// The scene of this octree: its surface (when it holds one) at
    /// `surface_opacity` (1 opaque, in (0, 1) translucent, 0 hidden), no shading.
    pub fn scene(&self, surface_opacity: f64) -> Scene<'_> {
        Scene {
            surface: self.surface.as_ref(),
            surface_opacity,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        }
    }

    /// The DrawList of `selection` (made from this octree's volume over the
    /// grid of `shape`) for `camera`, with the surface at `surface_opacity`
    /// (see [`draw_list`]; `polygons`: the selection's [`SlabPolygons`] for
    /// this surface, made here when `None` and needed), under `blend`.
    pub fn draw_list(
        &self,
        shape: &GridShape,
        selection: &Selection,
        camera: &Camera,
        surface_opacity: f64,
        blend: crate::plan::Blend,
        polygons: Option<&SlabPolygons>,
    ) -> Result<DrawList> {
        draw_list(&self.volume, shape, selection, camera, &Scene { blend, ..self.scene(surface_opacity) }, polygons)
    }

    /// The surface's polygons sorted into `selection`'s bricks and slabs, what
    /// a translucent surface is drawn from; `None` without a surface.
    pub fn slab_polygons(&self, shape: &GridShape, selection: &Selection) -> Option<SlabPolygons> {
        self.surface.as_ref().map(|s| SlabPolygons::new(&self.volume, s, shape, selection))
    }

    /// Checks the Volume Octree, then that every polygon belongs to exactly one
    /// terminal node (the node ranges partition the polygons, each range's
    /// polygons name its node), that every polygon lies inside its node's box,
    /// has at least 3 points and (DiscMC) a non-zero area, that no edge is used by
    /// more than two polygons or twice in the same direction, and that the
    /// edges used once are exactly the reported open ones: on the volume's
    /// faces and along NaN (no data). Without a surface only the Volume Octree is checked.
    pub fn validate(&self) -> std::result::Result<(), String> {
        self.volume.validate()?;
        let Some(s) = &self.surface else { return Ok(()) };
        if s.polygon_node.len() != s.polygon_count() {
            return Err(format!("{} polygon nodes for {} polygons", s.polygon_node.len(), s.polygon_count()));
        }
        let mut next = 0u32;
        let mut previous: Option<NodeId> = None;
        for &(id, first, end) in &s.node_ranges {
            if first != next || end < first {
                return Err(format!("node {id:?}: polygon range {first}..{end} does not follow {next}"));
            }
            if previous.is_some_and(|p| p >= id) {
                return Err(format!("node ranges are not sorted by node at {id:?}"));
            }
            previous = Some(id);
            let node = self.volume.node(id);
            if !node.is_terminal() {
                return Err(format!("node {id:?} holds polygons but is not terminal"));
            }
            for i in first as usize..end as usize {
                if s.polygon_node[i] != id {
                    return Err(format!("polygon {i} is in node {id:?}'s range but names {:?}", s.polygon_node[i]));
                }
                let poly = s.polygon(i);
                if poly.len() < 3 {
                    return Err(format!("polygon {i} has {} points", poly.len()));
                }
                for &v in poly {
                    let p = s.points[v as usize];
                    if (0..3).any(|a| p[a] < node.lo[a] as f64 || p[a] > node.hi[a] as f64) {
                        return Err(format!(
                            "polygon {i}: point {p:?} outside node {id:?} box {:?}..{:?}",
                            node.lo, node.hi
                        ));
                    }
                }
                // DiscMC facets join distinct edge midpoints, no three collinear, and
                // ear clipping cuts only ears with a strictly turning tip: never a
                // zero-area triangle. Interpolated vertices on samples equal to the
                // isovalue may coincide (as in every Marching Cubes), so only DiscMC is held to it.
                let n = crate::surface::check::polygon_normal(s, poly);
                if s.mode == SurfaceMode::Discretized && n.iter().all(|&c| c == 0.0) {
                    return Err(format!("polygon {i} has zero area"));
                }
            }
            next = end;
        }
        if next as usize != s.polygon_count() {
            return Err(format!("node ranges cover {next} of {} polygons", s.polygon_count()));
        }
        let edges = crate::surface::check::edge_use(s);
        if edges.nonmanifold > 0 {
            return Err(format!(
                "{} edges are used by more than two polygons or twice in one direction",
                edges.nonmanifold
            ));
        }
        let open = s.stats.boundary_edges + s.stats.nan_boundary_edges;
        if edges.boundary != open {
            return Err(format!(
                "{} edges are used once, but {} lie on the volume's faces and {} along NaN",
                edges.boundary, s.stats.boundary_edges, s.stats.nan_boundary_edges
            ));
        }
        Ok(())
    }
}
