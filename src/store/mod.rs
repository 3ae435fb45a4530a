//! The Hybrid Octree on disk: OME-Zarr (NGFF 0.5, Zarr v3) images whose
//! resolution levels are the textures' exact strides and whose group holds
//! the Volume Octree, so that a volume larger than memory opens in time of
//! the octree's size and its bricks are read as the selection asks.
//!
//! ```text
//! image.ome.zarr/
//!   zarr.json          group: attributes "ome" (multiscales, axes z y x, scale and
//!                      translation per level) and "hybrid_octree" (Metadata)
//!   0/ 1/ .. P-1/      level p: samples min(i 2^p, n - 1) per axis (pyramid), sharded,
//!                      16^3 zstd subchunks
//!   hybrid_octree/     min, max (float64 per node), errors, squared_errors (float32)
//! ```

pub mod ngff;
pub mod octree_arrays;
pub mod open;
pub mod pyramid;
pub mod subchunks;
pub mod write;
mod zarr;

pub use open::Store;
pub use write::{write_store, WriteOptions, WriteSummary};

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

#[cfg(test)]
mod tests;
