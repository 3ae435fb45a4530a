//! The fan geometry of a planar polygon of a surface: its area vector,
//! which [`super::place`] turns into vertex normals and [`super::check`]
//! sums into areas.

use super::mesh::Surface;
use crate::geometry::vec3::{cross, sub};

/// Twice the area vector of a planar polygon in index space: the sum over its
/// fan triangles `(p0, pk, pk+1)` of `(pk - p0) x (pk+1 - p0)` (its length is
/// twice the area, its direction the outward normal).
pub fn polygon_normal(s: &Surface, polygon: &[u32]) -> [f64; 3] {
    let o = s.points[polygon[0] as usize];
    (1..polygon.len().saturating_sub(1)).fold([0.0; 3], |n, k| {
        let c = fan_cross(o, s.points[polygon[k] as usize], s.points[polygon[k + 1] as usize]);
        [n[0] + c[0], n[1] + c[1], n[2] + c[2]]
    })
}

/// `(a - o) x (b - o)`: twice the area vector of triangle `(o, a, b)`.
pub(super) fn fan_cross(o: [f64; 3], a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    cross(sub(a, o), sub(b, o))
}
