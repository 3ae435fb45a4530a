//! The selection a [`HybridOctreeHandle`](super::HybridOctreeHandle) keeps
//! for its next one ([`crate::plan::select::Selector`]): an interactive
//! budget change (the mapper's interactive and still budgets) replays the
//! greedy refinement's record up to where the new budget changes it, with
//! every node's forms and steps kept; a new region of interest or camera
//! keeps the forms.
//!
//! The forms are valid for one visibility test: [`VisibilityKey`] holds
//! every field of the [`SelectDesc`] but the budget, the tolerance and the
//! region of interest (which reach the selection only through its options,
//! which the `Selector` compares itself); another key starts afresh.

use super::SelectDesc;
use crate::plan::select::Selector;

/// The kept `Selector` and the request it serves.
#[derive(Default)]
pub(crate) struct KeptSelector {
    key: Option<VisibilityKey>,
    selector: Selector,
}

impl std::fmt::Debug for KeptSelector {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("KeptSelector").field("kept", &self.key.is_some()).finish_non_exhaustive()
    }
}

impl KeptSelector {
    /// The `Selector` for `desc`: the kept one when `desc` classifies nodes
    /// as the last request did, a new one otherwise.
    pub(crate) fn for_desc(&mut self, desc: &SelectDesc) -> &mut Selector {
        let key = VisibilityKey::of(desc);
        if self.key.as_ref() != Some(&key) {
            self.selector = Selector::default();
            self.key = Some(key);
        }
        &mut self.selector
    }
}

/// What decides which nodes show and what a brick costs, besides the
/// selection's options (compared exactly: a NaN never matches, so it starts afresh).
#[derive(PartialEq)]
struct VisibilityKey {
    opacity_points: Vec<f64>,
    isovalue: Option<f64>,
    gradient_border: bool,
    blend_mode: i32,
    average_range: [f64; 2],
    texel_format: i32,
    isosurface_values: Vec<f64>,
    gradient_opacity_points: Vec<f64>,
    cropping: (bool, [f64; 6], u32),
    clipping_planes: Vec<f64>,
    transfer_2d: ([usize; 2], Vec<f32>, [f64; 2]),
    slice_plane: [f64; 6],
}

impl VisibilityKey {
    fn of(desc: &SelectDesc) -> VisibilityKey {
        let r = &desc.region;
        VisibilityKey {
            opacity_points: desc.opacity_points.clone(),
            isovalue: desc.has_isovalue.then_some(desc.isovalue),
            gradient_border: desc.gradient_border,
            blend_mode: desc.blend_mode,
            average_range: desc.average_range,
            texel_format: desc.texel_format,
            isosurface_values: desc.isosurface_values.clone(),
            gradient_opacity_points: desc.gradient_opacity_points.clone(),
            cropping: (r.cropping, r.cropping_planes, r.cropping_flags),
            clipping_planes: r.clipping_planes.clone(),
            transfer_2d: (desc.transfer_2d_size, desc.transfer_2d_rgba.clone(), desc.transfer_2d_range),
            slice_plane: desc.slice_plane,
        }
    }
}
