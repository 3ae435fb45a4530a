//! The root's `hybrid_octree` attribute: what a store written here holds.

use serde::{Deserialize, Serialize};

/// The root attribute naming a store written here.
pub const ATTRIBUTE: &str = "hybrid_octree";

/// The `hybrid_octree` attribute: what the store's levels and octree are.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metadata {
    /// The layout's version: 1.
    pub format: u32,
    /// Samples per axis `(x, y, z)` of level 0.
    pub dims: [usize; 3],
    /// Cells per axis of a leaf brick.
    pub leaf_size: usize,
    /// The samples' type (`u8`, `u16`, `f32`, ...).
    pub scalar_type: String,
    /// NaN samples (no data) at level 0.
    pub nan_count: usize,
    /// Smallest and largest finite sample.
    pub value_range: (f64, f64),
    /// Resolution levels: strides `1 .. 2^(levels - 1)`.
    pub levels: usize,
    /// The image's name.
    pub name: String,
}
