//! The cost model: the predicted time of a DrawList on the CPU compositor,
//! linear in its terms ([`CostTerms`]):
//!
//! ```text
//! t = c0 + c_px pixels + c_b bricks + c_bp brick_pixels + c_s samples
//!        + c_g gradient_samples + c_sc scattering_samples
//!        + c_tri triangles + c_pt points + c_u upload_bytes        (ms)
//! ```
//!
//! Every coefficient is finite and non-negative (more work never takes less
//! time) and at least one is positive. [`CostModel::prior`] is a starting
//! point measured on a 2-core machine; [`super::fit`] calibrates it on the
//! running one.

use super::terms::{CostTerms, TERMS, TERM_NAMES};
use crate::base::error::{Error, Result};

/// The coefficients of the model, ms per unit of each term (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CostModel {
    coefficients: [f64; TERMS],
}

impl CostModel {
    /// A model of these coefficients (the order of [`TERM_NAMES`]): refused
    /// when one is negative or not finite, or all are 0.
    pub fn new(coefficients: [f64; TERMS]) -> Result<CostModel> {
        if let Some(k) = coefficients.iter().position(|c| !(c.is_finite() && *c >= 0.0)) {
            return Err(Error::InvalidArgument(format!(
                "cost model: the coefficient of '{}' is {}: give a finite number of at least 0 (more work never \
                 takes less time)",
                TERM_NAMES[k], coefficients[k]
            )));
        }
        if coefficients.iter().all(|&c| c == 0.0) {
            return Err(Error::InvalidArgument(
                "cost model: every coefficient is 0, so every frame would take no time: give at least one positive \
                 coefficient"
                    .into(),
            ));
        }
        Ok(CostModel { coefficients })
    }

    /// The starting model before calibration, ms per unit: about what the
    /// CPU compositor took on 2 cores (a frame 0.5 ms, a pixel 20 ns, a
    /// brick 2 us, a brick's pixel ray test 10 ns, a sample 12 ns, a
    /// gradient 15 ns, a shadow ray 400 ns, a triangle 200 ns, a point
    /// 100 ns, an uploaded byte 0.2 ns).
    pub fn prior() -> CostModel {
        CostModel { coefficients: [0.5, 2e-5, 2e-3, 1e-5, 1.2e-5, 1.5e-5, 4e-4, 2e-4, 1e-4, 2e-7] }
    }

    /// The coefficients, in the order of [`TERM_NAMES`].
    pub fn coefficients(&self) -> [f64; TERMS] {
        self.coefficients
    }

    /// The predicted time of a frame of these terms, ms: `sum_k c_k x_k`.
    pub fn predict(&self, terms: &CostTerms) -> f64 {
        terms.as_array().iter().zip(&self.coefficients).map(|(x, c)| x * c).sum()
    }
}
