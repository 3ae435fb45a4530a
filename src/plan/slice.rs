//! The Slice blend mode's plane (VTK 9.2's `SLICE_BLEND`; ParaView's *Blend
//! Mode* Slice with its *Slice Function*, a `vtkPlane` that
//! `vtkVolumeProperty::SetSliceFunction` holds).
//!
//! VTK's GPU ray caster (`vtkVolumeShaderComposer.h`: `intersectRayPlane`,
//! `TerminationInit`, `ShadingSingleInput`) draws, for each pixel whose ray
//! crosses the volume's box, the one sample where the ray meets the plane
//! `{x : n . (x - o) = 0}`:
//!
//! ```text
//! t = n . (o - e) / (n . d)          (no point when |n . d| <= 1e-6 |n| |d|: the ray runs along the plane)
//! p = e + t d,   v = F(p)            (trilinear; nothing when p is outside the volume's box)
//! pixel = (a(v) c'(v), a(v))         composited over what is behind, nothing behind opaque geometry
//! ```
//!
//! `a(v)` is the scalar opacity, not corrected for a sample spacing (one
//! sample stands for the ray), `c'(v)` the colour, shaded at `p` (the
//! gradient there, the ray direction as the view) when *Shade* is on, as
//! in Composite. A point cropping or a clipping plane removes draws nothing
//! (VTK's cropping skips the sample; its clipping shortens the ray but does
//! not test the plane's point, so VTK still draws a clipped-away point of a
//! ray that keeps some unclipped segment: here it is removed as a cropped
//! one is). Gradient opacity is not applied (VTK multiplies the alpha by it
//! but not the colour).
//!
//! The plane is in the volume's data coordinates (the octree's world frame,
//! origin and spacing considered): VTK takes the `vtkPlane`'s origin and
//! normal, world coordinates, into data coordinates with the inverse of the
//! volume's matrix (the normal as a direction), which the mapper does.
//!
//! The selection spends texture only on nodes whose box the plane cuts
//! ([`SlicePlane::cuts_box`]): every other node draws nothing.

use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::geometry::vec3::dot;

/// Below this `|n . d| / (|n| |d|)` a ray runs along the plane: it meets it
/// nowhere (VTK's `abs(denom) > 1e-6`, its ray direction normalised).
pub const PARALLEL: f64 = 1e-6;

/// The plane of the Slice blend mode: the points `x` with `n . (x - o) = 0`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlicePlane {
    /// A point of the plane.
    pub origin: [f64; 3],
    /// Its normal (any length above 0).
    pub normal: [f64; 3],
}

impl SlicePlane {
    /// The plane through `origin` of normal `normal`, checked ([`SlicePlane::check`]).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a number that is not finite or a zero normal.
    pub fn new(origin: [f64; 3], normal: [f64; 3]) -> Result<SlicePlane> {
        let plane = SlicePlane { origin, normal };
        plane.check()?;
        Ok(plane)
    }

    /// Finite origin and normal, the normal not 0 (nor so small that its
    /// square underflows).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] naming the bad value.
    pub fn check(&self) -> Result<()> {
        let (o, n) = (self.origin, self.normal);
        if o.iter().chain(&n).any(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "slice plane (origin {o:?}, normal {n:?}): give finite numbers"
            )));
        }
        let len2 = dot(n, n);
        if !(len2 > 0.0 && len2.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "slice plane normal {n:?}: give a non-zero direction (the Slice blend mode draws the volume where \
                 this plane cuts it)"
            )));
        }
        Ok(())
    }

    /// `n . (p - o)`: positive on the normal's side (not normalised).
    #[inline]
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        dot(self.normal, [p[0] - self.origin[0], p[1] - self.origin[1], p[2] - self.origin[2]])
    }

    /// Whether the plane meets the closed box `[lo, hi]`: its corners'
    /// distances are not all of one strict sign.
    pub fn cuts_box(&self, lo: [f64; 3], hi: [f64; 3]) -> bool {
        let (mut below, mut above) = (false, false);
        for k in 0..8 {
            let c = [0, 1, 2].map(|a| if k >> a & 1 == 0 { lo[a] } else { hi[a] });
            let d = self.distance(c);
            below |= d <= 0.0;
            above |= d >= 0.0;
        }
        below && above
    }

    /// The ray parameter `t` where `e + t d` meets the plane (module
    /// documentation), `None` when the ray runs along it.
    #[inline]
    pub fn ray_parameter(&self, e: [f64; 3], d: [f64; 3]) -> Option<f64> {
        let denom = dot(self.normal, d);
        let scale = (dot(self.normal, self.normal) * dot(d, d)).sqrt();
        (denom.abs() > PARALLEL * scale).then(|| -self.distance(e) / denom)
    }

    /// The same plane in the index space of `shape` (`x = origin + i spacing`):
    /// origin `(o - origin) / spacing`, normal `n spacing` (so that
    /// `n' . (i - o') = n . (x - o)`).
    pub fn to_index(&self, shape: &GridShape) -> SlicePlane {
        SlicePlane {
            origin: [0, 1, 2].map(|a| (self.origin[a] - shape.origin[a]) / shape.spacing[a]),
            normal: [0, 1, 2].map(|a| self.normal[a] * shape.spacing[a]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_planes_are_refused_with_the_reason() {
        let e = SlicePlane::new([0.0; 3], [0.0; 3]).unwrap_err().to_string();
        assert!(e.contains("non-zero"), "{e}");
        let e = SlicePlane::new([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("finite"), "{e}");
        assert!(SlicePlane::new([0.0; 3], [0.0, f64::INFINITY, 1.0]).is_err());
        assert!(SlicePlane::new([0.0; 3], [1e-200, 0.0, 0.0]).is_err(), "its square underflows");
        assert!(SlicePlane::new([1.0, 2.0, 3.0], [0.0, 0.0, 1e-3]).is_ok());
    }

    #[test]
    fn boxes_cut_touched_or_missed() {
        let p = SlicePlane::new([2.0, 0.0, 0.0], [1.0, 1.0, 0.0]).unwrap(); // x + y = 2
        assert!(p.cuts_box([0.0; 3], [2.0; 3]));
        assert!(p.cuts_box([1.0, 1.0, 0.0], [3.0, 3.0, 1.0]), "a corner on the plane");
        assert!(!p.cuts_box([1.5, 1.5, 0.0], [3.0, 3.0, 1.0]));
        assert!(!p.cuts_box([0.0; 3], [0.5, 0.5, 9.0]));
    }

    #[test]
    fn rays_meet_the_plane_or_run_along_it() {
        let p = SlicePlane::new([0.0, 0.0, 2.0], [0.0, 0.0, -3.0]).unwrap();
        assert_eq!(p.ray_parameter([1.0, 1.0, 10.0], [0.0, 0.0, -2.0]), Some(4.0));
        assert_eq!(p.ray_parameter([1.0, 1.0, 10.0], [1.0, 0.0, 0.0]), None);
        assert_eq!(p.ray_parameter([1.0, 1.0, 10.0], [1.0, 0.0, 1e-9]), None);
    }

    #[test]
    fn index_space_keeps_the_distance_sign_and_zero() {
        let shape = GridShape { dims: [9, 9, 9], spacing: [0.5, 2.0, 1.0], origin: [1.0, -1.0, 3.0] };
        let p = SlicePlane::new([2.0, 1.0, 4.0], [0.3, -0.7, 0.2]).unwrap();
        let q = p.to_index(&shape);
        for i in [[0.0, 0.0, 0.0], [2.0, 1.0, 1.0], [8.0, 3.0, 5.0]] {
            let x = shape.world(i);
            assert!((q.distance(i) - p.distance(x)).abs() < 1e-12);
        }
    }
}
