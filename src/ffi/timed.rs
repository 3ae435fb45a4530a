//! Frames within a time for the OpenGL mapper: the cost model of
//! [`crate::plan::cost`] calibrated on the mapper's own frames (the GPU's,
//! or llvmpipe's, drawing time, measured with `glFinish`) and the
//! time-budgeted selection ([`select_for_time`]) over the handle's kept
//! selector.
//!
//! A [`FrameTimer`] warms up first: its first [`WARM_UP_FRAMES`] frames
//! draw the memory limit `B_max` (the full picture first, with the bytes
//! `B_f` it takes), then budgets shrinking geometrically from it,
//!
//! ```text
//! B_0 = B_max,  B_i = max(B_f / 8^i, B_min),  i = 1 .. n - 1,     B_min = B_max / 512
//! ```
//!
//! and the prior is fitted to their measured times ([`fit`]). After that each
//! search picks the budget (and slice spacing) of least estimated RMS error
//! predicted within the target, never below `B_min` (the coarsest
//! selection can be a single brick whose trilinear field the opacity hides
//! everywhere: an empty picture is no frame to meet a time with), and every measured frame moves the online
//! correction `r` ([`Calibration::observe`]). A frame's predicted time
//! counts no upload (the chosen bricks' textures are resident once drawn);
//! a measured frame's terms count the bytes it did upload, so the fit and
//! the correction learn what an upload costs without charging it to the
//! frames that do not pay it.

use super::guard::{guarded, Bridged};
use super::octree::HybridOctreeHandle;
use super::render::{prepared_with, SelectionHandle};
use super::{SelectDesc, TimedFrameDesc, TimedSummary};
use crate::base::error::{Error, Result};
use crate::plan::cost::{fit, select_for_time, Calibration, CostModel, CostTerms, FrameShape, Measurement, TimeTarget};
use crate::plan::select::{SelectOptions, Selection};
use crate::plan::DrawList;
use std::sync::atomic::Ordering;

/// Calibration frames before the model is fitted.
pub const WARM_UP_FRAMES: usize = 4;

/// The least budget a timed frame draws, as a share of the memory limit
/// (`B_min = B_max / MIN_BUDGET_DIVISOR`: 125 kB of a 64 MB limit).
pub const MIN_BUDGET_DIVISOR: usize = 512;

/// Each warm-up frame after the first draws this many times fewer bytes than the one before.
const WARM_UP_STEP: usize = 8;

/// The least budget a timed frame draws under the limit `limit` (see the module documentation).
pub fn min_budget(limit: usize) -> usize {
    (limit / MIN_BUDGET_DIVISOR).max(1)
}

/// How far the online correction may move from its value at the last
/// search before the next frame searches again: a quarter, either way.
pub const RESEARCH_RATIO: f64 = 1.25;

/// The cost model of this machine and what it last chose (see the module documentation).
#[derive(Debug)]
pub struct FrameTimer {
    calibration: Calibration,
    /// The warm-up frames measured so far (emptied once fitted).
    warm_up: Vec<Measurement>,
    fitted: bool,
    /// The full budget's bytes as selected, from the first warm-up frame.
    full_bytes: Option<usize>,
    /// The correction when the last search ran.
    searched_ratio: f64,
    last: Last,
}

/// What the last choice and the last frame were.
#[derive(Debug, Clone, Default)]
struct Last {
    target_ms: f64,
    predicted_ms: f64,
    measured_ms: f64,
    budget_bytes: usize,
    slice_factor: u32,
    outcome: &'static str,
    evaluations: usize,
    estimated_rms_error: f64,
    note: String,
}

/// A timer with the prior model, its warm-up to come.
pub(crate) fn new_frame_timer() -> Box<FrameTimer> {
    Box::new(FrameTimer::new())
}

impl Default for FrameTimer {
    fn default() -> Self {
        FrameTimer::new()
    }
}

impl FrameTimer {
    /// A timer with the prior model, its warm-up to come.
    pub fn new() -> FrameTimer {
        FrameTimer {
            calibration: Calibration::new(CostModel::prior()),
            warm_up: Vec::with_capacity(WARM_UP_FRAMES),
            fitted: false,
            full_bytes: None,
            searched_ratio: 1.0,
            last: Last { slice_factor: 1, outcome: "warm-up", ..Last::default() },
        }
    }

    /// The calibrated model and its correction.
    pub fn calibration(&self) -> &Calibration {
        &self.calibration
    }

    /// The budget of warm-up frame `i` under the limit `limit` (see the module documentation).
    fn warm_up_budget(&self, i: usize, limit: usize) -> usize {
        match (i, self.full_bytes) {
            (0, _) | (_, None) => limit,
            (_, Some(full)) => {
                let step = WARM_UP_STEP.saturating_pow(i as u32);
                (full.min(limit) / step).max(min_budget(limit))
            }
        }
    }

    pub(crate) fn select_for_time(
        &mut self,
        octree: &HybridOctreeHandle,
        desc: &SelectDesc,
        frame: &TimedFrameDesc,
    ) -> Bridged<Box<SelectionHandle>> {
        guarded(|| self.select(octree, desc, frame).map(Box::new))
    }

    fn select(
        &mut self,
        octree: &HybridOctreeHandle,
        desc: &SelectDesc,
        frame: &TimedFrameDesc,
    ) -> Result<SelectionHandle> {
        let target = TimeTarget {
            min_budget_bytes: min_budget(desc.budget_bytes),
            ..TimeTarget::new(frame.target_ms, desc.budget_bytes)?
        };
        if frame.width == 0 || frame.height == 0 {
            return Err(Error::InvalidArgument(format!(
                "a frame within a time of a {} x {} viewport: give a viewport of at least 1 x 1 pixel",
                frame.width, frame.height
            )));
        }
        let shape = FrameShape { width: frame.width, height: frame.height, uploads: false };
        if !self.fitted {
            let budget = self.warm_up_budget(self.warm_up.len(), desc.budget_bytes);
            let (handle, list) = prepared_with(octree, desc, |p| {
                let options = SelectOptions { budget_bytes: budget, ..*p.options };
                let selection = p.selector.select_in_view(p.tree, &options, p.visible, p.points, p.view)?;
                let handle = planned(octree, desc, frame, selection, p.transfer_2d.clone(), p.texel, p.mode)?;
                let list = handle.list(octree, &frame.camera, frame.surface_opacity)?;
                Ok((handle, list))
            })?;
            if self.warm_up.is_empty() {
                self.full_bytes = Some(handle.selection.texture_bytes.max(1));
            }
            let terms = CostTerms::of(&list, shape.width, shape.height, 0);
            self.last = Last {
                target_ms: target.target_ms,
                predicted_ms: self.calibration.predict(&terms),
                measured_ms: self.last.measured_ms,
                budget_bytes: budget,
                slice_factor: 1,
                outcome: "warm-up",
                evaluations: 1,
                estimated_rms_error: handle.selection.estimated_rms_error,
                note: String::new(),
            };
            return Ok(handle);
        }
        let calibration = self.calibration;
        let (choice, chosen) = prepared_with(octree, desc, |p| {
            let (transfer_2d, texel, mode) = (p.transfer_2d, p.texel, p.mode);
            let plan = |s: &Selection| -> Result<DrawList> {
                let handle = planned(octree, desc, frame, s.clone(), transfer_2d.clone(), texel, mode)?;
                handle.list(octree, &frame.camera, frame.surface_opacity)
            };
            let choice = select_for_time(
                &target,
                p.selector,
                p.tree,
                p.options,
                p.visible,
                p.points,
                p.view,
                &calibration,
                shape,
                plan,
            )?;
            // The estimate as drawn: its slices widened or not.
            let selection = Selection {
                estimated_rms_error: choice.chosen.value.estimated_rms_error,
                ..choice.chosen.value.selection.clone()
            };
            let handle = planned(octree, desc, frame, selection, transfer_2d.clone(), texel, mode)?;
            Ok((choice, handle))
        })?;
        chosen.slice_factor.store(choice.chosen.slice_factor, Ordering::Relaxed);
        self.searched_ratio = self.calibration.ratio();
        self.last = Last {
            target_ms: target.target_ms,
            predicted_ms: choice.chosen.predicted_ms,
            measured_ms: self.last.measured_ms,
            budget_bytes: choice.chosen.budget_bytes,
            slice_factor: choice.chosen.slice_factor,
            outcome: choice.outcome.name(),
            evaluations: choice.evaluations,
            estimated_rms_error: chosen.selection.estimated_rms_error,
            note: choice.note.unwrap_or_default(),
        };
        Ok(chosen)
    }

    pub(crate) fn observe_frame(
        &mut self,
        selection: &SelectionHandle,
        octree: &HybridOctreeHandle,
        frame: &TimedFrameDesc,
        uploaded_bytes: usize,
        ms: f64,
    ) -> Bridged<bool> {
        guarded(|| {
            let list = selection.list(octree, &frame.camera, frame.surface_opacity)?;
            let terms = CostTerms::of(&list, frame.width.max(1), frame.height.max(1), uploaded_bytes);
            Ok(self.observe(terms, ms))
        })
    }

    /// Feeds one measured frame of `terms` to the model (see
    /// `FrameTimer::observe_frame` for what the answer means).
    pub fn observe(&mut self, terms: CostTerms, ms: f64) -> bool {
        let measurement = Measurement { terms, ms };
        if !measurement.is_usable() {
            return false;
        }
        self.last.measured_ms = ms;
        if !self.fitted {
            self.warm_up.push(measurement);
            if self.warm_up.len() >= WARM_UP_FRAMES {
                if let Ok(model) = fit(&CostModel::prior(), &self.warm_up) {
                    self.calibration = Calibration::new(model);
                }
                self.fitted = true;
                self.warm_up.clear();
            }
            return true;
        }
        self.calibration.observe(&terms, ms);
        let moved = (self.calibration.ratio() / self.searched_ratio).ln().abs();
        moved > RESEARCH_RATIO.ln()
    }

    pub(crate) fn summary(&self) -> TimedSummary {
        let l = &self.last;
        TimedSummary {
            target_ms: l.target_ms,
            predicted_ms: l.predicted_ms,
            measured_ms: l.measured_ms,
            budget_bytes: l.budget_bytes,
            slice_factor: l.slice_factor.max(1),
            outcome: l.outcome.to_string(),
            evaluations: l.evaluations,
            estimated_rms_error: l.estimated_rms_error,
            warm_up_left: if self.fitted { 0 } else { WARM_UP_FRAMES - self.warm_up.len() },
            ratio: self.calibration.ratio(),
            note: l.note.clone(),
        }
    }
}

/// The handle of `selection` with the frame's effects set, as the mapper
/// sets them on the selection it draws.
fn planned(
    octree: &HybridOctreeHandle,
    desc: &SelectDesc,
    frame: &TimedFrameDesc,
    selection: Selection,
    transfer_2d: Option<crate::transfer::TransferFunction2D>,
    texel: crate::plan::texel_format::TexelEncoding,
    mode: crate::plan::select::ViewSelection,
) -> Result<SelectionHandle> {
    let handle = octree.selection_handle(desc, selection, transfer_2d, texel, mode)?;
    let bridged = |r: Bridged<()>| r.map_err(Error::InvalidArgument);
    bridged(handle.set_shading(&frame.shading))?;
    bridged(handle.set_gradient_opacity(&frame.gradient_opacity_points))?;
    bridged(handle.set_jittering(frame.jittering))?;
    bridged(handle.set_sample_distance(frame.sample_distance))?;
    bridged(handle.set_scattering(&frame.scattering))?;
    Ok(handle)
}
