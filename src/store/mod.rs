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

pub mod brick_loader;
pub mod metadata;
pub mod ngff;
pub mod octree_arrays;
pub mod open;
pub mod pyramid;
pub mod stream_write;
pub mod subchunks;
pub mod write;
mod zarr;

pub use open::Store;
pub use stream_write::{write_store_streaming, StreamWritten};
pub use write::{write_store, WriteOptions, WriteSummary};

pub use metadata::{Metadata, ATTRIBUTE};

#[cfg(test)]
mod brick_loader_tests;
#[cfg(test)]
mod stream_tests;
#[cfg(test)]
mod tests;
