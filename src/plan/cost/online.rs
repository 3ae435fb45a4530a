//! The online correction: each measured frame moves the prediction towards
//! what the machine does now (other work on the cores, caches, turbo).
//!
//! ```text
//! r_0 = 1,   r_(n+1) = r_n exp(alpha clamp(ln(t_n / (r_n m_n)), -ln 2, ln 2))
//! predicted(x) = r m(x)
//! ```
//!
//! `m(x)` the calibrated model's time, `t_n` the measured one: an
//! exponentially weighted mean of the log ratio measured / predicted, each
//! frame moving it by at most a factor of 2 (one frame that a other process
//! stalled does not throw the next ones off), `r` kept within
//! `[1/`[`MAX_RATIO`]`, `[`MAX_RATIO`]`]`. A measurement that is not finite
//! or not positive, or a prediction that is not, changes nothing.

use super::fit::{fit, Measurement};
use super::model::CostModel;
use super::terms::CostTerms;
use crate::base::error::Result;

/// The largest correction, either way.
pub const MAX_RATIO: f64 = 16.0;

/// The weight of the newest frame.
pub const ALPHA: f64 = 0.3;

/// A calibrated cost model and its online correction.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Calibration {
    model: CostModel,
    ratio: f64,
    frames: usize,
}

impl Calibration {
    /// `model` without correction.
    pub fn new(model: CostModel) -> Calibration {
        Calibration { model, ratio: 1.0, frames: 0 }
    }

    /// The prior fitted to the warm-up frames (see [`fit`]), without correction.
    pub fn warm_up(prior: &CostModel, frames: &[Measurement]) -> Result<Calibration> {
        fit(prior, frames).map(Calibration::new)
    }

    /// The calibrated model.
    pub fn model(&self) -> &CostModel {
        &self.model
    }

    /// The correction `r`: measured over modelled time, as the frames so far say.
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    /// Frames that corrected it.
    pub fn corrections(&self) -> usize {
        self.frames
    }

    /// The predicted time of a frame of `terms`, ms: `r m(x)`.
    pub fn predict(&self, terms: &CostTerms) -> f64 {
        self.ratio * self.model.predict(terms)
    }

    /// Corrects the prediction by a frame of `terms` measured at `ms`
    /// (ignored when either time is not finite and positive).
    pub fn observe(&mut self, terms: &CostTerms, ms: f64) {
        let modelled = self.model.predict(terms);
        if !(ms.is_finite() && ms > 0.0 && modelled.is_finite() && modelled > 0.0) {
            return;
        }
        let step = (ms / (self.ratio * modelled)).ln().clamp(-std::f64::consts::LN_2, std::f64::consts::LN_2);
        self.ratio = (self.ratio * (ALPHA * step).exp()).clamp(1.0 / MAX_RATIO, MAX_RATIO);
        self.frames += 1;
    }
}
