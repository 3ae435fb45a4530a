//! The Volume Octree (paper 1, section 2.1): min/max and the nodal error list
//! of every node, over a grid padded virtually to a power of two.
//!
//! One operation per file: [`layout`] fixes levels and node boxes,
//! [`trilinear`] defines T_p, [`leaf_stats`] is the per-brick kernel
//! ([`finite_brick`] its fast path for bricks with no NaN),
//! [`build`] runs it in parallel and reduces up the tree, [`cut`] walks the
//! tree, [`validate`] checks a built tree, [`brute_force`] is the slow reference
//! the tests compare against. [`stream_build`] builds the same octree in one
//! pass over z from a plane source, holding a few planes ([`plane_stack`])
//! and reducing row by row ([`stream_reduce`]); the kernel reads either
//! through [`lattice`].

pub mod brute_force;
pub mod build;
pub mod cut;
pub mod dependent;
pub mod finite_brick;
pub mod lattice;
pub mod layout;
pub mod leaf_stats;
pub mod plane_stack;
pub mod rgba;
pub mod stream_build;
pub mod stream_reduce;
pub mod trilinear;
pub mod validate;
pub mod volume_octree;

pub use build::{BuildOptions, DEFAULT_LEAF_SIZE};
pub use dependent::DependentOctree;
pub use layout::{Layout, NodeId};
pub use leaf_stats::KernelPath;
pub use rgba::RgbaOctree;
pub use stream_build::Streamed;
pub use volume_octree::{NodeRef, OctreeStats, VolumeOctree};

#[cfg(test)]
mod stream_tests;
