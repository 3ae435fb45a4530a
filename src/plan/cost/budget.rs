//! The time-budgeted selection: the texture budget (and, when bytes alone
//! cannot, the slice spacing) of the least estimated error whose frame the
//! calibrated model predicts within a target. The error compared is the
//! frame's estimated root-mean-square error ([`frame_rms_error`]: the
//! selection's, its slices as drawn, behind the view's transmittance): it
//! falls with every visible brick refined, where the largest error ties
//! over wide ranges of budgets on data with detail everywhere, and rises
//! when the slices are widened.
//!
//! [`select_for_time`] runs [`super::search`] over a kept [`Selector`]:
//! each candidate budget re-selects through it, which replays its recorded
//! greedy run up to the first step the new budget decides otherwise (a
//! budget change costs the tail of the greedy, not a fresh selection), the
//! caller plans the candidate's DrawList, and the model predicts its time
//! from the list's terms ([`CostTerms::of`]). Every candidate's selection
//! equals a fresh [`crate::plan::select::select_in_view`] under its budget.

use super::online::Calibration;
use super::search::{search, Choice, TimeTarget};
use super::terms::CostTerms;
use super::widen::widen_slices;
use crate::base::error::Result;
use crate::octree::VolumeOctree;
use crate::plan::select::{seen_rms_error, Seen, SelectOptions, Selection, Selector, ViewImportance};
use crate::plan::DrawList;
use crate::points::PointMass;
use std::collections::HashMap;

/// What a frame is drawn on and what it uploads.
#[derive(Debug, Clone, Copy)]
pub struct FrameShape {
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// Whether every brick's texture is uploaded for the frame (the CLI);
    /// `false`: textures are resident, nothing is uploaded (a kept renderer).
    pub uploads: bool,
}

/// A selection and its DrawList (slices widened as the search chose).
#[derive(Debug, Clone)]
pub struct TimedFrame {
    /// The selection.
    pub selection: Selection,
    /// Its DrawList.
    pub list: DrawList,
    /// Its cost terms.
    pub terms: CostTerms,
    /// Its estimated root-mean-square error as drawn: [`frame_rms_error`],
    /// what the search compares.
    pub estimated_rms_error: f64,
}

/// The estimated root-mean-square error of the picture `list` draws
/// ([`seen_rms_error`]): each brick at the spacing of its slices as the
/// list slices it (widened or not) and behind the transmittance the view
/// estimates in front of it (none without a visibility estimate).
pub fn frame_rms_error(
    octree: &VolumeOctree,
    list: &DrawList,
    visible: impl Fn(f64, f64) -> bool,
    view: Option<&ViewImportance>,
) -> f64 {
    let d0 = list.reference_spacing;
    let mut drawn: Vec<Seen<'_>> = list
        .bricks
        .iter()
        .map(|d| {
            let t = view.map_or(1.0, |v| v.transmittance(octree.layout(), d.brick.node));
            let slice_stride = if d0 > 0.0 { d.slice_spacing / d0 } else { d.brick.stride as f64 };
            Seen { brick: &d.brick, slice_stride, transmittance: t }
        })
        .collect();
    // Summed in the selection's order (by node id), not the drawing's: the
    // same bricks at their strides give the selection's estimate to the bit.
    drawn.sort_by_key(|s| s.brick.node);
    seen_rms_error(octree, drawn, visible)
}

/// The selection of least estimated error within `target` (see the module
/// documentation): `options` is the selection's with its budget replaced
/// by each candidate's (`target.max_budget_bytes` the hard limit),
/// `points` the hybrid representation's point mass when the octree holds
/// points, `plan(selection)` the caller's DrawList for it.
#[allow(clippy::too_many_arguments)]
pub fn select_for_time(
    target: &TimeTarget,
    selector: &mut Selector,
    octree: &VolumeOctree,
    options: &SelectOptions,
    visible: impl Fn(f64, f64) -> bool,
    points: Option<&PointMass>,
    view: Option<&ViewImportance>,
    calibration: &Calibration,
    frame: FrameShape,
    mut plan: impl FnMut(&Selection) -> Result<DrawList>,
) -> Result<Choice<TimedFrame>> {
    // Each budget's selection and DrawList, made once whatever the slice factor.
    let mut made: HashMap<usize, (Selection, DrawList)> = HashMap::new();
    search(target, |budget, factor| {
        let (selection, list) = match made.get(&budget) {
            Some((s, l)) => (s.clone(), l.clone()),
            None => {
                let o = SelectOptions { budget_bytes: budget, ..*options };
                let s = selector.select_in_view(octree, &o, &visible, points, view)?;
                let l = plan(&s)?;
                made.insert(budget, (s.clone(), l.clone()));
                (s, l)
            }
        };
        let list = widen_slices(list, factor);
        let upload = if frame.uploads { selection.texture_bytes } else { 0 };
        let terms = CostTerms::of(&list, frame.width, frame.height, upload);
        let predicted = calibration.predict(&terms);
        let error = frame_rms_error(octree, &list, &visible, view);
        Ok((TimedFrame { selection, list, terms, estimated_rms_error: error }, predicted, error))
    })
}
