//! Wider slices, when bytes alone cannot meet a frame time: every brick is
//! sliced at least `m d0` apart,
//!
//! ```text
//! d' = max(d, m d0)        m a power of two, d = stride d0 (capped; see crate::data::spacing)
//! ```
//!
//! so the spacings stay `d0` times powers of two and the lattices stay
//! nested (no seam between strides, the jitter period still a multiple of
//! each). The opacity correction `a' = 1 - (1 - a)^(d'/d0)` keeps the
//! picture's opacity; it loses the detail between the slices. A brick with
//! translucent-surface batches or points between its slices keeps its
//! slices (they were placed between them). [`Plan::min_slice_spacing`]
//! says what was done; the plan's effects are unchanged (the compositor's
//! per-sample work is the same).

use crate::plan::slab::slice_depths;
use crate::plan::{DrawList, Plan};

/// `list` with every brick sliced at least `factor d0` apart (see the module
/// documentation); `factor` 0 or 1 leaves it as it is.
pub fn widen_slices(mut list: DrawList, factor: u32) -> DrawList {
    if factor <= 1 {
        return list;
    }
    let spacing = f64::from(factor) * list.reference_spacing;
    if !(spacing.is_finite() && spacing > 0.0) {
        return list;
    }
    let camera = list.camera;
    for b in list.bricks.iter_mut().filter(|b| b.batches.is_empty() && b.points.is_empty()) {
        if b.slice_spacing < spacing {
            b.slice_spacing = spacing;
            b.slices = slice_depths(&camera, b.world_lo, b.world_hi, spacing);
        }
    }
    list.plan = Plan { min_slice_spacing: Some(spacing), ..list.plan };
    list
}
