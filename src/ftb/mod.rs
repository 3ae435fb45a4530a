//! Front-to-back display of a binary octree with blocking quadtrees (paper 2:
//! Zhao and Davis, "Fast Display of Octree Representations of 3D Objects"),
//! against Meagher's back-to-front display.
//!
//! A binary object (the inside of an isovalue, or one label of a label
//! volume) is encoded as an octree of white (W), black (B) and gray (G)
//! octants ([`binary_octree`]). For a view plane normal (VPN), [`view`] fixes
//! the octant order, the potentially visible faces and the parallel
//! projection; [`raster`] scan-converts octant faces into a z-buffer with
//! exact fixed-point edge stepping, so two displays of the same faces give
//! bit-identical depth images. [`back_to_front`] paints every potentially visible face
//! of every black octant back to front; [`front_to_back`] traverses front to back and
//! skips blocked octants (with their subtrees) and blocked faces, the test
//! being array indexing in the three blocking bitmaps of [`bitmap`].
//! [`shade`] turns a depth image into a shaded picture.

pub mod back_to_front;
pub mod binary_octree;
pub mod bitmap;
pub mod display;
pub mod front_to_back;
pub mod raster;
pub mod shade;
pub mod view;

pub use binary_octree::{BinaryOctree, Colour, Inside, OctantCounts};
pub use display::Display;
pub use raster::{Counters, DepthImage};
pub use view::{View, ViewCase};
