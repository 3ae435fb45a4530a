//! What a selection asks for ([`SelectOptions`], a region of interest
//! [`Roi`]) and what it returns: [`Brick`]s, one per node of the cut, in a
//! [`Selection`].
//!
//! ```text
//! bytes(n, p)  = texels_x * texels_y * texels_z * bytes_per_texel     (texels_a + 2 with a gradient border)
//! error(n, p)  = Imp(n) * e_p(n)              (e_p normalised by the data range)
//! ```

use crate::octree::{NodeId, NodeRef, VolumeOctree};

/// A region of interest: a sphere in index space.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Roi {
    /// Centre, index space.
    pub center: [f64; 3],
    /// Radius, index units (> 0).
    pub radius: f64,
}

/// What to select.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelectOptions {
    /// Texture memory budget in bytes (> 0).
    pub budget_bytes: usize,
    /// The error tolerance Eu (fraction of the data range, >= 0).
    pub tolerance: f64,
    /// Region of interest, refined first.
    pub roi: Option<Roi>,
    /// Bytes per texel (4 for f32 textures; see [`crate::plan::texel_format`]).
    pub bytes_per_texel: usize,
    /// The texel format's quantization error, normalised by the data range
    /// ([`crate::plan::texel_format::TexelEncoding::normalized_error`]): added
    /// to every brick's nodal error, `E_p + e_q` (0: exact texels).
    pub texel_error: f64,
    /// Largest brick: `2^max_brick_log2` cells per axis.
    pub max_brick_log2: u32,
    /// Count one more texel on each side of every brick in its bytes: the
    /// border the gradient of a shaded volume reads (`(n + 2)` texels per
    /// axis instead of `n`); set when the scene shades.
    pub gradient_border: bool,
    /// Coarse bricks hold peak-keeping texels (maximum and minimum
    /// intensity, [`crate::plan::BlendMode::is_extremum`]): a coarse form of
    /// a node is exact only when it is constant.
    pub pooled: bool,
    /// The samples the frame keeps (cropping, clipping planes), in index
    /// space ([`KeptRegion::to_index`](crate::plan::crop::KeptRegion::to_index)):
    /// a node whose box it removes draws nothing and is never selected
    /// (counted in [`Selection::skipped`]).
    pub region: Option<crate::plan::crop::KeptRegion>,
    /// The Slice blend mode's plane, in index space
    /// ([`SlicePlane::to_index`](crate::plan::slice::SlicePlane::to_index)):
    /// a node whose box it does not cut draws nothing and is never selected
    /// (counted in [`Selection::skipped`]).
    pub slice: Option<crate::plan::slice::SlicePlane>,
}

impl SelectOptions {
    /// A budget and a tolerance, no region of interest, f32 texels, bricks up
    /// to 128 cells per axis (129^3 texels, 8.6 MB: within every GL 3D
    /// texture limit, and large enough that data with detail everywhere can
    /// be drawn as a few big bricks with little border overhead).
    pub fn new(budget_bytes: usize, tolerance: f64) -> SelectOptions {
        SelectOptions {
            budget_bytes,
            tolerance,
            roi: None,
            bytes_per_texel: 4,
            texel_error: 0.0,
            max_brick_log2: 7,
            gradient_border: false,
            pooled: false,
            region: None,
            slice: None,
        }
    }
}

/// One selected node: a texture request.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Brick {
    /// The node.
    pub node: NodeId,
    /// Its level k.
    pub level: usize,
    /// Its voxel-to-texel level p: `2^p` cells per axis (before clipping).
    pub p: usize,
    /// Closed index box, clipped to the grid.
    pub lo: [usize; 3],
    /// Closed index box, clipped to the grid.
    pub hi: [usize; 3],
    /// Cells between texels: `2^(L - k - p)`.
    pub stride: usize,
    /// Texels per axis, borders included.
    pub texels: [usize; 3],
    /// Texture bytes.
    pub bytes: usize,
    /// e_p of the node (normalised by the data range).
    pub error: f32,
    /// Imp(n).
    pub importance: f64,
    /// Points of the hybrid representation the brick draws (0: none; see [`super::select_with_points`]).
    pub point_count: usize,
    /// Their bytes.
    pub point_bytes: usize,
}

impl Brick {
    /// Index of the texel positions along `axis`: `lo + i * stride`, the last
    /// one clamped to `hi`. For a brick clipped by the grid the last texel is
    /// closer than one stride to the one before, so a texture coordinate must
    /// be `u = (x - lo) / stride` texels, not the box scaled to `[0, 1]`.
    pub fn texel_positions(&self, axis: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.texels[axis]).map(move |i| (self.lo[axis] + i * self.stride).min(self.hi[axis]))
    }
}

/// The selected cut.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Selection {
    /// The bricks, by node id; their boxes tile the grid exactly once (the
    /// transparent nodes excepted).
    pub bricks: Vec<Brick>,
    /// Sum of the bricks' texture bytes.
    pub texture_bytes: usize,
    /// Sum of the bricks' point bytes (0 without points).
    pub point_bytes: usize,
    /// The budget asked for.
    pub budget_bytes: usize,
    /// Largest weighted error Imp(n) e_p(n) of the bricks: what the
    /// tolerance is compared with.
    pub max_error: f64,
    /// The estimated error of the picture ([`super::estimated_error`]): the largest
    /// e_p(n) of the bricks visible under the transfer function, 0 when they
    /// all draw the full-resolution field. What the CLI, the bridge and the
    /// volume mapper report.
    pub estimated_error: f64,
    /// The estimated root-mean-square error of the picture's visible samples
    /// ([`super::estimated_rms_error`]): falls with every visible brick
    /// refined, where [`Selection::estimated_error`] falls only with the
    /// worst one; what the time-budgeted selection minimises.
    pub estimated_rms_error: f64,
    /// Nodes left out as fully transparent, or removed by the kept region
    /// ([`SelectOptions::region`]).
    pub skipped: usize,
    /// Set when the budget is below the coarsest representation (then the
    /// coarsest one is returned anyway) or the tolerance was not reached.
    pub warning: Option<String>,
}

pub(super) fn texels(lo: [usize; 3], hi: [usize; 3], stride: usize) -> [usize; 3] {
    [0, 1, 2].map(|a| (hi[a] - lo[a]).div_ceil(stride) + 1)
}

/// `bytes(n, p)` of a brick of `texels` (see the module documentation).
pub(super) fn brick_bytes(texels: [usize; 3], bytes_per_texel: usize, gradient_border: bool) -> usize {
    texels.iter().map(|&n| n + 2 * usize::from(gradient_border)).product::<usize>() * bytes_per_texel
}

/// Node `n` drawn at level `p`: `stride = 2^(L - k - p)`, `bytes(n, p)`, `e_p(n)`.
pub(super) fn make_brick(
    octree: &VolumeOctree,
    n: &NodeRef<'_>,
    p: usize,
    importance: f64,
    bytes_per_texel: usize,
    gradient_border: bool,
) -> Brick {
    let l = octree.layout().root_log2 as usize;
    let stride = 1usize << (l - n.level - p);
    let texels = texels(n.lo, n.hi, stride);
    Brick {
        node: n.id,
        level: n.level,
        p,
        lo: n.lo,
        hi: n.hi,
        stride,
        texels,
        bytes: brick_bytes(texels, bytes_per_texel, gradient_border),
        error: n.error(p),
        importance,
        point_count: 0,
        point_bytes: 0,
    }
}

/// A brick over the index box `[lo, hi]` sampled every `stride` cells, for
/// tests that make DrawLists by hand.
#[cfg(test)]
pub(crate) fn test_brick(node: u32, lo: [usize; 3], hi: [usize; 3], stride: usize) -> Brick {
    Brick {
        node: NodeId(node),
        level: 0,
        p: 0,
        lo,
        hi,
        stride,
        texels: texels(lo, hi, stride),
        bytes: 0,
        error: 0.0,
        importance: 1.0,
        point_count: 0,
        point_bytes: 0,
    }
}

/// The importance of a node's box `[lo, hi]` under a region of interest:
///
/// ```text
/// Imp(n) = 1                            inside the region of interest, or without one
///        = r / (r + dist(box(n), c) - r) = r / dist(box(n), c)   outside it
/// ```
pub fn importance(roi: Option<&Roi>, lo: [usize; 3], hi: [usize; 3]) -> f64 {
    let Some(roi) = roi else { return 1.0 };
    let d2: f64 = (0..3)
        .map(|a| {
            let c = roi.center[a];
            let d = if c < lo[a] as f64 {
                lo[a] as f64 - c
            } else if c > hi[a] as f64 {
                c - hi[a] as f64
            } else {
                0.0
            };
            d * d
        })
        .sum();
    let d = d2.sqrt();
    if d <= roi.radius {
        1.0
    } else {
        roi.radius / d
    }
}
