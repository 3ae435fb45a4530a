//! The constant field `f(t) = 0.5`: every node is homogeneous, so the Volume
//! Octree is a single root node.

/// `f(t) = 0.5`.
pub fn value(_t: [f64; 3]) -> f64 {
    0.5
}
