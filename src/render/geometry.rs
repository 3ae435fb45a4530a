//! Rays against boxes and slice planes, and the screen footprint of a box.
//!
//! ```text
//! ray-box (slabs):  t_a = (lo_a - o_a) / d_a, (hi_a - o_a) / d_a;  [max_a min(t_a), min_a max(t_a)] ∩ [0, inf)
//! slice point:      p(z) = o + d (z - depth(o)) / (d . forward)          (the ray at view depth z)
//! pixel of p:       x = (u h + w) / 2 - 1/2,  y = (h - v h) / 2 - 1/2
//!                   u = (p - position) . right / s,  v = (p - position) . up / s              parallel
//!                   u = (p - position) . right / (t depth(p)),  v = ... up / (t depth(p))    perspective
//! ```
//!
//! (the inverse of [`Camera::ray`]; `s` the parallel scale, `t = tan(angle / 2)`).

use crate::geometry::camera::{Camera, Ray};

/// The parameter interval `[t0, t1]`, `t0 >= 0`, of `ray` inside the closed
/// box `[lo, hi]`, or `None`.
pub(crate) fn ray_box(ray: &Ray, lo: [f64; 3], hi: [f64; 3]) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.direction[a]);
        if d == 0.0 {
            if o < lo[a] || o > hi[a] {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((lo[a] - o) / d, (hi[a] - o) / d);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// The point of `ray` at view depth `z`, given `z_origin = depth(origin)` and
/// `cos = direction . forward > 0`.
#[inline]
pub(crate) fn at_depth(ray: &Ray, z_origin: f64, cos: f64, z: f64) -> [f64; 3] {
    let t = (z - z_origin) / cos;
    [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a])
}

/// Pixels `[x0, x1) x [y0, y1)` of a `width x height` picture that may see
/// the box `[lo, hi]` (its corners' pixels, one pixel of margin); `None` when
/// off screen. A perspective camera inside or behind the box gets the whole picture.
pub(crate) fn screen_rect(
    camera: &Camera,
    width: usize,
    height: usize,
    lo: [f64; 3],
    hi: [f64; 3],
) -> Option<[usize; 4]> {
    let Some([x0, x1, y0, y1]) = camera.box_on_screen(width, height, lo, hi) else {
        return Some([0, width, 0, height]);
    };
    // The corners' pixels (centres at whole numbers), one pixel of margin.
    let (x, y) = ((x0 - 0.5, x1 - 0.5), (y0 - 0.5, y1 - 0.5));
    let clamp = |v: f64, n: usize| v.clamp(0.0, n as f64) as usize;
    let rect = [clamp(x.0.floor() - 1.0, width), clamp(x.1.ceil() + 2.0, width)];
    let rect = [rect[0], rect[1], clamp(y.0.floor() - 1.0, height), clamp(y.1.ceil() + 2.0, height)];
    (rect[0] < rect[1] && rect[2] < rect[3]).then_some(rect)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::vec3::dot;

    #[test]
    fn rays_clip_to_boxes() {
        let ray = Ray { origin: [-1.0, 0.5, 0.5], direction: [1.0, 0.0, 0.0] };
        assert_eq!(ray_box(&ray, [0.0; 3], [2.0; 3]), Some((1.0, 3.0)));
        assert_eq!(ray_box(&ray, [0.0, 1.0, 0.0], [2.0; 3]), None);
        let inside = Ray { origin: [1.0; 3], direction: [0.0, 0.0, -1.0] };
        assert_eq!(ray_box(&inside, [0.0; 3], [2.0; 3]), Some((0.0, 1.0)));
        let behind = Ray { origin: [3.0, 1.0, 1.0], direction: [1.0, 0.0, 0.0] };
        assert_eq!(ray_box(&behind, [0.0; 3], [2.0; 3]), None);
    }

    #[test]
    fn footprints_hold_every_ray_that_hits_the_box() {
        for parallel in [true, false] {
            let camera = Camera::around([0.0; 3], [10.0; 3], 35.0, 25.0, parallel).unwrap();
            let (lo, hi) = ([2.0, 3.0, 1.0], [5.0, 4.0, 7.0]);
            let (w, h) = (48, 32);
            let r = screen_rect(&camera, w, h, lo, hi).unwrap();
            let mut hits = 0;
            for y in 0..h {
                for x in 0..w {
                    if ray_box(&camera.ray(x, y, w, h), lo, hi).is_some() {
                        hits += 1;
                        assert!(r[0] <= x && x < r[1] && r[2] <= y && y < r[3], "{x} {y} outside {r:?}");
                    }
                }
            }
            assert!(hits > 10);
            // The slice point lies at the asked depth.
            let ray = camera.ray(7, 9, w, h);
            let cos = dot(ray.direction, camera.forward());
            let p = at_depth(&ray, camera.depth(ray.origin), cos, 12.5);
            assert!((camera.depth(p) - 12.5).abs() < 1e-9);
        }
    }
}
