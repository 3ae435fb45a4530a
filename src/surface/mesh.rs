//! The extracted isosurface and what describes it: [`Surface`] (points,
//! normals, polygons by terminal node), [`SurfaceMode`], [`SurfaceOptions`]
//! and [`SurfaceStats`]. Extraction is [`super::build`]; points and normals
//! [`super::place`]; measures [`super::check`].

use crate::base::error::{Error, Result};
use crate::octree::NodeId;

/// Which isosurface to keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfaceMode {
    /// Discretized Marching Cubes: vertices at edge midpoints, coplanar facets merged.
    Discretized,
    /// Classic Marching Cubes: vertices linearly interpolated along edges, triangles.
    Interpolated,
}

impl SurfaceMode {
    /// Parses `discretized` / `interpolated`.
    pub fn parse(s: &str) -> Result<SurfaceMode> {
        match s.to_ascii_lowercase().as_str() {
            "discretized" | "discmc" => Ok(SurfaceMode::Discretized),
            "interpolated" | "mc" => Ok(SurfaceMode::Interpolated),
            other => Err(Error::InvalidArgument(format!(
                "unknown surface mode '{other}': use 'discretized' (DiscMC, merged facets) or 'interpolated' (classic MC)"
            ))),
        }
    }
    /// The name used by the CLI and the filter.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceMode::Discretized => "discretized",
            SurfaceMode::Interpolated => "interpolated",
        }
    }
}

/// What to extract.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceOptions {
    /// The isovalue; inside is `value >= isovalue`.
    pub isovalue: f64,
    /// Discretized or interpolated.
    pub mode: SurfaceMode,
    /// Merge coplanar facets (Discretized only; interpolated facets are never coplanar by construction).
    pub compress: bool,
}

impl SurfaceOptions {
    /// Discretized with compression, the Hybrid Octree's own surface.
    pub fn discretized(isovalue: f64) -> Self {
        SurfaceOptions { isovalue, mode: SurfaceMode::Discretized, compress: true }
    }
    /// The interpolated Marching Cubes surface.
    pub fn interpolated(isovalue: f64) -> Self {
        SurfaceOptions { isovalue, mode: SurfaceMode::Interpolated, compress: false }
    }
}

/// Counts and times of an extraction.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct SurfaceStats {
    /// Polygons (triangles) in the output.
    pub polygons: usize,
    /// Faces: coplanar facets merged into one polygon (DiscMC with
    /// compression), or the triangles themselves.
    pub faces: usize,
    /// Triangles in the output (every face triangulated with its own vertices).
    pub triangles: usize,
    /// Triangles marched, before compression.
    pub uncompressed_triangles: usize,
    /// Points in the output.
    pub vertices: usize,
    /// Edges used by one polygon only where the surface leaves the volume.
    pub boundary_edges: usize,
    /// Edges used by one polygon only along the no-data region (cells with
    /// a NaN corner have no facets; [`super::check::nan_boundary_edges`]).
    pub nan_boundary_edges: usize,
    /// Terminal nodes with surface.
    pub surface_nodes: usize,
    /// Marching time (all nodes, parallel), ms.
    pub extract_ms: f64,
    /// Compression (merging, straight vertices, triangulation), vertex naming and assembly time, ms.
    pub compress_ms: f64,
}

/// An extracted isosurface.
#[derive(Debug, Clone)]
pub struct Surface {
    /// The isovalue.
    pub isovalue: f64,
    /// Discretized or interpolated.
    pub mode: SurfaceMode,
    /// Edge key of each point (unique; vertices on node boundaries first, in
    /// key order, then each node's inner vertices).
    pub keys: Vec<u64>,
    /// Index-space positions.
    pub points: Vec<[f64; 3]>,
    /// Unit outward normals in world space.
    pub normals: Vec<[f32; 3]>,
    /// Start of each polygon (a triangle) in `connectivity`, plus the end.
    pub offsets: Vec<u32>,
    /// Point indices, counter-clockwise seen from outside.
    pub connectivity: Vec<u32>,
    /// The terminal node of each polygon.
    pub polygon_node: Vec<NodeId>,
    /// The face (merged coplanar polygon) each triangle belongs to.
    pub polygon_face: Vec<u32>,
    /// Per terminal node with surface: (node, first polygon, end polygon).
    pub node_ranges: Vec<(NodeId, u32, u32)>,
    /// Counts and times.
    pub stats: SurfaceStats,
}

impl Surface {
    /// Number of polygons.
    pub fn polygon_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
    /// Point indices of polygon `i`.
    pub fn polygon(&self, i: usize) -> &[u32] {
        &self.connectivity[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}
