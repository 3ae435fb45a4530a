//! A camera in world coordinates, as VTK's vtkCamera describes one: position,
//! focal point, view up, and a parallel or perspective projection.
//!
//! The view basis is right-handed and orthonormal: `forward` points from the
//! position to the focal point, `up` is `view_up` made orthogonal to it,
//! `right = forward x up`. The view depth of a point is
//! `depth(p) = (p - position) . forward`. Pixel `(x, y)` of a `w x h` image
//! (x to the right, y down, centres at half-integers) looks along
//!
//! ```text
//! parallel:     origin = position + u s right + v s up,  direction = forward
//! perspective:  origin = position,  direction = normalise(forward + u t right + v t up)
//! u = (2 (x + 0.5) - w) / h,  v = (h - 2 (y + 0.5)) / h
//! ```
//!
//! with `s` the parallel scale (half the view height in world units) and
//! `t = tan(view angle / 2)`.

use crate::base::error::{Error, Result};
use crate::geometry::vec3::{cross, dot, norm, normalize, sub};

/// How the camera projects.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum Projection {
    /// Orthographic, `scale` = half the view height in world units.
    Parallel {
        /// Half the view height in world units.
        scale: f64,
    },
    /// Perspective, full vertical view angle in degrees (VTK's default is 30).
    Perspective {
        /// Vertical view angle, degrees.
        view_angle_deg: f64,
    },
}

/// A camera (see the module documentation for the formulas).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Camera {
    /// Eye position.
    pub position: [f64; 3],
    /// The point looked at.
    pub focal_point: [f64; 3],
    /// Up direction (need not be orthogonal to the view direction).
    pub view_up: [f64; 3],
    /// Parallel or perspective.
    pub projection: Projection,
}

/// A ray: `origin + t direction`, `direction` unit length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Start.
    pub origin: [f64; 3],
    /// Unit direction.
    pub direction: [f64; 3],
}

impl Camera {
    /// A checked camera: finite values, position != focal point, view up not
    /// parallel to the view direction, a positive scale or an angle in (0, 180).
    pub fn new(position: [f64; 3], focal_point: [f64; 3], view_up: [f64; 3], projection: Projection) -> Result<Camera> {
        let bad = |what: &str| Err(Error::InvalidArgument(format!("camera: {what}")));
        if position.iter().chain(&focal_point).chain(&view_up).any(|v| !v.is_finite()) {
            return bad("position, focal point and view up must be finite numbers");
        }
        let d = sub(focal_point, position);
        if d.iter().all(|&v| v == 0.0) || !norm(d).is_finite() {
            return bad("the position equals the focal point: move the camera away from the point it looks at");
        }
        // On unit vectors: a scene of 1e-300 or 1e300 world units is checked like one of 1.
        let c = cross(normalize(d), normalize(view_up));
        let across = dot(c, c);
        if view_up.iter().all(|&v| v == 0.0) || across.is_nan() || across <= 1e-24 {
            return bad("view up is zero or parallel to the view direction: choose an up vector across the view");
        }
        match projection {
            Projection::Parallel { scale } if !(scale > 0.0 && scale.is_finite()) => {
                return bad("the parallel scale must be a positive number")
            }
            Projection::Perspective { view_angle_deg } if !(view_angle_deg > 0.0 && view_angle_deg < 180.0) => {
                return bad("the view angle must be between 0 and 180 degrees")
            }
            _ => {}
        }
        Ok(Camera { position, focal_point, view_up, projection })
    }

    /// A camera looking at the centre of the box `[lo, hi]` (world) from
    /// `azimuth` degrees about +z (0: from -y) and `elevation` degrees above
    /// the xy plane, far enough that the whole box is in view.
    pub fn around(lo: [f64; 3], hi: [f64; 3], azimuth_deg: f64, elevation_deg: f64, parallel: bool) -> Result<Camera> {
        let centre = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
        let radius = 0.5 * norm(sub(hi, lo));
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let dir = [az.sin() * el.cos(), -az.cos() * el.cos(), el.sin()];
        let angle = 30.0f64;
        let distance = radius / (angle.to_radians() / 2.0).sin() * 1.05;
        let position = [0, 1, 2].map(|a| centre[a] + distance * dir[a]);
        let up = if el.cos().abs() < 1e-6 { [0.0, 1.0, 0.0] } else { [0.0, 0.0, 1.0] };
        let projection = if parallel {
            Projection::Parallel { scale: radius * 1.05 }
        } else {
            Projection::Perspective { view_angle_deg: angle }
        };
        Camera::new(position, centre, up, projection)
    }

    /// `(right, up, forward)`: the orthonormal view basis.
    pub fn basis(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let forward = normalize(sub(self.focal_point, self.position));
        let right = normalize(cross(forward, self.view_up));
        let up = cross(right, forward);
        (right, up, forward)
    }

    /// The unit view direction (position to focal point).
    pub fn forward(&self) -> [f64; 3] {
        self.basis().2
    }

    /// View depth of `p`: `(p - position) . forward`.
    pub fn depth(&self, p: [f64; 3]) -> f64 {
        dot(sub(p, self.position), self.forward())
    }

    /// True for a perspective camera.
    pub fn is_perspective(&self) -> bool {
        matches!(self.projection, Projection::Perspective { .. })
    }

    /// The ray through the centre of pixel `(x, y)` of a `width x height` image.
    pub fn ray(&self, x: usize, y: usize, width: usize, height: usize) -> Ray {
        let (right, up, forward) = self.basis();
        let h = height as f64;
        let u = (2.0 * (x as f64 + 0.5) - width as f64) / h;
        let v = (h - 2.0 * (y as f64 + 0.5)) / h;
        match self.projection {
            Projection::Parallel { scale } => Ray {
                origin: [0, 1, 2].map(|a| self.position[a] + u * scale * right[a] + v * scale * up[a]),
                direction: forward,
            },
            Projection::Perspective { view_angle_deg } => {
                let t = (view_angle_deg.to_radians() / 2.0).tan();
                Ray {
                    origin: self.position,
                    direction: normalize([0, 1, 2].map(|a| forward[a] + u * t * right[a] + v * t * up[a])),
                }
            }
        }
    }

    /// Where the box `[lo, hi]` falls on a `width x height` image: the
    /// smallest and largest `x` and `y` of its eight corners, `[x0, x1, y0,
    /// y1]`, in pixel units with pixel `(i, j)` centred at `(i + 1/2, j +
    /// 1/2)` (the inverse of [`Camera::ray`]'s `u = (2x - width) / height`,
    /// `v = (height - 2y) / height`, at the corner's depth for a perspective
    /// camera); `None` when a corner lies at or behind a perspective eye (or
    /// its depth is not a number), where the box can cover the whole image.
    pub fn box_on_screen(&self, width: usize, height: usize, lo: [f64; 3], hi: [f64; 3]) -> Option<[f64; 4]> {
        let (right, up, forward) = self.basis();
        let (w, h) = (width as f64, height as f64);
        let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for corner in 0..8 {
            let p = [0, 1, 2].map(|a| if corner >> a & 1 == 0 { lo[a] } else { hi[a] });
            let r = sub(p, self.position);
            let scale = match self.projection {
                Projection::Parallel { scale } => scale,
                Projection::Perspective { view_angle_deg } => {
                    let depth = dot(r, forward);
                    if depth.is_nan() || depth <= 1e-9 * dot(r, r).sqrt() {
                        return None;
                    }
                    depth * (view_angle_deg.to_radians() / 2.0).tan()
                }
            };
            let (u, v) = (dot(r, right) / scale, dot(r, up) / scale);
            let (px, py) = ((u * h + w) / 2.0, (h - v * h) / 2.0);
            b = [b[0].min(px), b[1].max(px), b[2].min(py), b[3].max(py)];
        }
        Some(b)
    }
}

/// A camera from `position` to `focal` with any up vector across the view
/// (the world axis least aligned with it): parallel with `scale`, or
/// perspective at 30 degrees. For tests that sweep view directions.
#[cfg(test)]
pub(crate) fn test_camera(position: [f64; 3], focal: [f64; 3], parallel_scale: Option<f64>) -> Camera {
    let d = sub(focal, position);
    let up = if d[0].abs() <= d[1].abs() && d[0].abs() <= d[2].abs() {
        [1.0, 0.0, 0.0]
    } else if d[1].abs() <= d[2].abs() {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let projection = match parallel_scale {
        Some(scale) => Projection::Parallel { scale },
        None => Projection::Perspective { view_angle_deg: 30.0 },
    };
    Camera::new(position, focal, up, projection).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_and_rays_point_forward() {
        let c =
            Camera::new([0.0, -10.0, 0.0], [0.0; 3], [0.0, 0.0, 1.0], Projection::Perspective { view_angle_deg: 30.0 })
                .unwrap();
        let (r, u, f) = c.basis();
        assert!((dot(r, u)).abs() < 1e-12 && dot(r, f).abs() < 1e-12 && dot(u, f).abs() < 1e-12);
        assert_eq!(f, [0.0, 1.0, 0.0]);
        assert_eq!(r, [1.0, 0.0, 0.0]);
        let centre = c.ray(50, 50, 101, 101);
        assert!((dot(centre.direction, f) - 1.0).abs() < 1e-12);
        assert!((c.depth([0.0, 5.0, 3.0]) - 15.0).abs() < 1e-12);
    }

    #[test]
    fn bad_cameras_are_refused() {
        let p = Projection::Parallel { scale: 1.0 };
        assert!(Camera::new([0.0; 3], [0.0; 3], [0.0, 0.0, 1.0], p).is_err());
        assert!(Camera::new([0.0; 3], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], p).is_err());
        assert!(Camera::new([0.0; 3], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], Projection::Parallel { scale: 0.0 }).is_err());
        assert!(Camera::new([f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], p).is_err());
    }

    #[test]
    fn boxes_fall_where_the_pixels_rays_meet_them() {
        for parallel in [Some(4.0), None] {
            let c = test_camera([0.0, -10.0, 0.0], [0.0; 3], parallel);
            // A point at the focal point: the image centre.
            let b = c.box_on_screen(200, 100, [0.0; 3], [0.0; 3]).unwrap();
            assert!(b.iter().zip([100.0, 100.0, 50.0, 50.0]).all(|(v, e)| (v - e).abs() < 1e-9), "{b:?}");
            // The ray through pixel (i, j) meets a point at (i + 1/2, j + 1/2).
            let ray = c.ray(30, 70, 200, 100);
            let t = 10.0 / ray.direction[1];
            let p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]);
            let b = c.box_on_screen(200, 100, p, p).unwrap();
            assert!((b[0] - 30.5).abs() < 1e-9 && (b[2] - 70.5).abs() < 1e-9, "{b:?}");
        }
        // A corner at or behind a perspective eye: anywhere on the image.
        let c = test_camera([0.0, -10.0, 0.0], [0.0; 3], None);
        assert_eq!(c.box_on_screen(200, 100, [-1.0, -12.0, -1.0], [1.0, 1.0, 1.0]), None);
    }
}
