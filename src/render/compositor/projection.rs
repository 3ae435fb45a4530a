//! The compositor under the blend modes besides Composite (see
//! [`crate::plan::blend`]): each brick's samples, on the same slice
//! lattice and in the same boxes as Composite's (the run of
//! [`BrickDraw::slices`](crate::plan::BrickDraw::slices) whose `p(z)` lies
//! in the brick's half-open box, in front of the opaque surface), feed one
//! [`Reduction`] per pixel with weight `w = d / d0`; bricks in any order,
//! no early termination. The opaque surface goes under the result, as
//! VTK blends its ray-cast image over the geometry. Samples the list's
//! region removes are not fed. Translucent surface
//! batches and points are drawn in Composite only.

use super::{Executor, PixelRay, Scratch};
use crate::render::blend::{under, Rgba};
use crate::render::geometry::{at_depth, ray_box};
use crate::render::intensity::Reduction;
use crate::render::sample::to_index;
use crate::render::texture::Texel;

impl<S: Texel> Executor<'_, S> {
    /// The pixel of `pr` under the list's blend mode, `surface_hit` (shaded
    /// colour, opacity) under it.
    pub(super) fn project(
        &self,
        x: usize,
        y: usize,
        pr: &PixelRay,
        scratch: &Scratch,
        surface_hit: Option<([f64; 3], f64)>,
    ) -> [f32; 4] {
        let blend = &self.list.plan.blend;
        let lookup = |v: f64| self.lut.eval(v);
        let mut reduction = Reduction::new();
        for &b in &scratch.row {
            let rect = self.bricks[b].rect;
            if (rect[0]..rect[1]).contains(&x) && (rect[2]..rect[3]).contains(&y) {
                self.reduce_brick(b, pr, &mut reduction, &lookup);
            }
        }
        let volume_lo = self.shape.world([0.0; 3]);
        let volume_hi = self.shape.world(self.shape.dims.map(|d| (d - 1) as f64));
        let crossed = ray_box(&pr.ray, volume_lo, volume_hi).is_some_and(|(t0, _)| pr.depth(t0) < pr.limit);
        let mut acc: Rgba = reduction.resolve(blend, crossed, lookup);
        if let Some((rgb, a)) = surface_hit {
            acc = under(acc, rgb, a);
        }
        acc.map(|v| v as f32)
    }

    /// Feeds brick `b`'s samples along `pr` to `reduction`.
    fn reduce_brick(&self, b: usize, pr: &PixelRay, reduction: &mut Reduction, lookup: &impl Fn(f64) -> [f64; 4]) {
        let brick = &self.bricks[b];
        let Some((ta, tb)) = ray_box(&pr.ray, brick.draw.world_lo, brick.draw.world_hi) else { return };
        let (za, zb) = (pr.depth(ta), pr.depth(tb));
        let slices = &brick.draw.slices;
        // The slices Composite's brick() samples.
        let (s0, s1) = brick.sampled_run(pr, za, zb);
        if s0 == s1 {
            return;
        }
        let spacing = self.shape.spacing;
        let (ua, ub) = brick.texture.texel_line(
            to_index(&self.shape, at_depth(&pr.ray, pr.z_origin, pr.cos, za)),
            [0, 1, 2].map(|a| pr.ray.direction[a] / (spacing[a] * pr.cos)),
        );
        let blend = &self.list.plan.blend;
        for &z in slices[s0..s1].iter().filter(|&&z| self.keeps(pr, z)) {
            let dz = z - za;
            let v = brick.texture.at_texel([0, 1, 2].map(|k| ua[k] + dz * ub[k]));
            reduction.add(blend, v, brick.ratio, lookup);
        }
    }
}
