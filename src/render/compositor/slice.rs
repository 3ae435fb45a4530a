//! The compositor under the Slice blend mode ([`crate::plan::slice`]): a
//! pixel's ray meets the plane at `p` (in front of the eye, inside the
//! volume's closed box, in front of the opaque surface, kept by the list's
//! region); the brick whose box holds `p` (each point in exactly one, by the
//! near-face rule of Composite) gives the value `v = T_p(p)` on its texture,
//! and the pixel is `(a c, a)` of the transfer function at `v`, the opacity
//! not corrected, the colour shaded at the texture's gradient when the list
//! shades. No brick holds `p` where the selection left the node out (the
//! transfer function hides its values): nothing. The opaque surface goes
//! under it; translucent surfaces and points are drawn in Composite only.

use super::{Executor, PixelRay, Scratch};
use crate::render::blend::{under, Rgba};
use crate::render::sample::to_index;
use crate::render::texture::Texel;

impl<S: Texel> Executor<'_, S> {
    /// The pixel of `pr` under the Slice mode, `surface_hit` (shaded colour,
    /// opacity) under it.
    pub(super) fn slice_pixel(
        &self,
        x: usize,
        y: usize,
        pr: &PixelRay,
        scratch: &mut Scratch,
        surface_hit: Option<([f64; 3], f64)>,
    ) -> [f32; 4] {
        let mut acc: Rgba = self.slice_sample(x, y, pr, scratch).map_or([0.0; 4], |(c, a)| under([0.0; 4], c, a));
        if let Some((rgb, a)) = surface_hit {
            acc = under(acc, rgb, a);
        }
        acc.map(|v| v as f32)
    }

    /// The straight colour and opacity of the plane's point on `pr`, if it shows.
    fn slice_sample(&self, x: usize, y: usize, pr: &PixelRay, scratch: &mut Scratch) -> Option<([f64; 3], f64)> {
        let plane = self.list.plan.blend.slice.as_ref()?;
        let ray = &pr.ray;
        let t = plane.ray_parameter(ray.origin, ray.direction).filter(|&t| t >= 0.0)?;
        let p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]);
        let (lo, hi) = (self.shape.world([0.0; 3]), self.shape.world(self.shape.dims.map(|d| (d - 1) as f64)));
        let inside = (0..3).all(|a| lo[a] <= p[a] && p[a] <= hi[a]);
        if !inside || pr.depth(t) >= pr.limit || self.region.is_some_and(|r| !r.keeps(p)) {
            return None;
        }
        let brick = scratch.row.iter().map(|&b| &self.bricks[b]).find(|b| {
            let rect = b.rect;
            (rect[0]..rect[1]).contains(&x) && (rect[2]..rect[3]).contains(&y) && b.contains(p)
        })?;
        let at = brick.texture.point(brick.texture.texel_line(to_index(&self.shape, p), [0.0; 3]).0);
        let v = brick.texture.value_at(&at);
        let [r, g, b, a] = self.lut.eval(v);
        if a.is_nan() || a <= 0.0 {
            return None;
        }
        let (rgb, a) = self.effects(brick, &at, None, [r, g, b], a, ray.direction, scratch);
        (a > 0.0).then_some((rgb, a))
    }
}
