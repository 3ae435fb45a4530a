//! The compositor's jittered samples ([`crate::plan::jitter`]): brick `b`
//! of slice spacing `d` samples pixel `(x, y)`'s ray at the depths
//!
//! ```text
//! z_k = k d + o_b,   o_b = frac(n(x, y) P / d) d   (crate::plan::jitter::offset)
//! ```
//!
//! whose point `p(z_k)` lies in the brick's half-open box (the rule of
//! `Prepared::contains`, as for slices) and in front of the opaque surface
//! (`z_k < limit`), front to back, each sample as an unjittered one. A brick
//! without slices draws nothing (the OpenGL mapper draws no box for it).
//! Only lists without batches or points jitter (the planner's rule), so no
//! event interleaves.

use super::{Executor, PixelRay, Prepared, Scratch, OPAQUE};
use crate::plan::jitter::{noise, offset};
use crate::render::blend::Rgba;
use crate::render::geometry::{at_depth, ray_box};
use crate::render::sample::to_index;
use crate::render::texture::Texel;

impl<S> Prepared<'_, S> {
    /// The run `k0..k1` (front to back) of lattice indices `k` whose depth
    /// `k d + o` is a sample of pixel ray `pr` in this brick, `za`, `zb`
    /// the depths where it enters and leaves the box.
    pub(super) fn jittered_run(&self, pr: &PixelRay, za: f64, zb: f64, o: f64) -> (i64, i64) {
        let d = self.draw.slice_spacing;
        if d.is_nan() || d <= 0.0 || self.draw.slices.is_empty() {
            return (0, 0);
        }
        let depth = |k: i64| k as f64 * d + o;
        let tol = 1e-9 * (1.0 + za.abs().max(zb.abs()));
        let mut k0 = ((za - tol - o) / d).floor() as i64;
        let mut k1 = ((zb + tol - o) / d).ceil() as i64 + 1;
        if pr.limit.is_finite() {
            k1 = k1.min(((pr.limit - o) / d).ceil() as i64 + 1);
        }
        while k1 > k0 && depth(k1 - 1) >= pr.limit {
            k1 -= 1;
        }
        let inside = |k: i64| self.contains(at_depth(&pr.ray, pr.z_origin, pr.cos, depth(k)));
        while k0 < k1 && !inside(k0) {
            k0 += 1;
        }
        while k1 > k0 && !inside(k1 - 1) {
            k1 -= 1;
        }
        (k0, k1)
    }
}

impl<S: Texel> Executor<'_, S> {
    /// The offset `o_b` of brick `b` for pixel `(x, y)` under period `period`.
    #[inline]
    pub(super) fn jitter_offset(&self, b: usize, x: usize, y: usize, period: f64) -> f64 {
        offset(noise(x, y), period, self.bricks[b].draw.slice_spacing)
    }

    /// Brick `b`'s jittered samples of pixel `(x, y)` blended under `acc`,
    /// front to back, stopping once `acc` is [`OPAQUE`] (`PLAIN` as in
    /// `Executor::brick`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn brick_jittered<const PLAIN: bool>(
        &self,
        b: usize,
        pr: &PixelRay,
        x: usize,
        y: usize,
        period: f64,
        mut acc: Rgba,
        scratch: &mut Scratch,
    ) -> Rgba {
        let brick = &self.bricks[b];
        let Some((ta, tb)) = ray_box(&pr.ray, brick.draw.world_lo, brick.draw.world_hi) else { return acc };
        let (za, zb) = (pr.depth(ta), pr.depth(tb));
        let o = self.jitter_offset(b, x, y, period);
        scratch.counts.jittered += 1;
        let (k0, k1) = brick.jittered_run(pr, za, zb, o);
        if k0 == k1 {
            return acc;
        }
        let line = self.texel_line(brick, pr, za);
        let d = brick.draw.slice_spacing;
        for k in k0..k1 {
            acc = self.sample_at_depth::<PLAIN>(brick, pr, k as f64 * d + o, za, line, acc, scratch);
            if acc[3] >= OPAQUE {
                break;
            }
        }
        acc
    }

    /// The texel line `(ua, ub)` of `pr` in `brick` from its entry depth `za`
    /// (the compositor's module documentation).
    #[inline]
    pub(super) fn texel_line(&self, brick: &Prepared<'_, S>, pr: &PixelRay, za: f64) -> ([f64; 3], [f64; 3]) {
        let spacing = self.shape.spacing;
        brick.texture.texel_line(
            to_index(&self.shape, at_depth(&pr.ray, pr.z_origin, pr.cos, za)),
            [0, 1, 2].map(|a| pr.ray.direction[a] / (spacing[a] * pr.cos)),
        )
    }
}
