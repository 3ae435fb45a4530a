//! The compositor under the blend modes besides Composite (see
//! [`crate::plan::blend`]): each brick's samples, on the same slice
//! lattice and in the same boxes as Composite's (the run of
//! [`BrickDraw::slices`](crate::plan::BrickDraw::slices) whose `p(z)` lies
//! in the brick's half-open box, in front of the opaque surface), feed one
//! [`Reduction`] per pixel with weight `w = d / d0`; bricks in any order,
//! no early termination. The opaque surface goes under the result, as
//! VTK blends its ray-cast image over the geometry. Samples the list's
//! region removes are not fed. Jittered, a brick's samples are its
//! jittered depths (`super::jitter`). Translucent surface
//! batches and points are drawn in Composite only.

use super::{Executor, PixelRay, Scratch};
use crate::render::blend::{under, Rgba};
use crate::render::geometry::ray_box;
use crate::render::intensity::Reduction;
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
                let jitter = self.jitter.map(|p| self.jitter_offset(b, x, y, p));
                self.reduce_brick(b, pr, jitter, &mut reduction, &lookup);
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

    /// Feeds brick `b`'s samples along `pr` to `reduction`: the slices, or
    /// with a jitter offset `o` the depths `k d + o` (`super::jitter`).
    fn reduce_brick(
        &self,
        b: usize,
        pr: &PixelRay,
        jitter: Option<f64>,
        reduction: &mut Reduction,
        lookup: &impl Fn(f64) -> [f64; 4],
    ) {
        let brick = &self.bricks[b];
        let Some((ta, tb)) = ray_box(&pr.ray, brick.draw.world_lo, brick.draw.world_hi) else { return };
        let (za, zb) = (pr.depth(ta), pr.depth(tb));
        let (ua, ub) = self.texel_line(brick, pr, za);
        let blend = &self.list.plan.blend;
        let mut feed = |z: f64| {
            if self.keeps(pr, z) {
                let dz = z - za;
                let v = brick.texture.at_texel([0, 1, 2].map(|k| ua[k] + dz * ub[k]));
                reduction.add(blend, v, brick.ratio, lookup);
            }
        };
        // The samples Composite's brick() (or brick_jittered()) takes.
        match jitter {
            None => {
                let (s0, s1) = brick.sampled_run(pr, za, zb);
                brick.draw.slices[s0..s1].iter().for_each(|&z| feed(z));
            }
            Some(o) => {
                let (k0, k1) = brick.jittered_run(pr, za, zb, o);
                let d = brick.draw.slice_spacing;
                (k0..k1).for_each(|k| feed(k as f64 * d + o));
            }
        }
    }
}
