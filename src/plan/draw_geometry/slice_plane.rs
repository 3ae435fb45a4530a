//! The OpenGL mapper's vertices under the Slice blend mode
//! ([`crate::plan::slice`]): each drawn brick is the polygon where the plane
//! cuts its drawn box, [`append_slice_polygon`] of the plane
//! `{x : (x - o) . n = 0}` (the eye at the plane's origin, its normal as
//! the view direction, depth 0), ordered in the basis `view_basis(n, a)`
//! with `a` the axis along which `n` is smallest (never parallel to `n`).
//! Its fragments sample the brick's texture at their position (the shader's
//! `HO_SLICE` variant: the opacity not corrected). A brick the plane misses,
//! or not drawn, has no vertex; no brick is ray-marched.

use super::brick_geometry::{BrickGeometry, BrickSlabs, FLOATS_PER_VERTEX, UNBOUNDED};
use super::slice_polygon::{append_slice_polygon, view_basis};
use crate::plan::slice::SlicePlane;

/// The plane's polygon in every brick (see the module documentation), one
/// brick after the other; `point_up` the basis' up.
pub fn slice_plane_geometry(plane: &SlicePlane, bricks: &[BrickSlabs<'_>]) -> BrickGeometry {
    let n = plane.normal;
    let smallest = (0..3).min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap_or(0);
    let mut axis = [0.0; 3];
    axis[smallest] = 1.0;
    let basis = view_basis(n, axis);
    let mut out = BrickGeometry {
        point_up: basis.1.map(|v| v as f32),
        brick_first: Vec::with_capacity(bricks.len() + 1),
        ray_marched: vec![false; bricks.len()],
        ..BrickGeometry::default()
    };
    out.brick_first.push(0);
    let mut polygon = Vec::new();
    for (index, brick) in bricks.iter().enumerate() {
        polygon.clear();
        if brick.drawn {
            append_slice_polygon(&brick.bounds, plane.origin, n, basis, 0.0, &mut polygon);
        }
        for v in polygon.chunks_exact(3) {
            out.vertices.extend_from_slice(v);
            out.vertices.extend([0.0, 0.0, 0.0, -UNBOUNDED, UNBOUNDED, 0.0, 0.0, index as f32]);
        }
        out.brick_first.push(out.vertices.len() / FLOATS_PER_VERTEX);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::vec3::{cross, norm, sub};

    fn brick(bounds: [f64; 6], drawn: bool) -> BrickSlabs<'static> {
        BrickSlabs { slices: &[], bounds, drawn, batches: Vec::new(), buckets: Vec::new() }
    }

    /// An oblique plane through a cube: a polygon on the plane of the
    /// cross-section's area; a brick it misses and one not drawn: nothing.
    #[test]
    fn polygons_lie_on_the_plane_and_cover_the_section() {
        let plane = SlicePlane::new([1.0, 1.0, 1.0], [0.0, 1.0, 1.0]).unwrap();
        let bricks = [
            brick([0.0, 2.0, 0.0, 2.0, 0.0, 2.0], true),
            brick([0.0, 2.0, 3.0, 4.0, 3.0, 4.0], true),
            brick([0.0, 2.0, 0.0, 2.0, 0.0, 2.0], false),
        ];
        let g = slice_plane_geometry(&plane, &bricks);
        assert_eq!(g.brick_first.len(), 4);
        assert_eq!(g.ray_marched, vec![false; 3]);
        let count = g.brick_first[1] - g.brick_first[0];
        assert!(count >= 3 && count.is_multiple_of(3));
        assert_eq!(g.brick_first[2], g.brick_first[1], "the plane misses the second brick");
        assert_eq!(g.brick_first[3], g.brick_first[2], "the third is not drawn");
        let v: Vec<[f64; 3]> =
            g.vertices.chunks(FLOATS_PER_VERTEX).map(|c| [c[0] as f64, c[1] as f64, c[2] as f64]).collect();
        assert!(v.iter().all(|p| plane.distance(*p).abs() < 1e-6));
        assert!(g.vertices.chunks(FLOATS_PER_VERTEX).all(|c| c[8] == 0.0), "slice primitives");
        // y + z = 2 across the cube: a rectangle 2 wide and 2 sqrt 2 long.
        let area: f64 = v.chunks(3).map(|t| 0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])))).sum();
        assert!((area - 4.0 * 2f64.sqrt()).abs() < 1e-5, "{area}");
    }
}
