//! The reference caster under the blend modes besides Composite (see
//! [`crate::plan::blend`]): the ray's midpoint samples of the volume's box
//! (segment length `l`, weight `w = l / d0`) in front of the opaque surface
//! feed one [`Reduction`]; the opaque surface goes under the result.
//! Translucent surfaces are drawn in Composite only.

use super::Caster;
use crate::data::grid::{Sample, TypedGrid};
use crate::geometry::camera::Ray;
use crate::render::blend::under;
use crate::render::geometry::ray_box;
use crate::render::intensity::Reduction;
use crate::render::sample::{grid_value, to_index};
use crate::render::triangles::Hit;

impl Caster<'_> {
    /// The pixel of `ray` under the caster's blend mode; `first` is the
    /// surface's first hit (opaque surfaces only end the ray).
    pub(super) fn project<T: Sample>(&self, g: &TypedGrid<'_, T>, ray: &Ray, first: Option<&Hit>) -> [f32; 4] {
        let lookup = |v: f64| self.tf.eval(v).map(|c| c as f64);
        let opaque = self.surface.filter(|s| s.2[3] >= 1.0).and(first);
        let limit = opaque.map_or(f64::INFINITY, |h| h.t);
        let mut reduction = Reduction::new();
        let (lo, hi) = (self.shape.world([0.0; 3]), self.shape.world(self.shape.dims.map(|d| (d - 1) as f64)));
        let mut crossed = false;
        if let Some((t0, t1)) = ray_box(ray, lo, hi) {
            crossed = t0 < limit;
            let n = ((t1 - t0) / self.step).ceil().max(1.0) as usize;
            let l = (t1 - t0) / n as f64;
            for i in 0..n {
                let t = t0 + (i as f64 + 0.5) * l;
                if t > limit {
                    break;
                }
                let p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]);
                if self.region.is_some_and(|r| !r.keeps(p)) {
                    continue;
                }
                reduction.add(&self.blend, grid_value(g, to_index(&self.shape, p)), l / self.d0, lookup);
            }
        }
        let mut acc = reduction.resolve(&self.blend, crossed, lookup);
        if let (Some((surface, tris, colour)), Some(h)) = (self.surface, opaque) {
            acc = under(acc, tris.shade(surface, h, ray.direction, *colour), colour[3] as f64);
        }
        acc.map(|v| v as f32)
    }
}
