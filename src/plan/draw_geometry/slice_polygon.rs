//! The polygon of a view-aligned slice inside a brick's box (paper 1,
//! section 3: each brick is drawn as the polygons of the view-aligned planes
//! through it, back to front), and the view basis it is ordered in.
//!
//! The plane of view depth `z` is `{x : (x - eye) . forward = z}`. With the
//! box's corners `c` (corner `k` at `x[k & 1], y[(k >> 1) & 1], z[(k >> 2) & 1]`)
//! at signed distances `d_c = (c - eye) . forward - z`, the plane meets the
//! box in
//!
//! ```text
//! the corners with d_c = 0, then per edge (a, b) with d_a, d_b of strict opposite signs
//! p = c_a + t (c_b - c_a),   t = d_a / (d_a - d_b)
//! ```
//!
//! The polygon is the convex hull of those points: ordered by angle
//! `atan2((p - m) . up, (p - m) . right)` around their centroid `m` (ties by
//! the order found), emitted as the triangle fan `(p_0, p_i, p_{i+1})`. Fewer
//! than three points (the plane misses the box or grazes an edge): nothing.
//! Exactly the arithmetic the OpenGL mapper used, in `f64`, the vertices
//! rounded to `f32` at the end.

use crate::geometry::vec3::{cross, dot};

/// The view basis of the slices: unit `right = forward x view_up /
/// |forward x view_up|` (0 when they are parallel) and `up = right x forward`.
pub fn view_basis(forward: [f64; 3], view_up: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let mut right = cross(forward, view_up);
    let norm = dot(right, right).sqrt();
    right = right.map(|v| if norm > 0.0 { v / norm } else { 0.0 });
    (right, cross(right, forward))
}

/// Box corner `k` of `bounds` (VTK order: xmin, xmax, ymin, ymax, zmin, zmax).
pub(crate) fn corner(bounds: &[f64; 6], k: usize) -> [f64; 3] {
    [bounds[k & 1], bounds[2 + ((k >> 1) & 1)], bounds[4 + ((k >> 2) & 1)]]
}

/// The box's 12 edges as corner pairs.
const EDGES: [[usize; 2]; 12] =
    [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]];

/// Appends the polygon of the plane `{x : (x - eye) . forward = depth}`
/// inside the box `bounds` (VTK order) to `out` as triangles, 3 floats a
/// vertex (see the module documentation; `right` and `up` from
/// [`view_basis`]). Returns the vertices appended: 0 when the plane meets
/// the box in fewer than 3 points.
pub fn append_slice_polygon(
    bounds: &[f64; 6],
    eye: [f64; 3],
    forward: [f64; 3],
    (right, up): ([f64; 3], [f64; 3]),
    depth: f64,
    out: &mut Vec<f32>,
) -> usize {
    let corners: [[f64; 3]; 8] = std::array::from_fn(|k| corner(bounds, k));
    let dist = corners.map(|c| dot([c[0] - eye[0], c[1] - eye[1], c[2] - eye[2]], forward) - depth);
    let mut points: Vec<[f64; 3]> = Vec::with_capacity(12);
    points.extend((0..8).filter(|&c| dist[c] == 0.0).map(|c| corners[c]));
    for [a, b] in EDGES {
        let (da, db) = (dist[a], dist[b]);
        if (da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0) {
            let t = da / (da - db);
            points.push([0, 1, 2].map(|k| corners[a][k] + t * (corners[b][k] - corners[a][k])));
        }
    }
    if points.len() < 3 {
        return 0;
    }
    let count = points.len() as f64;
    let mut centre = [0.0; 3];
    for p in &points {
        for k in 0..3 {
            centre[k] += p[k] / count;
        }
    }
    let mut order: Vec<(f64, usize)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let rel = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
            (dot(rel, up).atan2(dot(rel, right)), i)
        })
        .collect();
    order.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal).then(a.1.cmp(&b.1)));
    let mut added = 0;
    for i in 1..order.len() - 1 {
        for j in [order[0].1, order[i].1, order[i + 1].1] {
            out.extend(points[j].map(|v| v as f32));
            added += 1;
        }
    }
    added
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::vec3::{norm, sub};

    fn polygon(bounds: [f64; 6], eye: [f64; 3], forward: [f64; 3], depth: f64) -> Vec<[f64; 3]> {
        let basis = view_basis(forward, [0.0, 0.0, 1.0]);
        let basis = if norm(basis.0) > 0.0 { basis } else { view_basis(forward, [0.0, 1.0, 0.0]) };
        let mut out = Vec::new();
        let n = append_slice_polygon(&bounds, eye, forward, basis, depth, &mut out);
        assert_eq!(out.len(), 3 * n);
        out.chunks(3).map(|c| [c[0] as f64, c[1] as f64, c[2] as f64]).collect()
    }

    /// The area of a triangle list.
    fn area(v: &[[f64; 3]]) -> f64 {
        v.chunks(3).map(|t| 0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])))).sum()
    }

    #[test]
    fn the_view_basis_is_orthonormal_and_right_handed() {
        let (r, u) = view_basis([0.0, 0.0, -1.0], [0.0, 1.0, 0.0]);
        assert_eq!((r, u), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        let f = [0.6, 0.0, 0.8];
        let (r, u) = view_basis(f, [0.1, 1.0, 0.3]);
        assert!((norm(r) - 1.0).abs() < 1e-15 && (norm(u) - 1.0).abs() < 1e-15);
        assert!(dot(r, f).abs() < 1e-15 && dot(u, f).abs() < 1e-15 && dot(r, u).abs() < 1e-15);
        // Up on the viewer's up side.
        assert!(dot(u, [0.1, 1.0, 0.3]) > 0.0);
        // View up along the view: no right.
        assert_eq!(view_basis([0.0, 0.0, 1.0], [0.0, 0.0, 2.0]).0, [0.0; 3]);
    }

    #[test]
    fn an_axis_aligned_slice_is_the_face_rectangle() {
        // Looking along +z from z = -10: depth = z + 10.
        let b = [1.0, 3.0, 2.0, 7.0, 0.0, 4.0];
        let v = polygon(b, [2.0, 4.0, -10.0], [0.0, 0.0, 1.0], 12.5);
        assert_eq!(v.len(), 6, "a quadrilateral: two triangles");
        assert!(v.iter().all(|p| p[2] == 2.5));
        assert!((area(&v) - 2.0 * 5.0).abs() < 1e-12);
        // On a face (depth 10: z = 0): the 4 corners there.
        let face = polygon(b, [2.0, 4.0, -10.0], [0.0, 0.0, 1.0], 10.0);
        assert!((area(&face) - 10.0).abs() < 1e-12);
        // Outside: nothing.
        assert!(polygon(b, [2.0, 4.0, -10.0], [0.0, 0.0, 1.0], 9.0).is_empty());
        assert!(polygon(b, [2.0, 4.0, -10.0], [0.0, 0.0, 1.0], 14.5).is_empty());
    }

    #[test]
    fn a_diagonal_slice_through_the_centre_of_a_cube_is_a_regular_hexagon() {
        let s = 1.0 / 3f64.sqrt();
        let v = polygon([0.0, 1.0, 0.0, 1.0, 0.0, 1.0], [0.0; 3], [s, s, s], 1.5 * s);
        assert_eq!(v.len(), 3 * 4, "a hexagon: four fan triangles");
        // Side sqrt(2)/2: area 3 sqrt(3)/2 a^2.
        let a = 2f64.sqrt() / 2.0;
        assert!((area(&v) - 1.5 * 3f64.sqrt() * a * a).abs() < 1e-6);
        // Near a corner: a triangle.
        let t = polygon([0.0, 1.0, 0.0, 1.0, 0.0, 1.0], [0.0; 3], [s, s, s], 0.5 * s);
        assert_eq!(t.len(), 3);
        // Through a corner only: fewer than 3 points.
        assert!(polygon([0.0, 1.0, 0.0, 1.0, 0.0, 1.0], [0.0; 3], [s, s, s], 0.0).is_empty());
    }

    /// Brute force: the area of the plane inside the box, by sampling the
    /// plane on a fine grid in the (right, up) basis.
    #[test]
    fn the_fan_covers_the_plane_inside_the_box_in_any_view() {
        let b = [-1.0, 2.0, 0.5, 1.5, -3.0, 0.0];
        let mut seed = 7u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..40 {
            let f = crate::geometry::vec3::normalize([next() - 0.5, next() - 0.5, next() - 0.5]);
            let eye = [5.0 * next(), -4.0 * next(), 6.0 * next()];
            let depths: Vec<f64> = (0..8).map(|k| dot(sub(corner(&b, k), eye), f)).collect();
            let (lo, hi) = depths.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &d| (l.min(d), h.max(d)));
            let depth = lo + (hi - lo) * (0.05 + 0.9 * next());
            let (right, up) = view_basis(f, [0.0, 0.0, 1.0]);
            let mut out = Vec::new();
            append_slice_polygon(&b, eye, f, (right, up), depth, &mut out);
            let v: Vec<[f64; 3]> = out.chunks(3).map(|c| [c[0] as f64, c[1] as f64, c[2] as f64]).collect();
            // Every vertex on the plane and in the box.
            for p in &v {
                assert!((dot(sub(*p, eye), f) - depth).abs() < 1e-5);
                assert!((0..3).all(|a| b[2 * a] - 1e-5 <= p[a] && p[a] <= b[2 * a + 1] + 1e-5));
            }
            // Each fan triangle turns the same way (a convex polygon in order).
            let turns: Vec<f64> = v.chunks(3).map(|t| dot(cross(sub(t[1], t[0]), sub(t[2], t[0])), f)).collect();
            assert!(turns.iter().all(|&t| t >= -1e-9) || turns.iter().all(|&t| t <= 1e-9), "{turns:?}");
            // The area against a count of the plane's grid points inside the box.
            let centre = [0, 1, 2].map(|a| 0.5 * (b[2 * a] + b[2 * a + 1]));
            let off = dot(sub(centre, eye), f) - depth;
            let o = [0, 1, 2].map(|a| centre[a] - off * f[a]);
            let (n, h) = (400, 0.02);
            let mut inside = 0usize;
            for i in 0..n {
                for j in 0..n {
                    let (x, y) = ((i as f64 - n as f64 / 2.0 + 0.5) * h, (j as f64 - n as f64 / 2.0 + 0.5) * h);
                    let p = [0, 1, 2].map(|a| o[a] + x * right[a] + y * up[a]);
                    if (0..3).all(|a| b[2 * a] <= p[a] && p[a] <= b[2 * a + 1]) {
                        inside += 1;
                    }
                }
            }
            let expected = inside as f64 * h * h;
            assert!((area(&v) - expected).abs() < 0.05 * expected.max(0.1), "{} against {expected}", area(&v));
        }
    }
}
