//! Accuracy for time: the predicted time of a DrawList on the CPU
//! compositor and the selection of least error within a frame-time target.
//!
//! - [`terms`](CostTerms): what a DrawList asks of the compositor (bricks,
//!   samples on the slices of the pixels each brick covers, gradients,
//!   shadow rays, triangles, points, uploaded bytes);
//! - [`model`](CostModel): the predicted time, linear in the terms with
//!   non-negative coefficients (below);
//! - [`fit`](fit()): the coefficients fitted to warm-up frames measured on
//!   the running machine (non-negative least squares on relative errors,
//!   pulled towards a prior);
//! - [`online`](Calibration): the fitted model corrected from each measured
//!   frame (an exponentially weighted ratio measured / predicted);
//! - [`search`](search()): the budget bisected on the predicted time, the
//!   slices widened ([`widen_slices`]) when the coarsest selection misses;
//! - [`budget`](select_for_time): that search over a kept
//!   [`crate::plan::select::Selector`], which re-selects cheaply after a budget change;
//! - [`rank`](rank_correlation): how well the estimated error ranks frames by their measured RMSE.
//!
//! ```text
//! t = c0 + c_px pixels + c_b bricks + c_bp brick_pixels + c_s samples
//!        + c_g gradient_samples + c_sc scattering_samples
//!        + c_tri triangles + c_pt points + c_u upload_bytes        (ms)
//! ```
//!
//! Nothing here is the CLI's: a renderer keeps a [`Calibration`], measures
//! its frames and hands each to [`Calibration::observe`].

mod budget;
mod fit;
mod model;
mod online;
mod rank;
mod search;
mod terms;
mod widen;

#[cfg(test)]
mod tests;

pub use budget::{frame_rms_error, select_for_time, FrameShape, TimedFrame};
pub use fit::{fit, Measurement, PULL};
pub use model::CostModel;
pub use online::{Calibration, ALPHA, MAX_RATIO};
pub use rank::rank_correlation;
pub use search::{check_target_ms, search, Candidate, Choice, Outcome, TimeTarget, MAX_TARGET_MS};
pub use terms::{CostTerms, TERMS, TERM_NAMES};
pub use widen::widen_slices;
