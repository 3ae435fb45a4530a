//! The ray sample distance (VTK's `SampleDistance`) of the effects whose
//! classification aliases at one sample a lattice step: the Isosurface blend
//! mode (a crossing is found between two consecutive samples) and the 2D
//! transfer function (the table's row is the sample's gradient magnitude).
//!
//! VTK 9.2's GPU ray caster samples every `s` along each ray, ParaView's
//! *Volume* (vtkSmartVolumeMapper, `LockSampleDistanceToInputSpacing`) at
//! `s = (mean spacing / 2) (0.01 + 0.99 n / 100)` for `n < 100` cells a
//! side (0.32 of a voxel at 64^3), half the mean spacing above. The
//! slices here are one lattice step `d = stride d0` apart. At a step of the
//! data one voxel wide (the Shepp-Logan phantom's shells), a sample one voxel
//! after the last misses a shell the field crosses for less than a voxel,
//! and a gradient-magnitude row is hit by one or two samples a ray instead
//! of three to six: the picture's crossings and rows depend on the sample
//! lattice (measured against ParaView's *Volume* at 64^3: RMSE 0.043 for the
//! Isosurface, 0.044 for the 2D function at `d = d0`; 0.011 and 0.016 at
//! `d = s`; VTK's own picture at `s = d0` is 0.066 and 0.13 from its `s`).
//! The planner then refines each brick's slices by the same factor:
//!
//! ```text
//! d' = d (s / d0)        for s < d0, every brick (the lattices stay nested)
//! ```
//!
//! and the renderers follow the DrawList (the opacity correction `d' / d0`,
//! the Isosurface's sample before, the jitter period). Only those two
//! effects (a volume, no translucent surface or points between the slices,
//! whose batches were placed between the stride's slices) refine:
//! [`Plan::sample_distance`], effect [`EFFECT`]. A plain or shaded frame
//! keeps one slice a lattice step, its sampling within 0.01 of VTK's.

use super::draw_list::{effects, DrawList, Plan, SAMPLE_DISTANCE_EFFECT};
use super::BlendMode;

/// The effect's name in [`Plan::effects`].
pub const EFFECT: &str = SAMPLE_DISTANCE_EFFECT;

/// Whether `plan`'s classification aliases at one sample a lattice step
/// (Isosurface, or the 2D transfer function) and it draws a volume.
pub fn aliases(plan: &Plan) -> bool {
    plan.volume && (plan.transfer_2d || plan.blend.mode == BlendMode::Isosurface)
}

/// `list` with its slices refined to the sample distance `s` (world units;
/// `None`, not positive or not below `d0`: the stride's slices), when
/// [`aliases`] and no brick has batches or points between its slices
/// (module documentation). Planning a list again with another distance
/// starts from the stride's spacing: it is not refined twice.
pub fn plan_sample_distance(mut list: DrawList, s: Option<f64>) -> DrawList {
    let d0 = list.reference_spacing;
    let undo = list.plan.sample_distance.map_or(1.0, |p| p / d0);
    let refines = aliases(&list.plan) && list.bricks.iter().all(|b| b.batches.is_empty() && b.points.is_empty());
    let wanted = s.filter(|&s| refines && s > 0.0 && s.is_finite() && s < d0);
    let factor = wanted.map_or(1.0, |s| s / d0) / undo;
    if factor != 1.0 {
        let camera = list.camera;
        for b in &mut list.bricks {
            b.slice_spacing *= factor;
            b.slices = super::slab::slice_depths(&camera, b.world_lo, b.world_hi, b.slice_spacing);
        }
    }
    list.plan.sample_distance = wanted;
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}
