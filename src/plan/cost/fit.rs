//! Calibration: the cost model's coefficients fitted to measured frames.
//!
//! Each coefficient is the prior's times a gain, `c_k = g_k p_k`, and the
//! gains minimise the relative error of the measured times `t_i` plus a
//! pull towards the prior:
//!
//! ```text
//! minimise  sum_i (sum_k g_k p_k x_ik / t_i - 1)^2  +  lambda sum_k (g_k - 1)^2,   g_k >= 0
//! ```
//!
//! (non-negative least squares, solved by projected coordinate descent on
//! its normal equations). Relative errors weigh a 20 ms frame as much as a
//! 200 ms one; the pull (`lambda` = [`PULL`]) decides the terms the frames
//! do not tell apart (a term that never varies, or two that vary together,
//! as the constant and the pixels at one image size) and leaves a term
//! without data at its prior. Measurements that are not finite, not
//! positive, or whose terms are not are left out.

use super::model::CostModel;
use super::terms::{CostTerms, TERMS};
use crate::base::error::{Error, Result};

/// The pull towards the prior, per gain.
pub const PULL: f64 = 1e-3;

/// Sweeps of coordinate descent (the system is at most [`TERMS`] wide).
const SWEEPS: usize = 2000;

/// One measured frame: its terms and its time, ms.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Measurement {
    /// The frame's terms.
    pub terms: CostTerms,
    /// Its measured time, ms.
    pub ms: f64,
}

impl Measurement {
    /// Whether it can be fitted: a finite positive time and valid terms.
    pub fn is_usable(&self) -> bool {
        self.ms.is_finite() && self.ms > 0.0 && self.terms.is_valid()
    }
}

/// `prior` fitted to `frames` (see the module documentation); an error when
/// no frame is usable.
pub fn fit(prior: &CostModel, frames: &[Measurement]) -> Result<CostModel> {
    let p = prior.coefficients();
    let rows: Vec<[f64; TERMS]> = frames
        .iter()
        .filter(|m| m.is_usable())
        .map(|m| {
            let x = m.terms.as_array();
            std::array::from_fn(|k| x[k] * p[k] / m.ms)
        })
        .collect();
    if rows.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "cost model: none of the {} measured frames has a finite positive time: measure at least one frame",
            frames.len()
        )));
    }
    // Normal equations (A^T A + lambda I) g = A^T 1 + lambda 1.
    let mut m = [[0.0; TERMS]; TERMS];
    let mut b = [PULL; TERMS];
    for r in &rows {
        for i in 0..TERMS {
            b[i] += r[i];
            for j in 0..TERMS {
                m[i][j] += r[i] * r[j];
            }
        }
    }
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += PULL;
    }
    let mut g = [1.0; TERMS];
    for _ in 0..SWEEPS {
        let mut moved = 0.0f64;
        for i in 0..TERMS {
            let rest: f64 = (0..TERMS).filter(|&j| j != i).map(|j| m[i][j] * g[j]).sum();
            let next = ((b[i] - rest) / m[i][i]).max(0.0);
            moved = moved.max((next - g[i]).abs());
            g[i] = next;
        }
        if moved < 1e-12 {
            break;
        }
    }
    let fitted: [f64; TERMS] = std::array::from_fn(|k| g[k] * p[k]);
    // All gains 0 cannot fit positive times; the prior then stands.
    CostModel::new(fitted).or(Ok(*prior))
}
