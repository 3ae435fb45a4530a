//! The estimated error of a selection: how far its picture can be from the
//! full-resolution one, as the picture sees it: the largest error of a
//! visible brick ([`estimated_error`]), and the root-mean-square error of
//! the visible samples ([`estimated_rms_error`]).
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
/// count of those samples.
///
/// ```text
/// estimate_rms = sqrt( sum_b (Q_(p_b)(b) + n_b q_b^2 / 3) / sum_b n_b )
///                over drawn bricks b with visible(min_b, max_b)
/// ```
///
/// `Q_p(b)` is the brick's squared error at its level, summed over the
/// `n_b` samples of its closed box and normalised by the squared data
/// range (the build's, see [`crate::octree::build`]); `q_b` the
/// quantization error its texel format adds (the brick's error envelope
/// less `E_p(b)`: the largest rounding error, whose mean square over
/// uniformly spread rounding is `q^2 / 3`). Where [`estimated_error`] says
/// how wrong the worst visible sample can be, this says how wrong the
/// visible samples are on the whole: it falls with every brick refined,
/// not only when the worst one is, so it ranks selections by the RMSE of
/// their pictures where the largest error ties (a field with detail
/// everywhere keeps one coarse brick's maximum over a wide range of
/// budgets). 0 exactly when every visible brick draws the full-resolution
/// field losslessly; 0 with no visible brick.
pub fn estimated_rms_error(octree: &VolumeOctree, bricks: &[Brick], visible: impl Fn(f64, f64) -> bool) -> f64 {
    let (mut squared, mut samples) = (0.0f64, 0.0f64);
    for b in bricks {
        let n = octree.node(b.node);
        if !visible(n.min, n.max) {
            continue;
        }
        let count = (0..3).map(|a| (b.hi[a] - b.lo[a] + 1) as f64).product::<f64>();
        let q = (f64::from(b.error) - f64::from(n.error(b.p))).max(0.0);
        squared += f64::from(n.squared_error(b.p)).max(0.0) + count * q * q / 3.0;
        samples += count;
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
}
