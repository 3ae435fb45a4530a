//! The estimated error of a selection: how far its picture can be from the
//! full-resolution one, as the picture sees it: the largest error of a
//! visible brick ([`estimated_error`]), and the root-mean-square error of
//! the visible samples ([`estimated_rms_error`]; as drawn, its slices'
//! spacing and the transmittance in front of each brick counted:
//! [`seen_rms_error`]).
//!
//! ```text
//! estimate = max over drawn bricks b with visible(min_b, max_b) of E_(p_b)(b)
//! ```
//!
//! `E_p(b)` is the brick's nodal error at its level `p`: the largest
//! `|f(v) - T_s(v)|` over the samples `v` of its closed box, normalised by
//! the data range (the stored envelope, see [`crate::octree::build`]); `min_b`,
//! `max_b` its value range. So a brick contributes 0 when:
//!
//! - it is at full resolution (stride 1: `E_(L-k) = 0`);
//! - its coarse form is lossless (constant, or trilinear over its coarse
//!   cells, up to and including its faces: `E_p = 0`);
//! - the transfer function is transparent over its whole value range (a
//!   brick kept only for the isosurface it holds): its coarse values
//!   interpolate samples of that range, and draw nothing at any stride.
//!
//! Transparent nodes the selection dropped draw nothing at any resolution and
//! are not bricks. The estimate is 0 exactly when every visible brick draws
//! the full-resolution field; it is not weighted by the region of interest's
//! importance (the selection's tolerance is; see [`super::Selection::max_error`]),
//! and points of the hybrid representation are not counted (a brick that
//! took points reports its texture's error).

use super::Brick;
use crate::octree::VolumeOctree;

/// The estimated error of drawing `bricks` of `octree` (see the module
/// documentation); `visible(min, max)` is the selection's transfer-function
/// test.
pub fn estimated_error(octree: &VolumeOctree, bricks: &[Brick], visible: impl Fn(f64, f64) -> bool) -> f64 {
    bricks
        .iter()
        .filter(|b| b.error > 0.0)
        .filter(|b| {
            let n = octree.node(b.node);
            visible(n.min, n.max)
        })
        .map(|b| b.error as f64)
        .fold(0.0, f64::max)
}

/// The estimated root-mean-square error of drawing `bricks` of `octree`:
/// the visible bricks' squared errors summed over their samples, over the
/// count of those samples (each brick at its own stride, nothing in front
/// of it: [`seen_rms_error`] with `T = 1` and slices at the strides).
pub fn estimated_rms_error(octree: &VolumeOctree, bricks: &[Brick], visible: impl Fn(f64, f64) -> bool) -> f64 {
    seen_rms_error(octree, bricks.iter().map(|b| Seen::at_stride(b, 1.0)), visible)
}

/// A drawn brick as [`seen_rms_error`] reads it.
#[derive(Debug, Clone, Copy)]
pub struct Seen<'a> {
    /// The brick.
    pub brick: &'a Brick,
    /// The spacing of its slices in samples of the full-resolution grid
    /// (`slice spacing / d0`): its stride or less, unless the slices were
    /// widened to meet a frame time ([`crate::plan::cost::widen_slices`]).
    pub slice_stride: f64,
    /// `T_b`: the transmittance in front of it, from 0 (hidden) to 1
    /// ([`super::Transmittance`]; 1 without a visibility estimate).
    pub transmittance: f64,
}

impl<'a> Seen<'a> {
    /// `brick` sliced at its stride, behind transmittance `t`.
    pub fn at_stride(brick: &'a Brick, t: f64) -> Seen<'a> {
        Seen { brick, slice_stride: brick.stride as f64, transmittance: t }
    }
}

/// The estimated root-mean-square error of a picture drawing `drawn`
/// bricks of `octree`: each visible brick's squared error summed over its
/// samples, weighted by the transmittance in front of it, over the
/// weighted count of those samples,
///
/// ```text
/// estimate_rms = sqrt( sum_b T_b (Q'_b + n_b q_b^2 / 3) / sum_b T_b n_b )
///                over drawn bricks b with visible(min_b, max_b)
/// Q'_b         = Q_(p_b)(b)                               slices at the stride or finer
///              = max(Q_(p_b)(b), Q_(p'_b)(b) / 3)          slices m_b >= 2 strides apart
/// p'_b         = p_b - floor(log2 m_b)   (at least 0)
/// ```
///
/// `Q_p(b)` is the brick's squared error at its level, summed over the
/// `n_b` samples of its closed box and normalised by the squared data
/// range (the build's, see [`crate::octree::build`]); `q_b` the
/// quantization error its texel format adds (the brick's error envelope
/// less `E_p(b)`: the largest rounding error, whose mean square over
/// uniformly spread rounding is `q^2 / 3`).
///
/// Slices `m_b` strides apart sample the brick's field on a lattice that
/// coarse along the view alone: of the level whose stride is the slices'
/// (`p'_b`), one axis of three, so a third of its squared error, and
/// never less than the brick's own. `T_b` is how much of a sample reaches
/// its pixel: a brick behind opaque material adds little error to the
/// picture however coarse it is, and counts as few samples.
///
/// Where [`estimated_error`] says how wrong the worst visible sample can
/// be, this says how wrong the samples are on the whole: it falls with
/// every brick refined, not only when the worst one is, so it ranks
/// selections by the RMSE of their pictures where the largest error ties
/// (a field with detail everywhere keeps one coarse brick's maximum over a
/// wide range of budgets). 0 exactly when every visible, unhidden brick
/// draws the full-resolution field losslessly at slices no wider than its
/// texels; 0 with no such brick.
pub fn seen_rms_error<'a>(
    octree: &VolumeOctree,
    drawn: impl IntoIterator<Item = Seen<'a>>,
    visible: impl Fn(f64, f64) -> bool,
) -> f64 {
    let (mut squared, mut samples) = (0.0f64, 0.0f64);
    for Seen { brick: b, slice_stride, transmittance } in drawn {
        let n = octree.node(b.node);
        let t = if transmittance.is_finite() { transmittance.clamp(0.0, 1.0) } else { 1.0 };
        if !visible(n.min, n.max) || t == 0.0 {
            continue;
        }
        let count = (0..3).map(|a| (b.hi[a] - b.lo[a] + 1) as f64).product::<f64>();
        let q = (f64::from(b.error) - f64::from(n.error(b.p))).max(0.0);
        let mut field = f64::from(n.squared_error(b.p)).max(0.0);
        let widened = slice_stride / b.stride.max(1) as f64;
        if widened >= 2.0 && widened.is_finite() {
            let coarser = (widened.log2().floor() as usize).min(b.p);
            field = field.max(f64::from(n.squared_error(b.p - coarser)).max(0.0) / 3.0);
        }
        squared += t * (field + count * q * q / 3.0);
        samples += t * count;
    }
    if samples > 0.0 {
        (squared / samples).sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, uniform, SelectOptions};

    #[test]
    fn visible_bricks_at_their_level_count_and_nothing_else() {
        let v = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
        let s = select(&o, &SelectOptions::new(20_000, 0.0), |_, _| true).unwrap();
        let largest = s.bricks.iter().map(|b| b.error as f64).fold(0.0, f64::max);
        assert!(largest > 0.0);
        assert_eq!(s.estimated_error, largest);
        assert_eq!(estimated_error(&o, &s.bricks, |_, _| true), largest);
        // Bricks the transfer function hides draw nothing at any stride.
        assert_eq!(estimated_error(&o, &s.bricks, |_, _| false), 0.0);
        // The ranges of the bricks with the largest error hidden: the next largest.
        let range = |b: &Brick| (o.node(b.node).min, o.node(b.node).max);
        let hidden: Vec<(f64, f64)> = s.bricks.iter().filter(|b| b.error as f64 == largest).map(range).collect();
        let shown = |min: f64, max: f64| !hidden.contains(&(min, max));
        let next =
            s.bricks.iter().filter(|b| shown(range(b).0, range(b).1)).map(|b| b.error as f64).fold(0.0, f64::max);
        assert!(next < largest);
        assert_eq!(estimated_error(&o, &s.bricks, shown), next);
        // Full resolution: 0; one coarse texture: the root's error at its level.
        assert_eq!(uniform(&o, 1, 4).unwrap().estimated_error, 0.0);
        let coarse = uniform(&o, 4, 4).unwrap();
        assert_eq!(coarse.estimated_error, o.node(o.root()).error(coarse.bricks[0].p) as f64);
    }

    #[test]
    fn the_rms_estimate_is_the_visible_samples_squared_error_over_their_count() {
        let v = generate(Dataset::MarschnerLobb, 33, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
        let root = o.node(o.root());
        // One coarse texture: sqrt(Q_p / n) over the root's 33^3 samples.
        let coarse = uniform(&o, 4, 4).unwrap();
        let q = root.squared_error(coarse.bricks[0].p) as f64;
        assert!(q > 0.0);
        let expected = (q / 33f64.powi(3)).sqrt();
        assert!((coarse.estimated_rms_error - expected).abs() <= 1e-12 * expected, "{coarse:?}");
        // At most the largest error, and finer strides have less.
        assert!(coarse.estimated_rms_error <= coarse.estimated_error);
        let finer = uniform(&o, 2, 4).unwrap();
        assert!(finer.estimated_rms_error < coarse.estimated_rms_error);
        assert_eq!(uniform(&o, 1, 4).unwrap().estimated_rms_error, 0.0);
        // Hidden bricks count for nothing; nothing visible is 0.
        assert_eq!(estimated_rms_error(&o, &coarse.bricks, |_, _| false), 0.0);
        // A greedy selection: it falls as the budget grows while the largest error may tie.
        let small = select(&o, &SelectOptions::new(4_000, 0.0), |_, _| true).unwrap();
        let large = select(&o, &SelectOptions::new(40_000, 0.0), |_, _| true).unwrap();
        assert!(large.estimated_rms_error < small.estimated_rms_error, "{small:?} {large:?}");
        assert_eq!(small.estimated_rms_error, estimated_rms_error(&o, &small.bricks, |_, _| true));
        // The quantization a texel format adds counts as q^2 / 3 per sample.
        let quantized =
            select(&o, &SelectOptions { texel_error: 0.01, ..SelectOptions::new(1 << 30, 0.0) }, |_, _| true).unwrap();
        assert!(quantized.bricks.iter().all(|b| o.node(b.node).squared_error(b.p) == 0.0), "lossless at any budget");
        let r = quantized.estimated_rms_error;
        assert!((r - 0.01 / 3f64.sqrt()).abs() < 1e-6, "{r}");
    }

    /// Slices wider than a brick's texels count a third of the squared
    /// error of the level at the slices' stride; a transmittance weighs a
    /// brick's samples, 0 leaving it out; against sums made here in f64.
    #[test]
    fn widened_slices_and_transmittance_enter_the_rms_estimate() {
        fn seen(brick: &Brick, slice_stride: f64, transmittance: f64) -> Seen<'_> {
            Seen { brick, slice_stride, transmittance }
        }
        let v = generate(Dataset::MarschnerLobb, 33, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
        let root = o.node(o.root());
        let full = uniform(&o, 1, 4).unwrap().bricks[0];
        let n = 33f64.powi(3);
        let one = |s: Seen<'_>| seen_rms_error(&o, [s], |_, _| true);
        // At its stride, or sliced finer: lossless.
        assert_eq!(one(seen(&full, 1.0, 1.0)), 0.0);
        assert_eq!(one(seen(&full, 0.5, 1.0)), 0.0);
        assert_eq!(one(seen(&full, 1.9, 1.0)), 0.0, "below two strides the lattice is the brick's");
        // Slices 4 samples apart: the level at stride 4, a third of it.
        let p = full.p;
        let expected = (root.squared_error(p - 2) as f64 / 3.0 / n).sqrt();
        assert!(expected > 0.0);
        let r = one(seen(&full, 4.0, 1.0));
        assert!((r - expected).abs() <= 1e-12 * expected, "{r} vs {expected}");
        // 5 samples: still stride 4 (floor); past the root: the coarsest level.
        assert_eq!(one(seen(&full, 5.0, 1.0)), r);
        let coarsest = (root.squared_error(0) as f64 / 3.0 / n).sqrt();
        assert!((one(seen(&full, 1e9, 1.0)) - coarsest).abs() <= 1e-12 * coarsest);
        // A coarse brick keeps its own error when a third of the wider level's is less.
        let coarse = uniform(&o, 4, 4).unwrap().bricks[0];
        let own = (root.squared_error(coarse.p) as f64 / n).sqrt();
        let wide = (root.squared_error(coarse.p - 1) as f64 / 3.0 / n).sqrt();
        assert!((one(seen(&coarse, 8.0, 1.0)) - own.max(wide)).abs() <= 1e-12 * own);
        // Not a number as a slice stride or a transmittance: read as the stride, and as 1.
        assert_eq!(one(seen(&coarse, f64::NAN, f64::NAN)), one(seen(&coarse, 4.0, 1.0)));
        // Hidden: nothing; one transmittance for all: the same as none.
        assert_eq!(one(seen(&coarse, 4.0, 0.0)), 0.0);
        assert!((one(seen(&coarse, 4.0, 0.25)) - own).abs() <= 1e-12 * own);
        // A coarse brick behind T and a lossless one in front: sqrt(T Q / (T n + n)).
        for t in [1.0, 0.5, 0.01] {
            let both = seen_rms_error(&o, [seen(&coarse, 4.0, t), seen(&full, 1.0, 1.0)], |_, _| true);
            let want = (t * root.squared_error(coarse.p) as f64 / (t * n + n)).sqrt();
            assert!((both - want).abs() <= 1e-12 * want, "T {t}: {both} vs {want}");
        }
    }
}
