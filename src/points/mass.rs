//! What a brick's points would buy, for the texture-budget selection
//! (issue 8: "selection may spend bytes on a brick's points instead of
//! refining it, choosing whichever buys more error reduction per byte").
//!
//! The selection ranks steps by the squared error they remove per byte,
//! `Q_p(n) = sum over the node's samples of (f - T_p)^2 / range^2`. Points
//! complete T_f, so a brick of stride `f` that takes its points removes the
//! squared error of those it can correct. A point drawn with its voxel-mean
//! shade ([`super::shade`]) adds back `m`, the mean of `e = f - T_f` over its
//! voxel, so of the voxel's squared error `sum e_i^2` it leaves
//! `sum (e_i - m)^2`: it removes one sample's worth of `m^2` (points only
//! add opacity, so only `m > 0` counts):
//!
//! ```text
//! removed(n) = eta x sum over the points of n with m > 0 of (m / range)^2,   bytes(n) = point bytes x count(n)
//! ```
//!
//! `eta` ([`POINT_EFFICIENCY`], 1/2) is the share of that data-space error a
//! splatted point removes from the picture, against a texel refined in
//! place: measured, not derived. A point corrects only where the low
//! resolution underestimates, and does so with a footprint of whole pixels
//! around its centre, not the texture's trilinear profile; on the
//! `vessels` angiogram at 256^3 (`bench render --points`, 1.10 MB) the
//! selection with `eta = 1` bought 1,464 factor-4 points in place of
//! refinement and drew a picture 12 % worse than the octree alone; with
//! `eta = 1/2` it buys 112 and is 1 % better, and no octree+points row of
//! docs/BENCHMARKS.md is worse than the octree alone (at 1/4 the gains
//! shrink: 0.14 MB vessels 0.84 -> 0.95 of the octree).
//!
//! ([`PointMass::with_errors`] with [`super::shade::voxel_mean_errors`];
//! [`PointMass::new`] takes `m = e`, the point's own sample). Counting `e^2`
//! overrates points on thin structures, where `m` is about half of `e`: the
//! selection then traded texture for points that made the picture worse
//! (docs/BENCHMARKS.md).
//!
//! A point at sample `x` belongs to the node whose half-open box holds it,
//! that is whose cells hold cell `min(x, dims - 2)` (the convention of
//! `Q_p`). Counts and sums are kept on a lattice of `block`-cell blocks with
//! summed-area tables, so any node box aligned to blocks (every node at or
//! above the leaf level) is answered in O(1).

use super::PointSet;
use crate::error::{Error, Result};

/// `eta`: the share of a point's removable data-space squared error the
/// selection counts (see the module documentation for the measurement).
pub const POINT_EFFICIENCY: f64 = 0.5;

/// Per-block point counts and removable squared error, as summed-area tables.
#[derive(Debug, Clone)]
pub struct PointMass {
    /// The low-resolution factor the points complete: only bricks of this stride take them.
    pub factor: usize,
    /// Bytes of one stored point.
    pub point_bytes: usize,
    block: usize,
    /// Blocks per axis.
    blocks: [usize; 3],
    /// Summed-area tables over `(blocks + 1)^3`: all points, and (e > 0 only) their count and `eta (e / range)^2`.
    count: Vec<u64>,
    positive: Vec<u64>,
    removable: Vec<f64>,
}

impl PointMass {
    /// The tables of `set` on blocks of `block` cells (the octree's leaf
    /// size), each point correcting its own sample's error.
    pub fn new(set: &PointSet, block: usize) -> PointMass {
        let errors: Vec<f64> = set.points.iter().map(|p| set.error(p)).collect();
        PointMass::tables(set, block, &errors)
    }

    /// [`PointMass::new`] with the error each point corrects given, one per
    /// point of `set` ([`super::shade::voxel_mean_errors`] for points drawn
    /// with their voxel-mean shade); only positive ones are removable.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when there are not as many errors as points.
    pub fn with_errors(set: &PointSet, block: usize, errors: &[f64]) -> Result<PointMass> {
        if errors.len() != set.points.len() {
            return Err(Error::InvalidArgument(format!(
                "{} errors for {} points: give one per point of the set",
                errors.len(),
                set.points.len()
            )));
        }
        Ok(PointMass::tables(set, block, errors))
    }

    /// The tables, one error per point.
    fn tables(set: &PointSet, block: usize, errors: &[f64]) -> PointMass {
        let block = block.max(1);
        let cells = set.dims.map(|n| n.saturating_sub(1).max(1));
        let blocks = cells.map(|c| c.div_ceil(block));
        let side = blocks.map(|b| b + 1);
        let at = |i: usize, j: usize, k: usize| i + side[0] * (j + side[1] * k);
        let mut count = vec![0u64; side[0] * side[1] * side[2]];
        let mut positive = vec![0u64; count.len()];
        let mut removable = vec![0.0f64; count.len()];
        let range = set.value_range[1] - set.value_range[0];
        for (p, &e) in set.points.iter().zip(errors) {
            let b: [usize; 3] = std::array::from_fn(|a| usize::from(p.ijk[a]).min(cells[a] - 1) / block);
            let slot = at(b[0] + 1, b[1] + 1, b[2] + 1);
            count[slot] += 1;
            if e > 0.0 && range > 0.0 {
                positive[slot] += 1;
                removable[slot] += POINT_EFFICIENCY * (e / range) * (e / range);
            }
        }
        // Prefix sums along each axis in turn.
        for axis in 0..3 {
            for k in 0..side[2] {
                for j in 0..side[1] {
                    for i in 0..side[0] {
                        let idx = [i, j, k];
                        if idx[axis] == 0 {
                            continue;
                        }
                        let mut prev = idx;
                        prev[axis] -= 1;
                        let (here, before) = (at(i, j, k), at(prev[0], prev[1], prev[2]));
                        count[here] += count[before];
                        positive[here] += positive[before];
                        removable[here] += removable[before];
                    }
                }
            }
        }
        PointMass { factor: set.factor, point_bytes: set.point_bytes(), block, blocks, count, positive, removable }
    }

    /// For the node with cell box `[lo, hi)` (samples `lo ..= hi`): its
    /// points, those with `e > 0`, and their removable squared error (`eta` included).
    pub fn in_box(&self, lo: [usize; 3], hi: [usize; 3]) -> (usize, usize, f64) {
        let b0: [usize; 3] = std::array::from_fn(|a| (lo[a] / self.block).min(self.blocks[a]));
        let b1: [usize; 3] = std::array::from_fn(|a| hi[a].div_ceil(self.block).min(self.blocks[a]).max(b0[a]));
        let side = self.blocks.map(|b| b + 1);
        let at = |i: usize, j: usize, k: usize| i + side[0] * (j + side[1] * k);
        let sum_u = |t: &[u64]| {
            t[at(b1[0], b1[1], b1[2])]
                + t[at(b0[0], b0[1], b1[2])]
                + t[at(b0[0], b1[1], b0[2])]
                + t[at(b1[0], b0[1], b0[2])]
                - t[at(b0[0], b1[1], b1[2])]
                - t[at(b1[0], b0[1], b1[2])]
                - t[at(b1[0], b1[1], b0[2])]
                - t[at(b0[0], b0[1], b0[2])]
        };
        let t = &self.removable;
        let removable = t[at(b1[0], b1[1], b1[2])]
            - t[at(b0[0], b1[1], b1[2])]
            - t[at(b1[0], b0[1], b1[2])]
            - t[at(b1[0], b1[1], b0[2])]
            + t[at(b0[0], b0[1], b1[2])]
            + t[at(b0[0], b1[1], b0[2])]
            + t[at(b1[0], b0[1], b0[2])]
            - t[at(b0[0], b0[1], b0[2])];
        (sum_u(&self.count) as usize, sum_u(&self.positive) as usize, removable.max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::datasets::{generate as dataset, Dataset};
    use crate::grid::ScalarType;
    use crate::points::{generate, PointOptions, PointSelect};

    #[test]
    fn box_sums_equal_counting_the_points() {
        let v = dataset(Dataset::SheppLogan, 33, ScalarType::F32);
        let set = generate(&v.grid(None).unwrap(), &PointOptions::new(2, PointSelect::Threshold(0.05))).unwrap();
        let mass = PointMass::new(&set, 4);
        let range = set.value_range[1] - set.value_range[0];
        for (lo, hi) in [([0, 0, 0], [32, 32, 32]), ([8, 4, 16], [16, 12, 32]), ([28, 28, 28], [32, 32, 32])] {
            let mut expect = (0, 0, 0.0);
            for p in &set.points {
                let c: [usize; 3] = std::array::from_fn(|a| usize::from(p.ijk[a]).min(31));
                if (0..3).all(|a| lo[a] <= c[a] && c[a] < hi[a]) {
                    expect.0 += 1;
                    let e = set.error(p);
                    if e > 0.0 {
                        expect.1 += 1;
                        expect.2 += POINT_EFFICIENCY * (e / range) * (e / range);
                    }
                }
            }
            let got = mass.in_box(lo, hi);
            assert_eq!((got.0, got.1), (expect.0, expect.1), "{lo:?} {hi:?}");
            assert!((got.2 - expect.2).abs() < 1e-9 * (1.0 + expect.2), "{lo:?} {hi:?}: {got:?} {expect:?}");
        }
        assert_eq!(mass.in_box([0; 3], [32; 3]).0, set.points.len());
    }
}
