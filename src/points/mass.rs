//! What a brick's points would buy, for the texture-budget selection: it
//! may spend bytes on a brick's points instead of refining it, choosing
//! whichever buys more error reduction per byte.
//!
//! The selection ranks steps by the squared error they remove per byte,
//! `Q_p(n) = sum over the node's samples of (f - T_p)^2 / range^2`. Points
//! complete T_f, so a brick of stride `f` that takes its points removes the
//! squared error of those it can correct. A point drawn with its voxel-mean
//! shade ([`super::shade()`]) adds back `m`, the mean of `e = f - T_f` over its
//! voxel, so of the voxel's squared error `sum e_i^2` it leaves
//! `sum (e_i - m)^2`: it removes one sample's worth of `m^2` (points only
//! add opacity, so only `m > 0` counts):
//!
//! ```text
//! removed(n) = eta_f x sum over the points of n with m > 0 of (m / range)^2,   bytes(n) = point bytes x count(n)
//! eta_f      = 1 / sqrt(f)
//! ```
//!
//! `eta_f` ([`point_efficiency`]) is the share of that data-space error a
//! point removes from the picture, measured, not derived: a point corrects
//! the underestimate on a fine structure and leaves T_f's overestimate
//! beside it, spread over a region that grows with `f`; a ray integrates
//! that spread error, so the picture weighs it more than its squared sum
//! says. The measurements behind `1 / sqrt(f)` are in docs/BENCHMARKS.md
//! (hybrid point/volume rendering).
//!
//! ([`PointMass::voxel_means`]; [`PointMass::new`] takes `m = e`, the
//! point's own sample, and [`PointMass::with_errors`] any given `m`.)
//!
//! A point at sample `x` belongs to the node whose half-open box holds it,
//! that is whose cells hold cell `min(x, dims - 2)` (the convention of
//! `Q_p`). Counts and sums are kept on a lattice of `block`-cell blocks with
//! summed-area tables, so any node box aligned to blocks (every node at or
//! above the leaf level) is answered in O(1).

use super::set::PointSet;
use crate::base::error::{Error, Result};

/// `eta_f = 1 / sqrt(f)`: the share of a factor-`f` point's removable
/// data-space squared error the selection counts (see the module
/// documentation for the measurement).
pub fn point_efficiency(factor: usize) -> f64 {
    1.0 / (factor.max(1) as f64).sqrt()
}

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
    /// Summed-area tables over `(blocks + 1)^3`: all points, and (e > 0 only) their count and `eta_f (e / range)^2`.
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

    /// The tables of `set` on blocks of `block` cells, each point rated at
    /// what its voxel-mean shade removes ([`super::shade::voxel_mean_errors`]
    /// over `grid`, the grid the points were made from): what the renderers
    /// draw, so what the selection should count.
    pub fn voxel_means(grid: &crate::data::grid::Grid<'_>, set: &PointSet, block: usize) -> PointMass {
        PointMass::tables(set, block, &super::shade::voxel_mean_errors(grid, set))
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
        let eta = point_efficiency(set.factor);
        for (p, &e) in set.points.iter().zip(errors) {
            let b: [usize; 3] = std::array::from_fn(|a| usize::from(p.ijk[a]).min(cells[a] - 1) / block);
            let slot = at(b[0] + 1, b[1] + 1, b[2] + 1);
            count[slot] += 1;
            if e > 0.0 && range > 0.0 {
                positive[slot] += 1;
                removable[slot] += eta * (e / range) * (e / range);
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
    /// points, those with `e > 0`, and their removable squared error (`eta_f` included).
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
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate as dataset, Dataset};
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
                        expect.2 += point_efficiency(2) * (e / range) * (e / range);
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
