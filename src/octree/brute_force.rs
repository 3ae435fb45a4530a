//! The reference: nodal errors (and squared errors) of one node computed straight from the
//! definition, sample by sample, with no sharing between nodes or strides.
//! Slow (O(samples x levels) per node); for tests and for checking a build.
//! NaN follows the no-data rule of [`super::build`], written out in
//! [`sample_error`].

use super::build::{normalise, squared_error};
use super::layout::NodeId;
use super::trilinear::{eval, kernel_scale};
use super::volume_octree::VolumeOctree;
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};

/// The error of one sample: `None` for a hole (exactly one of `f` and `t`
/// NaN), 0 when both are NaN, `f - t` otherwise.
pub fn sample_error(f: f64, t: f64) -> Option<f64> {
    match (f.is_nan(), t.is_nan()) {
        (true, true) => Some(0.0),
        (false, false) => Some(f - t),
        _ => None,
    }
}

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
                            *r = match sample_error(g.at(x, y, z) * k, eval(&g, s, x, y, z) * k) {
                                Some(d) => r.max(d.abs()),
                                None => f64::INFINITY,
                            };
                        }
                    }
                }
            }
            let mut out = vec![0.0f32; n];
            let mut envelope = 0.0f64;
            for p in (0..n).rev() {
                envelope = envelope.max(raw[p]);
                out[p] = if envelope == f64::INFINITY { 1.0 } else { normalise(envelope, vmax * k - vmin * k) };
            }
            out
        }
    }
    grid.visit(Brute { octree, id })
}

/// Q_p(n), p = 0 .. L-k-1, of node `id`, from the definition: the sum of
/// `(f(v) - T_(2^(L-k-p))(v))^2 / range^2` over the samples v of the node's
/// half-open box (its max faces belong to the next node, except on the
/// grid's last samples), plus 1 per hole sample.
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
                    let (mut sum, mut holes) = (0.0, 0.0);
                    for z in node.lo[2]..end(2) {
                        for y in node.lo[1]..end(1) {
                            for x in node.lo[0]..end(0) {
                                match sample_error(g.at(x, y, z) * k, eval(&g, s, x, y, z) * k) {
                                    Some(d) => sum += d * d,
                                    None => holes += 1.0,
                                }
                            }
                        }
                    }
                    squared_error(sum, holes, range2) as f64
                })
                .collect()
        }
    }
    grid.visit(Brute { octree, id })
}
