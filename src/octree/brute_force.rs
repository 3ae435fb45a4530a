//! The reference: nodal errors (and squared errors) of one node computed straight from the
//! definition, sample by sample, with no sharing between nodes or strides.
//! Slow (O(samples x levels) per node); for tests and for checking a build.

use super::build::normalise;
use super::layout::NodeId;
use super::trilinear::{eval, kernel_scale};
use super::volume_octree::VolumeOctree;
use crate::grid::{Grid, GridVisitor, Sample, TypedGrid};

/// Values are scaled by [`kernel_scale`] of the data range, as the build
/// scales them (1 unless the values are extreme).
///
/// E_p(n), p = 0 .. L-k-1, of node `id`, from the definition
/// `max over q >= p of max over v in n of |f(v) - T_(2^(L-k-q))(v)| / range`.
pub fn nodal_errors(grid: &Grid<'_>, octree: &VolumeOctree, id: NodeId) -> Vec<f32> {
    struct Brute<'o> {
        octree: &'o VolumeOctree,
        id: NodeId,
    }
    impl GridVisitor for Brute<'_> {
        type Output = Vec<f32>;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f32> {
            let node = self.octree.node(self.id);
            let (vmin, vmax) = self.octree.value_range();
            let k = kernel_scale(vmin, vmax);
            let n = self.octree.layout().error_count(node.level);
            let mut raw = vec![0.0f64; n];
            for (p, r) in raw.iter_mut().enumerate() {
                let s = 1usize << (n - p);
                for z in node.lo[2]..=node.hi[2] {
                    for y in node.lo[1]..=node.hi[1] {
                        for x in node.lo[0]..=node.hi[0] {
                            *r = r.max((g.at(x, y, z) * k - eval(&g, s, x, y, z) * k).abs());
                        }
                    }
                }
            }
            let mut out = vec![0.0f32; n];
            let mut envelope = 0.0f64;
            for p in (0..n).rev() {
                envelope = envelope.max(raw[p]);
                out[p] = normalise(envelope, vmax * k - vmin * k);
            }
            out
        }
    }
    grid.visit(Brute { octree, id })
}

/// Q_p(n), p = 0 .. L-k-1, of node `id`, from the definition: the sum of
/// `(f(v) - T_(2^(L-k-p))(v))^2 / range^2` over the samples v of the node's
/// half-open box (its max faces belong to the next node, except on the
/// grid's last samples).
pub fn squared_errors(grid: &Grid<'_>, octree: &VolumeOctree, id: NodeId) -> Vec<f64> {
    struct Brute<'o> {
        octree: &'o VolumeOctree,
        id: NodeId,
    }
    impl GridVisitor for Brute<'_> {
        type Output = Vec<f64>;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f64> {
            let node = self.octree.node(self.id);
            let (vmin, vmax) = self.octree.value_range();
            let k = kernel_scale(vmin, vmax);
            let range = vmax * k - vmin * k;
            let range2 = if range > 0.0 { range * range } else { 1.0 };
            let n = self.octree.layout().error_count(node.level);
            let end = |a: usize| if node.hi[a] == g.dims[a] - 1 { node.hi[a] + 1 } else { node.hi[a] };
            (0..n)
                .map(|p| {
                    let s = 1usize << (n - p);
                    let mut sum = 0.0;
                    for z in node.lo[2]..end(2) {
                        for y in node.lo[1]..end(1) {
                            for x in node.lo[0]..end(0) {
                                let d = g.at(x, y, z) * k - eval(&g, s, x, y, z) * k;
                                sum += d * d;
                            }
                        }
                    }
                    sum / range2
                })
                .collect()
        }
    }
    grid.visit(Brute { octree, id })
}
