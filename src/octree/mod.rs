//! The Volume Octree (paper 1, section 2.1): min/max and the nodal error list
//! of every node, over a grid padded virtually to a power of two.
//!
//! One operation per file: [`layout`] fixes levels and node boxes,
//! [`trilinear`] defines T_p, [`leaf_stats`] is the per-brick kernel
//! ([`finite_brick`] its fast path for bricks with no NaN),
//! [`build`] runs it in parallel and reduces up the tree, [`cut`] walks the
//! tree, [`validate`] checks a built tree, [`brute_force`] is the slow reference
//! the tests compare against.

pub mod brute_force;
pub mod build;
pub mod cut;
pub mod dependent;
pub mod finite_brick;
pub mod layout;
pub mod leaf_stats;
pub mod rgba;
pub mod trilinear;
pub mod validate;
pub mod volume_octree;

pub use build::{BuildOptions, DEFAULT_LEAF_SIZE};
pub use dependent::DependentOctree;
pub use layout::{Layout, NodeId};
pub use leaf_stats::KernelPath;
pub use rgba::RgbaOctree;
pub use volume_octree::{NodeRef, OctreeStats, VolumeOctree};
