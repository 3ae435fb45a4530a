//! The Hybrid Octree (paper 1, section 2.3): the Volume Octree and the
//! surface it contains, known node by node.
//!
//! Construction follows the paper: (1) volume data integration builds the
//! Volume Octree with min/max and nodal errors per node; (2) surface data
//! integration visits the terminal nodes whose `[min, max]` brackets the
//! isovalue and codes their surface (DiscMC facets merged into planar
//! polygons, or interpolated triangles). Each terminal node owns a contiguous
//! range of polygons, every polygon lies inside its node's box, so later
//! stages can take a node's volume and its surface together.

use crate::error::Result;
use crate::grid::Grid;
use crate::octree::{BuildOptions, NodeId, VolumeOctree};
use crate::surface::{Surface, SurfaceMode, SurfaceOptions};

/// A Volume Octree and the isosurface it holds, node by node.
#[derive(Debug, Clone)]
pub struct HybridOctree {
    /// The Volume Octree.
    pub volume: VolumeOctree,
    /// The isosurface, polygons grouped by terminal node.
    pub surface: Surface,
}

impl HybridOctree {
    /// Builds both octrees from `grid`.
    pub fn build(grid: &Grid<'_>, build: &BuildOptions, surface: &SurfaceOptions) -> Result<HybridOctree> {
        let volume = VolumeOctree::build(grid, build)?;
        let surface = Surface::extract(grid, &volume, surface)?;
        Ok(HybridOctree { volume, surface })
    }

    /// The polygon index range of terminal node `id` (empty when it holds no surface).
    pub fn polygons_of(&self, id: NodeId) -> std::ops::Range<usize> {
        match self.surface.node_ranges.binary_search_by_key(&id, |r| r.0) {
            Ok(i) => self.surface.node_ranges[i].1 as usize..self.surface.node_ranges[i].2 as usize,
            Err(_) => 0..0,
        }
    }

    /// Checks the Volume Octree, then that every polygon belongs to exactly one
    /// terminal node (the node ranges partition the polygons, each range's
    /// polygons name its node), that every polygon lies inside its node's box,
    /// has at least 3 points and (DiscMC) a non-zero area, that no edge is used by
    /// more than two polygons or twice in the same direction, and that the
    /// edges used once are exactly the reported open ones: on the volume's
    /// faces and along NaN (no data).
    pub fn validate(&self) -> std::result::Result<(), String> {
        self.volume.validate()?;
        let s = &self.surface;
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
