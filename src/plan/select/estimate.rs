//! The estimated error of a selection: how far its picture can be from the
//! full-resolution one, as the picture sees it.
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
}
