//! Which passes a scene needs (ARCHITECTURE section 6) and the DrawList the
//! renderers execute.
//!
//! The planner looks at the scene and emits only what it calls for, and says
//! which passes it chose ([`Plan::passes`]):
//!
//! - no surface: volume bricks only;
//! - opaque surface: the surface pass first (depth test and write), then the
//!   bricks with depth test only, no interleaving;
//! - translucent surface: each brick's triangle batches drawn inside its
//!   slabs, back to front, clip planes only for batches spanning slabs;
//! - bricks fully transparent under the transfer function: never selected
//!   (no texture spent), counted in [`Plan::skipped_bricks`];
//! - shading only when asked for.

use crate::camera::Camera;
use crate::select::Brick;

/// How the surface is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfacePass {
    /// No surface in the scene.
    None,
    /// Opaque: a depth-tested surface pass before the volume.
    Opaque,
    /// Translucent: batches inside the slabs of the bricks.
    Translucent,
}

/// What the renderer will do, and why it skipped the rest.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Plan {
    /// Any brick to draw.
    pub volume: bool,
    /// How the surface is drawn.
    pub surface: SurfacePass,
    /// Gradient shading of the volume.
    pub shading: bool,
    /// Nodes not selected because the transfer function makes them fully transparent.
    pub skipped_bricks: usize,
    /// The passes, in the order they run (e.g. `["surface-opaque", "volume"]`).
    pub passes: Vec<String>,
}

/// Triangles of the surface drawn between two slices of a brick.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Batch {
    /// Slab index within the brick: slab `s` lies between slices `s` and `s + 1`
    /// counted from the back (see [`BrickDraw::slices`]).
    pub slab: usize,
    /// Surface triangle ids.
    pub triangles: Vec<u32>,
    /// `Some((near, far))`: clip to view depths `near <= depth < far`
    /// (batches whose triangles span more than this slab).
    pub clip: Option<(f64, f64)>,
}

/// One brick of the DrawList.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BrickDraw {
    /// The texture request: node, level p, texel box.
    pub brick: Brick,
    /// World box of the brick.
    pub world_lo: [f64; 3],
    /// World box of the brick.
    pub world_hi: [f64; 3],
    /// World distance d between consecutive slices (the brick's sample
    /// spacing along the view); opacity is corrected by `a' = 1 - (1 - a)^(d/d0)`.
    pub slice_spacing: f64,
    /// View depths of the slices through the brick, back to front: slice
    /// planes at depths `k * slice_spacing` (a lattice shared by all bricks of
    /// the same spacing), those inside the brick's depth range.
    pub slices: Vec<f64>,
    /// Surface batches (translucent surfaces only), back to front.
    pub batches: Vec<Batch>,
}

/// What every renderer executes: bricks in compositing order (back to
/// front), their slices, and the surface passes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DrawList {
    /// The plan.
    pub plan: Plan,
    /// The camera the list was made for.
    pub camera: Camera,
    /// Bricks back to front.
    pub bricks: Vec<BrickDraw>,
    /// Opaque surface pass: all triangle ids (empty unless the plan says opaque).
    pub opaque_triangles: Vec<u32>,
    /// Reference slice spacing d0 (world units): the full-resolution sample
    /// spacing, against which opacity is corrected.
    pub reference_spacing: f64,
}
