//! Jittering (VTK's `vtkGPUVolumeRayCastMapper::UseJittering`): each pixel's
//! samples are moved along its ray by a fixed fraction of the sample
//! spacing, so that a coarse brick's sparse lattice shows fine noise instead
//! of wood-grain rings.
//!
//! VTK offsets each ray's start by `jitter * step` along the ray, `jitter`
//! read from a random noise texture at the fragment. Here the offset is a
//! view depth `o` per pixel, the same in every brick, and each brick of
//! slice spacing `d` samples the depths
//!
//! ```text
//! z = k d + (o mod d),   o = n(x, y) P,   k an integer
//! ```
//!
//! `P` ([`period`]) the largest slice spacing of the DrawList and `n(x, y)`
//! in `[0, 1)` the pixel's noise ([`noise`], `(x, y)` from the picture's
//! top left). Spacings are `d0` times powers of two, so `P / d` is a whole
//! number: the lattices `k d + (o mod d)` of all bricks are sublattices of
//! the finest one along the ray, as without jitter (no seam where bricks of
//! different strides meet), and `o mod d = frac(n P / d) d` covers `[0, d)`
//! for every brick. The noise is a fixed integer hash, not a random
//! texture: the CPU compositor and the OpenGL mapper compute the same bits
//! (24-bit fractions, exact in `f32`), and a picture is reproducible.
//!
//! The planner runs it only when asked, for a volume drawn in a blend mode
//! that samples along rays (not Slice), and only when no brick interleaves
//! a translucent surface's batches or points between its slices (those
//! bricks are drawn as slices, ordered against what lies between them):
//! [`Plan::jitter`], effect [`EFFECT`], last of [`Plan::effects`]. Without
//! it no noise is computed and every sample lies on the slice lattice.

use super::draw_list::{effects, DrawList, Plan, JITTER_EFFECT};
use super::BlendMode;

/// The effect's name in [`Plan::effects`].
pub const EFFECT: &str = JITTER_EFFECT;

/// One round of the `lowbias32` integer hash (Wellons' constants).
#[inline]
fn hash(mut v: u32) -> u32 {
    v ^= v >> 16;
    v = v.wrapping_mul(0x7feb_352d);
    v ^= v >> 15;
    v = v.wrapping_mul(0x846c_a68b);
    v ^= v >> 16;
    v
}

/// The noise of pixel `(x, y)` (from the top left), in `[0, 1)`:
/// `n = (h(x xor h(y)) >> 8) / 2^24`, `h` the `lowbias32` hash, 24 bits
/// (exact in `f32`, as the shader computes it).
#[inline]
pub fn noise(x: usize, y: usize) -> f64 {
    let h = hash((x as u32) ^ hash(y as u32));
    f64::from(h >> 8) / f64::from(1u32 << 24)
}

/// The jitter period `P`: the largest slice spacing of the list's bricks (0 without bricks).
pub fn period(list: &DrawList) -> f64 {
    list.bricks.iter().map(|b| b.slice_spacing).fold(0.0, f64::max)
}

/// The offset `o mod d = frac(n P / d) d` of a brick of slice spacing `d`
/// for a pixel of noise `n` (see the module documentation); 0 for a spacing
/// that is not positive.
#[inline]
pub fn offset(n: f64, period: f64, d: f64) -> f64 {
    if d > 0.0 {
        (n * (period / d)).fract() * d
    } else {
        0.0
    }
}

/// Whether a plan jitters: asked (`asked`), a volume drawn in a blend mode
/// that samples along rays, and no brick with batches or points between
/// its slices.
pub fn plans_jitter(list: &DrawList, asked: bool) -> bool {
    asked
        && list.plan.volume
        && list.plan.blend.mode != BlendMode::Slice
        && list.bricks.iter().all(|b| b.batches.is_empty() && b.points.is_empty())
}

/// `list` planned with or without jitter (`asked`: the scene's
/// `UseJittering`): [`Plan::jitter`] and [`Plan::effects`] set, or cleared.
/// Call it last, after the points are bucketed.
pub fn plan_jitter(mut list: DrawList, asked: bool) -> DrawList {
    list.plan.jitter = plans_jitter(&list, asked);
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}

/// Whether `plan` runs an effect besides jittering.
pub fn other_effects(plan: &Plan) -> bool {
    plan.effects.iter().any(|e| e != EFFECT)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_a_fixed_fraction_spread_over_the_unit_interval() {
        // Fixed bits: the shader's values.
        assert_eq!(noise(0, 0), noise(0, 0));
        let mut bins = [0usize; 16];
        for y in 0..64 {
            for x in 0..64 {
                let n = noise(x, y);
                assert!((0.0..1.0).contains(&n));
                assert_eq!(n, f64::from(n as f32), "24 bits, exact in f32");
                bins[(n * 16.0) as usize] += 1;
            }
        }
        // 4096 draws in 16 bins: each within 30 % of 256.
        assert!(bins.iter().all(|&b| (180..=332).contains(&b)), "{bins:?}");
        assert_ne!(noise(1, 0), noise(0, 1));
    }

    #[test]
    fn offsets_keep_the_lattices_nested() {
        let (d0, p) = (0.5, 4.0);
        for &n in &[0.0, 0.1234, 0.5, 0.999] {
            let o = offset(n, p, d0);
            assert!((0.0..d0).contains(&o));
            // A coarser brick's lattice is a subset of the finest one.
            for d in [1.0, 2.0, 4.0] {
                let od = offset(n, p, d);
                assert!((0.0..d).contains(&od));
                let k = (od - o) / d0;
                assert!((k - k.round()).abs() < 1e-9, "n {n} d {d}: {od} vs {o}");
            }
        }
    }
}
