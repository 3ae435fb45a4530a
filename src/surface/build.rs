//! Extracting the isosurface of the Hybrid Octree: march the terminal nodes
//! that bracket the isovalue in parallel, compress each node's facets, name
//! vertices once for the whole mesh, drop straight vertices, and place points
//! and normals.
//!
//! Points and normals: [`super::place`].
//!
//! Polygons are ordered by terminal node id (level by level, x fastest);
//! `node_ranges` gives each node's polygons. Deterministic: every step is
//! either per node (collected in node order) or a sort.

use super::assemble::{assemble, Mesh, NodePart};
use super::extract::{march, EdgeIndex, NodeTriangles, Record};
use super::faces::{merge_coplanar, NodeFaces};
pub use super::mesh::{Surface, SurfaceMode, SurfaceOptions, SurfaceStats};
use super::place::{finish_normals, Placer};
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::octree::{NodeId, VolumeOctree};
use rayon::prelude::*;
use std::time::Instant;

impl Surface {
    /// Extracts the isosurface of `grid` through the terminal nodes of `octree`
    /// (built from the same grid). An isovalue outside the data range gives an
    /// empty surface; a non-finite one is an error.
    pub fn extract(grid: &Grid<'_>, octree: &VolumeOctree, options: &SurfaceOptions) -> Result<Surface> {
        if !options.isovalue.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "isovalue {} must be a finite number (inside the data range {} .. {} to get a surface)",
                options.isovalue,
                octree.value_range().0,
                octree.value_range().1
            )));
        }
        if grid.dims() != octree.layout().dims {
            return Err(Error::InvalidArgument(format!(
                "the grid ({:?}) is not the one the octree was built from ({:?}); rebuild the octree",
                grid.dims(),
                octree.layout().dims
            )));
        }
        grid.visit(Extraction { octree, options, spacing: grid.shape().spacing, has_nan: grid.nan_count() > 0 })
    }
}

/// The terminal nodes whose range brackets `isovalue` (`min < iso <= max`), by id.
pub fn surface_nodes(octree: &VolumeOctree, isovalue: f64) -> Vec<NodeId> {
    let mut nodes = Vec::new();
    octree.for_each_node(|n| {
        if n.is_terminal() && n.min < isovalue && isovalue <= n.max {
            nodes.push(n.id);
        }
    });
    nodes.sort_unstable();
    nodes
}

/// Marches every surface node (parallel, node order kept), recording cells.
pub fn march_nodes<T: Sample>(
    g: &TypedGrid<'_, T>,
    octree: &VolumeOctree,
    nodes: &[NodeId],
    iso: f64,
) -> Vec<NodeTriangles> {
    nodes
        .par_iter()
        .map_init(EdgeIndex::default, |index, &id| {
            let n = octree.node(id);
            march(g, n.lo, n.hi, iso, index, Record { cells: true, across: false })
        })
        .collect()
}

struct Extraction<'a> {
    octree: &'a VolumeOctree,
    options: &'a SurfaceOptions,
    spacing: [f64; 3],
    /// The grid has NaN samples (only then are edges along them counted).
    has_nan: bool,
}

impl GridVisitor for Extraction<'_> {
    type Output = Result<Surface>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Result<Surface> {
        let Extraction { octree, options, spacing, has_nan } = self;
        let dims = g.dims;
        let iso = options.isovalue;
        // Per node, in parallel: march its cells, then merge its coplanar
        // facets into faces while they are still in cache.
        let started = Instant::now();
        let merge = options.compress && options.mode == SurfaceMode::Discretized;
        let nodes = surface_nodes(octree, iso);
        let placer = Placer { grid: &g, isovalue: iso, mode: options.mode };
        let parts: Vec<(NodePart, usize)> = nodes
            .par_iter()
            .map_init(EdgeIndex::default, |index, &id| {
                let n = octree.node(id);
                let m = march(&g, n.lo, n.hi, iso, index, Record { cells: false, across: merge });
                let marched = m.triangles.len();
                let faces = if merge { merge_coplanar(m) } else { NodeFaces::from_triangles(m) };
                // The node's inner vertices that stay, placed while the node's samples are in cache.
                (NodePart::new(id, faces, merge, |a, axis| placer.place(a, axis)), marched)
            })
            .collect();
        let uncompressed_triangles = parts.iter().map(|p| p.1).sum();
        let parts: Vec<NodePart> = parts.into_iter().map(|p| p.0).collect();
        let extract_ms = started.elapsed().as_secs_f64() * 1e3;

        let started = Instant::now();
        let mesh = assemble(&parts)?;
        let Mesh { keys: kept, triangles, triangle_face, triangle_node, node_ranges, faces, shared } = mesh;
        // Points and raw normals: the vertices on node boundaries, then each node's inner ones.
        let mut placed: Vec<([f64; 3], [f64; 3])> = kept[..shared].par_iter().map(|&k| placer.place_key(k)).collect();
        placed.par_extend(parts.par_iter().flat_map_iter(|p| p.inner.iter().copied()));
        drop(parts);
        let (points, raw_normals): (Vec<[f64; 3]>, Vec<[f64; 3]>) = placed.into_par_iter().unzip();
        let offsets: Vec<u32> = (0..=triangles.len() as u32).into_par_iter().map(|i| 3 * i).collect();
        let connectivity: Vec<u32> = triangles.par_iter().flat_map_iter(|t| t.iter().copied()).collect();
        let mut surface = Surface {
            isovalue: iso,
            mode: options.mode,
            keys: kept,
            points,
            normals: Vec::new(),
            offsets,
            connectivity,
            polygon_node: triangle_node,
            polygon_face: triangle_face,
            node_ranges,
            stats: SurfaceStats::default(),
        };
        surface.normals = finish_normals(&surface, raw_normals, spacing);
        surface.stats = SurfaceStats {
            polygons: surface.polygon_count(),
            faces,
            triangles: surface.polygon_count(),
            uncompressed_triangles,
            vertices: surface.points.len(),
            boundary_edges: super::check::boundary_edges(&surface, dims),
            nan_boundary_edges: if has_nan {
                super::check::nan_boundary_edges_with(&surface, dims, |p| g.at(p[0], p[1], p[2]).is_nan())
            } else {
                0
            },
            surface_nodes: nodes.len(),
            extract_ms,
            compress_ms: started.elapsed().as_secs_f64() * 1e3,
        };
        Ok(surface)
    }
}
