//! The reference caster under the Slice blend mode ([`crate::plan::slice`]):
//! the ray's point on the plane (in front of the eye, inside the volume's
//! closed box, before the opaque surface's first hit, kept by the region),
//! the full grid's trilinear value there, `(a c, a)` of the transfer
//! function, the opacity not corrected, the colour shaded at the full grid's
//! gradient with a lighting; the opaque surface goes under it. Translucent
//! surfaces are drawn in Composite only.

use super::Caster;
use crate::data::grid::{Sample, TypedGrid};
use crate::geometry::camera::Ray;
use crate::render::blend::{under, Rgba};
use crate::render::sample::{grid_value, to_index};
use crate::render::shade::{gradient, normal};
use crate::render::triangles::Hit;

impl Caster<'_> {
    /// The pixel of `ray` under the Slice mode; `first` is the surface's
    /// first hit (opaque surfaces only hide the plane behind them).
    pub(super) fn slice<T: Sample>(&self, g: &TypedGrid<'_, T>, ray: &Ray, first: Option<&Hit>) -> [f32; 4] {
        let opaque = self.surface.filter(|s| s.2[3] >= 1.0).and(first);
        let limit = opaque.map_or(f64::INFINITY, |h| h.t);
        let mut acc: Rgba = self.slice_sample(g, ray, limit).map_or([0.0; 4], |(c, a)| under([0.0; 4], c, a));
        if let (Some((surface, tris, colour)), Some(h)) = (self.surface, opaque) {
            acc = under(acc, tris.shade(surface, h, ray.direction, *colour), colour[3] as f64);
        }
        acc.map(|v| v as f32)
    }

    /// The straight colour and opacity of the plane's point on `ray` before
    /// parameter `limit`, if it shows.
    fn slice_sample<T: Sample>(&self, g: &TypedGrid<'_, T>, ray: &Ray, limit: f64) -> Option<([f64; 3], f64)> {
        let plane = self.blend.slice.as_ref()?;
        let t = plane.ray_parameter(ray.origin, ray.direction).filter(|&t| t >= 0.0 && t < limit)?;
        let p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]);
        let (lo, hi) = (self.shape.world([0.0; 3]), self.shape.world(self.shape.dims.map(|d| (d - 1) as f64)));
        if !(0..3).all(|a| lo[a] <= p[a] && p[a] <= hi[a]) || self.region.is_some_and(|r| !r.keeps(p)) {
            return None;
        }
        let u = to_index(&self.shape, p);
        let [r, gr, b, a] = self.tf.eval(grid_value(g, u)).map(f64::from);
        if a.is_nan() || a <= 0.0 {
            return None;
        }
        let c = [r, gr, b];
        let rgb = match self.lighting {
            Some(lighting) => {
                lighting.shade(c, normal(gradient(|v| grid_value(g, v), u, self.shape.spacing)), ray.direction)
            }
            None => c,
        };
        Some((rgb, a))
    }
}
