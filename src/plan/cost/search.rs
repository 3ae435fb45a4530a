//! The search for the least error within a frame-time target.
//!
//! The predicted time of a frame grows with its texture budget over most of
//! the range (more bytes buy finer bricks: more bricks, more slices, more
//! samples), but not at its low end: the coarsest selection is one brick
//! whose trilinear field is visible everywhere, with no transparent brick
//! left out and no early ray termination, and can take longer than a finer
//! cut that skips the air. The estimated error falls with the budget, not
//! strictly either. So the search first scans the budget on a log scale
//! from the coarsest selection (`B_lo`) to the hard memory limit (`B_hi`),
//! then bisects next to the best scanned budget:
//!
//! ```text
//! t(B_hi) <= T                     -> B_hi: the full budget (Full)
//! scan B_i = B_lo (B_hi / B_lo)^(i / (n - 1)),  i = 0 .. n - 1        (n = scan_points)
//! B* = the scanned budget of least error with t(B*) <= T (ties: the larger)
//! bisect between B* and the next scanned budget B+ (t(B+) > T):
//!     B = sqrt(B* B+); B* = B if t(B) <= T (kept when its error is no larger) else B+ = B,
//!     until B+ / B* <= 1 + resolution or the steps run out      (Met)
//! no scanned budget fits at any factor m -> the fastest predicted candidate at the widest slices (BelowFastest)
//! ```
//!
//! `t` the calibrated prediction. When no scanned budget fits, bytes alone
//! cannot meet the target: the slices are widened, `m = 2, 4, ...` up to
//! [`TimeTarget::max_slice_factor`] (every brick sliced at least `m d0`
//! apart, [`super::widen`]), and the scan and bisection run again at the
//! first `m` where a budget fits. The predictions never rise as the
//! slices widen, so the widest `m` is scanned right after `m = 1`: when
//! no budget fits there either, the target is below the fastest frame
//! without the spacings between.

use crate::base::error::{Error, Result};

/// The largest frame-time target, ms (ten minutes).
pub const MAX_TARGET_MS: f64 = 600_000.0;

/// What the search looks for and within what.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TimeTarget {
    /// The frame time to meet, ms.
    pub target_ms: f64,
    /// The smallest budget tried, bytes (1: the coarsest selection).
    pub min_budget_bytes: usize,
    /// The hard memory limit, bytes.
    pub max_budget_bytes: usize,
    /// The widest slices, in multiples of `d0` (a power of two; 1: never widened).
    pub max_slice_factor: u32,
    /// Bisection stops when the budgets bracketing the target are within this ratio of each other, minus 1.
    pub resolution: f64,
    /// At most this many evaluations in one bisection.
    pub max_steps: usize,
    /// Budgets scanned before the bisection (at least 2: the ends).
    pub scan_points: usize,
}

impl TimeTarget {
    /// A target of `target_ms` (checked, [`check_target_ms`]) under the
    /// memory limit `max_budget_bytes` (at least 1): budgets from 1 byte,
    /// 12 scanned, slices widened up to 8 times, bisected to 2 %, in at most 12 steps.
    pub fn new(target_ms: f64, max_budget_bytes: usize) -> Result<TimeTarget> {
        Ok(TimeTarget {
            target_ms: check_target_ms(target_ms)?,
            min_budget_bytes: 1,
            max_budget_bytes: max_budget_bytes.max(1),
            max_slice_factor: 8,
            resolution: 0.02,
            max_steps: 12,
            scan_points: 12,
        })
    }
}

/// `ms` when it is a usable frame-time target: finite, above 0 and at most
/// [`MAX_TARGET_MS`]; else an error naming the problem and the fix.
pub fn check_target_ms(ms: f64) -> Result<f64> {
    if ms.is_finite() && ms > 0.0 && ms <= MAX_TARGET_MS {
        return Ok(ms);
    }
    let problem = if ms.is_nan() {
        "is not a number".to_string()
    } else if ms <= 0.0 {
        "is not above 0".to_string()
    } else {
        format!("is above {MAX_TARGET_MS} ms (ten minutes)")
    };
    Err(Error::InvalidArgument(format!(
        "frame-time target {ms} ms {problem}: give milliseconds above 0 and at most {MAX_TARGET_MS} (e.g. 50)"
    )))
}

/// How the choice relates to the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// The predicted time is within the target, the budget bisected to it.
    Met,
    /// The full budget is predicted within the target.
    Full,
    /// Even the coarsest selection at the widest slices is predicted above the target.
    BelowFastest,
}

impl Outcome {
    /// Its name in reports: `met`, `full`, `below-fastest`.
    pub fn name(&self) -> &'static str {
        match self {
            Outcome::Met => "met",
            Outcome::Full => "full",
            Outcome::BelowFastest => "below-fastest",
        }
    }
}

/// One evaluated candidate.
#[derive(Debug, Clone)]
pub struct Candidate<T> {
    /// What the caller made for it (a selection and its DrawList).
    pub value: T,
    /// The budget it was selected under, bytes.
    pub budget_bytes: usize,
    /// Its slices' least spacing in multiples of `d0` (1: the strides').
    pub slice_factor: u32,
    /// Its predicted time, ms.
    pub predicted_ms: f64,
    /// Its estimated error.
    pub error: f64,
}

/// What the search chose.
#[derive(Debug, Clone)]
pub struct Choice<T> {
    /// The candidate.
    pub chosen: Candidate<T>,
    /// How it relates to the target.
    pub outcome: Outcome,
    /// Candidates evaluated.
    pub evaluations: usize,
    /// Said when the target is below the fastest frame.
    pub note: Option<String>,
}

/// The candidate of least error within `target` (see the module
/// documentation). `eval(budget, slice_factor)` makes a candidate and
/// returns it with its predicted time and estimated error; a prediction
/// that is not a number counts as missing the target.
pub fn search<T>(target: &TimeTarget, mut eval: impl FnMut(usize, u32) -> Result<(T, f64, f64)>) -> Result<Choice<T>> {
    let target_ms = check_target_ms(target.target_ms)?;
    let hi = target.max_budget_bytes.max(1);
    let lo = target.min_budget_bytes.clamp(1, hi);
    let mut evaluations = 0;
    let mut run = |budget: usize, factor: u32| -> Result<Candidate<T>> {
        evaluations += 1;
        let (value, predicted_ms, error) = eval(budget, factor)?;
        Ok(Candidate { value, budget_bytes: budget, slice_factor: factor, predicted_ms, error })
    };
    let fits = |c: &Candidate<T>| c.predicted_ms <= target_ms;
    let full = run(hi, 1)?;
    if fits(&full) {
        return Ok(Choice { chosen: full, outcome: Outcome::Full, evaluations, note: None });
    }
    let budgets = scan(lo, hi, target.scan_points);
    let widest = target.max_slice_factor.max(1);
    let mut factor = 1u32;
    // The widest spacing's scan, when made out of turn.
    let mut widest_scan: Option<Vec<Candidate<T>>> = None;
    loop {
        let mut scanned = match widest_scan.take().filter(|_| factor == widest) {
            Some(kept) => kept,
            None => budgets.iter().map(|&b| run(b, factor)).collect::<Result<Vec<_>>>()?,
        };
        let best = (0..scanned.len()).filter(|&i| fits(&scanned[i])).fold(None, |best: Option<usize>, i| match best {
            Some(j) if !(scanned[i].error <= scanned[j].error || scanned[j].error.is_nan()) => Some(j),
            _ => Some(i),
        });
        if let Some(i) = best {
            let above = scanned.get(i + 1).filter(|c| !fits(c)).map(|c| c.budget_bytes);
            let mut best = scanned.swap_remove(i);
            drop(scanned);
            if let Some(above) = above {
                let (mut a, mut b) = (best.budget_bytes as f64, above as f64);
                for _ in 0..target.max_steps {
                    if b <= a * (1.0 + target.resolution.max(1e-6)) {
                        break;
                    }
                    let mid = (a * b).sqrt().round();
                    if mid <= a || mid >= b {
                        break;
                    }
                    let c = run(mid as usize, factor)?;
                    if fits(&c) {
                        a = mid;
                        if c.error <= best.error || best.error.is_nan() {
                            best = c;
                        }
                    } else {
                        b = mid;
                    }
                }
            }
            return Ok(Choice { chosen: best, outcome: Outcome::Met, evaluations, note: None });
        }
        let mut next = factor.saturating_mul(2);
        if factor == 1 && next < widest {
            // Nothing fits at the strides' spacing. A prediction never rises
            // as the slices widen (fewer samples, non-negative
            // coefficients), so when nothing fits at the widest spacing
            // either, nothing fits between: scan it first.
            let at_widest = budgets.iter().map(|&b| run(b, widest)).collect::<Result<Vec<_>>>()?;
            if !at_widest.iter().any(fits) {
                (scanned, factor, next) = (at_widest, widest, widest.saturating_mul(2));
            } else {
                widest_scan = Some(at_widest);
            }
        }
        if next > widest {
            let fastest = (0..scanned.len())
                .reduce(|j, i| if scanned[i].predicted_ms < scanned[j].predicted_ms { i } else { j })
                .unwrap_or(0);
            let Some(lower) = (fastest < scanned.len()).then(|| scanned.swap_remove(fastest)) else {
                return Err(Error::Internal("the time search scanned no budget".into()));
            };
            let note = format!(
                "the frame-time target {target_ms} ms is below the fastest frame: the fastest selection{} is \
                 predicted at {:.1} ms; it is drawn, over the target",
                if factor > 1 { format!(" with slices {factor} times wider") } else { String::new() },
                lower.predicted_ms
            );
            return Ok(Choice { chosen: lower, outcome: Outcome::BelowFastest, evaluations, note: Some(note) });
        }
        factor = next;
    }
}

/// `n` (at least 2) budgets from `lo` to `hi` on a log scale, ascending, without repeats.
fn scan(lo: usize, hi: usize, n: usize) -> Vec<usize> {
    let n = n.max(2);
    let mut v: Vec<usize> = (0..n)
        .map(|i| {
            let r = i as f64 / (n - 1) as f64;
            ((lo as f64) * (hi as f64 / lo as f64).powf(r)).round() as usize
        })
        .map(|b| b.clamp(lo, hi))
        .collect();
    v.dedup();
    v
}
