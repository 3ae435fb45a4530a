//! Frames within a time (`render --target-ms`, `bench render --targets-ms`):
//! the cost model calibrated on warm-up frames of this machine, then per
//! frame the texture budget (and, when bytes alone cannot, the slice
//! spacing) of the least estimated error predicted within the target
//! (`plan::cost::select_for_time`), drawn, measured, and the measurement
//! fed back to the model's online correction.
//!
//! A frame's time here is what drawing its DrawList takes: uploading its
//! textures and compositing (`upload_ms + composite_ms`). The selection,
//! the search and the DrawList are made before and reported apart
//! (`select_ms`): a renderer that keeps its selection does not pay them
//! each frame.

use crate::field::Field;
use crate::scene::{draw_frame, plan_frame, Frame, Loaded, Planned, SceneArgs};
use hybrid_octree::plan::cost::{
    select_for_time, Calibration, CostModel, CostTerms, FrameShape, Measurement, Outcome, TimeTarget,
};
use hybrid_octree::select::{SelectOptions, Selection, Selector, ViewImportance};
use hybrid_octree::Result;
use std::time::Instant;

/// The scene a run of timed frames draws, and what it has learnt of the machine.
pub struct Timer<'a> {
    field: Field<'a>,
    scene: &'a Loaded,
    args: &'a SceneArgs,
    /// The selection's options; their budget is the hard memory limit.
    options: SelectOptions,
    view: Option<&'a ViewImportance>,
    isovalue: Option<f64>,
    selector: Selector,
    /// The calibrated model (the prior before [`Timer::calibrate`]).
    pub calibration: Calibration,
    /// The measured time of the coarsest selection's frame (set by [`Timer::calibrate`]), ms.
    pub fastest_ms: Option<f64>,
    /// Warm-up frames measured.
    pub warmup_frames: usize,
}

/// One timed frame.
pub struct Timed {
    /// The selection drawn.
    pub selection: Selection,
    /// The frame.
    pub frame: Frame,
    /// The target, ms.
    pub target_ms: f64,
    /// Its predicted time, ms.
    pub predicted_ms: f64,
    /// Its measured time (upload and compositing), ms.
    pub ms: f64,
    /// The budget it was selected under, bytes.
    pub budget_bytes: usize,
    /// Its slices' least spacing in multiples of d0 (1: the strides').
    pub slice_factor: u32,
    /// How the choice relates to the target.
    pub outcome: Outcome,
    /// Said when the target is below the fastest frame.
    pub note: Option<String>,
    /// The search (selections and DrawLists of every candidate), ms.
    pub search_ms: f64,
    /// Candidates the search evaluated.
    pub evaluations: usize,
}

/// The measured time of a frame: upload and compositing, ms.
pub fn frame_ms(f: &Frame) -> f64 {
    f.upload_ms + f.composite_ms
}

impl<'a> Timer<'a> {
    /// A timer of `scene` under `options` (their budget the memory limit) and `view`.
    pub fn new(
        field: Field<'a>,
        scene: &'a Loaded,
        args: &'a SceneArgs,
        options: SelectOptions,
        view: Option<&'a ViewImportance>,
    ) -> Timer<'a> {
        Timer {
            field,
            scene,
            args,
            options,
            view,
            isovalue: args.isovalue,
            selector: Selector::default(),
            calibration: Calibration::new(CostModel::prior()),
            fastest_ms: None,
            warmup_frames: 0,
        }
    }

    fn shape(&self) -> FrameShape {
        FrameShape { width: self.args.width, height: self.args.height, uploads: true }
    }

    fn select(&mut self, budget: usize) -> Result<Selection> {
        let o = SelectOptions { budget_bytes: budget, ..self.options };
        let visible = crate::scene::visible(self.scene, self.isovalue);
        self.selector.select_in_view(&self.scene.octree, &o, &visible, None, self.view)
    }

    /// Calibrates the model on `frames` warm-up frames (at least 2): budgets
    /// spread geometrically from the coarsest selection's bytes to the
    /// memory limit, each drawn and measured, the prior fitted to them.
    pub fn calibrate(&mut self, frames: usize) -> Result<()> {
        let frames = frames.max(2);
        let coarsest = self.select(1)?.texture_bytes.max(1);
        let limit = self.options.budget_bytes.max(coarsest);
        let mut measured = Vec::with_capacity(frames);
        for i in 0..frames {
            let budget = if i == 0 {
                1
            } else {
                let r = i as f64 / (frames - 1) as f64;
                ((coarsest as f64) * (limit as f64 / coarsest as f64).powf(r)).round() as usize
            };
            let selection = self.select(budget)?;
            let planned = plan_frame(self.field.shape(), self.scene, &selection, self.args, None)?;
            let terms = CostTerms::of(&planned.list, self.args.width, self.args.height, selection.texture_bytes);
            let f = draw_frame(self.field, self.scene, planned, self.args, None)?;
            let ms = frame_ms(&f);
            if i == 0 {
                self.fastest_ms = Some(ms);
            }
            measured.push(Measurement { terms, ms });
        }
        self.calibration = Calibration::warm_up(&CostModel::prior(), &measured)?;
        self.warmup_frames = measured.len();
        Ok(())
    }

    /// One frame within `target_ms`: searched, drawn, measured, and the
    /// measurement handed to the online correction.
    pub fn frame(&mut self, target_ms: f64) -> Result<Timed> {
        let target = TimeTarget::new(target_ms, self.options.budget_bytes)?;
        let started = Instant::now();
        let (field, scene, args) = (self.field, self.scene, self.args);
        let visible = crate::scene::visible(scene, self.isovalue);
        let shape = self.shape();
        let choice = select_for_time(
            &target,
            &mut self.selector,
            &scene.octree,
            &self.options,
            &visible,
            None,
            self.view,
            &self.calibration,
            shape,
            |s| plan_frame(field.shape(), scene, s, args, None).map(|p| p.list),
        )?;
        let search_ms = started.elapsed().as_secs_f64() * 1e3;
        let chosen = choice.chosen;
        let planned = Planned { list: chosen.value.list, slab_polygons_ms: 0.0, drawlist_ms: 0.0 };
        let frame = draw_frame(field, scene, planned, args, None)?;
        let ms = frame_ms(&frame);
        self.calibration.observe(&chosen.value.terms, ms);
        Ok(Timed {
            // The estimate as drawn: its slices widened or not.
            selection: Selection { estimated_rms_error: chosen.value.estimated_rms_error, ..chosen.value.selection },
            frame,
            target_ms,
            predicted_ms: chosen.predicted_ms,
            ms,
            budget_bytes: chosen.budget_bytes,
            slice_factor: chosen.slice_factor,
            outcome: choice.outcome,
            note: choice.note,
            search_ms,
            evaluations: choice.evaluations,
        })
    }
}
