//! The error mass of a node at a level, and what a step buys per byte
//! (see the module documentation of [`super`]).

use crate::octree::NodeRef;

/// The error mass of node `n` drawn at level `p`, `removed` of its squared
/// error corrected by points:
///
/// ```text
/// mass(n, p) = max(Q_p(n) - removed, E_p(n)^2)
/// ```
///
/// `Q_p` sums the node's half-open box (each sample counted once across
/// nodes), but the node draws its closed box: the cells along its far faces
/// interpolate towards face samples that `Q_p` leaves to the neighbours. A
/// node whose only error lies on a far face has `Q_p = 0` and still draws
/// that error; `E_p` (the closed box's largest error) keeps its mass above
/// 0, so that a budget with room left refines it to full resolution, and
/// keeps a coarser level from passing for one of no more error
/// (the cheapest form, `refine::cheapest`): a node at full resolution has mass 0, and only an exact
/// coarse form (`E_q = 0`) matches it.
///
/// Maximum and minimum intensity draw a coarse brick from peak-keeping
/// texels ([`crate::render::texture`]'s `pool`): they are exact only for a
/// constant node, elsewhere they may show any value of the node's range a
/// stride away. With `pooled = Some(1 / range)` (the data range) a node
/// drawn coarser than its full resolution (`p < L - level`) keeps at least
/// that error,
///
/// ```text
/// E_pool(n) = (max(n) - min(n)) / range,   mass(n, p) >= E_pool(n)^2   (p < L - level)
/// ```
///
/// (normalised like `E_p`), so that only a constant node passes for exact
/// at a coarse level and a peak's node is refined first.
pub(super) fn error_mass(n: &NodeRef<'_>, p: usize, removed: f64, pooled: Option<f64>) -> f64 {
    let e = n.error(p) as f64;
    let e_pool = match pooled {
        Some(inv_range) if p < n.errors.len() => (n.max - n.min) * inv_range,
        _ => 0.0,
    };
    (n.squared_error(p) as f64 - removed).max(e * e).max(e_pool * e_pool)
}

/// What a step buys: error mass removed per byte added, and a step that
/// frees bytes without adding error before any step that costs bytes.
/// A step that changes neither (the same bricks again) buys nothing: 0.
pub(super) fn gain(removed: f64, added_bytes: f64) -> f64 {
    if added_bytes == 0.0 && removed == 0.0 {
        0.0
    } else if added_bytes <= 0.0 && removed >= 0.0 {
        f64::INFINITY
    } else {
        removed / added_bytes.max(1.0)
    }
}
