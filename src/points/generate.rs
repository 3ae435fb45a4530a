//! Point generation (paper 3, section 3.1): the error grid of the
//! low-resolution volume's trilinear reconstruction, and points where it is
//! large.
//!
//! For a grid `f` and factor `s`, the low-resolution volume is T_s (the grid
//! every `s` samples, see [`crate::octree::trilinear`]: what a uniform
//! stride-`s` texture holds and the renderer interpolates). At every sample
//!
//! ```text
//! e(x) = f(x) - T_s(x)
//! ```
//!
//! and a point is inserted where `|e(x)| > threshold * (max f - min f)`
//! ([`PointSelect::Threshold`]), or at the `K` samples of largest `|e|`
//! ([`PointSelect::Budget`]; ties by grid order); with
//! [`PointOptions::underestimates_only`], only where `e > 0`. Samples where `e = 0` (the
//! low-resolution samples themselves among them) never get a point. Each
//! point keeps its value, its error and the direction of the central-
//! difference gradient of `f` (the shading normal), quantised as
//! [`super::Point`] says. NaN is no data: where `f` or `T_s` is NaN, `e` is
//! NaN and no point is made (no comparison holds for NaN), and the gradient
//! leaves NaN neighbours out. Slices of the grid run in parallel and are joined
//! in grid order, so the points do not depend on the number of threads.

use super::lowres::low_resolution;
use super::normals;
use super::set::{Point, PointSet};
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::data::volume::Volume;
use crate::octree::trilinear;
use rayon::prelude::*;

/// Which samples become points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointSelect {
    /// `|e| > threshold * data range` (threshold in `[0, 1]`).
    Threshold(f64),
    /// The `K` largest `|e|` (a point budget).
    Budget(usize),
}

/// What to generate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointOptions {
    /// Low-resolution factor: 2, 4 or 8.
    pub factor: usize,
    /// Which samples become points.
    pub select: PointSelect,
    /// Only where the low resolution underestimates (`e > 0`). Points only
    /// add opacity (paper 3, sections 3.2 and 4.1), so under a transfer
    /// function whose opacity grows with the value a point where `e < 0`
    /// changes nothing; this spends a point budget on the points that can.
    /// Off: the paper's `|e|`.
    pub underestimates_only: bool,
    /// The optimized representation's bound (paper 3, section 3.2): the low
    /// resolution may overestimate the data by at most this fraction of the
    /// data range ([`super::lowres`]); `None`: plain subsampling.
    pub max_overestimate: Option<f64>,
}

impl PointOptions {
    /// Factor `factor`, points chosen by `select` on `|e|` (the paper's rule).
    pub fn new(factor: usize, select: PointSelect) -> PointOptions {
        PointOptions { factor, select, underestimates_only: false, max_overestimate: None }
    }
}

/// The points completing T_`factor` of `grid` (see the module
/// documentation), and, with [`PointOptions::max_overestimate`], the
/// optimized low-resolution volume they complete (textures must then be
/// made from it, not from `grid`).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for a factor other than 2, 4 or 8, a factor
/// not smaller than every axis, a threshold or bound outside `[0, 1]`, or an
/// axis of more than 65,536 samples.
pub fn generate_hybrid(grid: &Grid<'_>, options: &PointOptions) -> Result<(PointSet, Option<Volume>)> {
    check(grid, options)?;
    let (lo, hi) = value_range(grid);
    let low = match options.max_overestimate {
        Some(b) if (0.0..=1.0).contains(&b) => Some(low_resolution(grid, options.factor, b * (hi - lo))?),
        Some(b) => {
            return Err(Error::InvalidArgument(format!(
                "the overestimation bound {b} is not a fraction of the data range: use a value in [0, 1]"
            )))
        }
        None => None,
    };
    let low_grid = low.as_ref().map(|v| v.grid(None)).transpose()?;
    let mut set = grid.visit(Generate { options: *options, range: (lo, hi), low: low_grid.as_ref() })?;
    set.max_overestimate = options.max_overestimate.map_or(f64::INFINITY, |b| b * (hi - lo));
    Ok((set, low))
}

/// The points completing plain T_`factor` of `grid` ([`generate_hybrid`]
/// without [`PointOptions::max_overestimate`]).
///
/// # Errors
///
/// As [`generate_hybrid`], and when `options` asks for the optimized
/// representation (use [`generate_hybrid`], which returns its volume).
pub fn generate(grid: &Grid<'_>, options: &PointOptions) -> Result<PointSet> {
    if options.max_overestimate.is_some() {
        return Err(Error::InvalidArgument(
            "the optimized representation changes the low-resolution volume: use generate_hybrid, which returns it"
                .into(),
        ));
    }
    Ok(generate_hybrid(grid, options)?.0)
}

/// The options checked against the grid.
fn check(grid: &Grid<'_>, options: &PointOptions) -> Result<()> {
    let dims = grid.dims();
    let s = options.factor;
    if ![2, 4, 8].contains(&s) {
        return Err(Error::InvalidArgument(format!("the low-resolution factor {s} is not supported: use 2, 4 or 8")));
    }
    if dims.iter().any(|&n| n <= s) {
        return Err(Error::InvalidArgument(format!(
            "a {}x{}x{} grid is too small for factor {s}: every axis needs more than {s} samples",
            dims[0], dims[1], dims[2]
        )));
    }
    if dims.iter().any(|&n| n > 1 << 16) {
        return Err(Error::InvalidArgument(format!(
            "a {}x{}x{} grid has an axis over 65,536 samples: point coordinates are 16 bits; crop the grid",
            dims[0], dims[1], dims[2]
        )));
    }
    if let PointSelect::Threshold(t) = options.select {
        if !(0.0..=1.0).contains(&t) {
            return Err(Error::InvalidArgument(format!(
                "the point threshold {t} is not a fraction of the data range: use a value in [0, 1]"
            )));
        }
    }
    Ok(())
}

/// Smallest and largest sample, in parallel by z slices.
fn value_range(grid: &Grid<'_>) -> (f64, f64) {
    let d = grid.dims();
    (0..d[2])
        .into_par_iter()
        .map(|k| {
            let mut r = (f64::INFINITY, f64::NEG_INFINITY);
            for j in 0..d[1] {
                for i in 0..d[0] {
                    let v = grid.value(i, j, k);
                    r = (r.0.min(v), r.1.max(v));
                }
            }
            r
        })
        .reduce(|| (f64::INFINITY, f64::NEG_INFINITY), |a, b| (a.0.min(b.0), a.1.max(b.1)))
}

/// T_s at sample `(i, j, k)` of the samples `at` gives: the formula and
/// evaluation order of [`trilinear::eval`] (bracket, then z, y, x lerps).
fn t_s(at: impl Fn(usize, usize, usize) -> f64, dims: [usize; 3], s: usize, i: usize, j: usize, k: usize) -> f64 {
    let (x0, x1, tx) = trilinear::bracket(i, s, dims[0]);
    let (y0, y1, ty) = trilinear::bracket(j, s, dims[1]);
    let (z0, z1, tz) = trilinear::bracket(k, s, dims[2]);
    let w = |xa| {
        let v0 = trilinear::lerp(at(xa, y0, z0), at(xa, y0, z1), tz);
        let v1 = trilinear::lerp(at(xa, y1, z0), at(xa, y1, z1), tz);
        trilinear::lerp(v0, v1, ty)
    };
    trilinear::lerp(w(x0), w(x1), tx)
}

struct Generate<'a> {
    options: PointOptions,
    /// The data range.
    range: (f64, f64),
    /// The optimized low-resolution volume, if any (else T_s of the grid itself).
    low: Option<&'a Grid<'a>>,
}

/// A candidate: `|e|`, its linear sample index, `e`.
type Candidate = (f64, usize, f64);

impl GridVisitor for Generate<'_> {
    type Output = Result<PointSet>;

    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Result<PointSet> {
        let dims = g.dims;
        let s = self.options.factor;
        let (lo, hi) = self.range;
        let low = self.low;
        let approx = |i, j, k| match low {
            Some(l) => t_s(|x, y, z| l.value(x, y, z), dims, s, i, j, k),
            None => trilinear::eval(&g, s, i, j, k),
        };
        let floor = match self.options.select {
            PointSelect::Threshold(t) => t * (hi - lo),
            PointSelect::Budget(_) => 0.0,
        };
        // Candidates per z slice, joined in grid order.
        let mut candidates: Vec<Candidate> = (0..dims[2])
            .into_par_iter()
            .flat_map_iter(|k| {
                let mut out = Vec::new();
                for j in 0..dims[1] {
                    for i in 0..dims[0] {
                        let e = g.at(i, j, k) - approx(i, j, k);
                        if e.abs() > floor && (e > 0.0 || !self.options.underestimates_only) {
                            out.push((e.abs(), i + dims[0] * (j + dims[1] * k), e));
                        }
                    }
                }
                out
            })
            .collect();
        if let PointSelect::Budget(budget) = self.options.select {
            if candidates.len() > budget {
                // Largest |e| first, ties by grid order: a total order, so the K chosen are unique.
                let order = |a: &Candidate, b: &Candidate| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1));
                if budget > 0 {
                    candidates.select_nth_unstable_by(budget - 1, order);
                }
                candidates.truncate(budget);
                candidates.sort_by_key(|c| c.1);
            }
        }
        let error_scale = candidates.iter().map(|c| c.0).fold(0.0, f64::max);
        let range = hi - lo;
        let points = candidates
            .par_iter()
            .map(|&(_, index, e)| {
                let ijk = [index % dims[0], index / dims[0] % dims[1], index / (dims[0] * dims[1])];
                let value = g.at(ijk[0], ijk[1], ijk[2]);
                Point {
                    ijk: ijk.map(|c| c as u16),
                    normal: normals::quantise(gradient(&g, ijk)),
                    error: if error_scale > 0.0 { (e / error_scale * 127.0).round() as i8 } else { 0 },
                    value: if range > 0.0 { ((value - lo) / range * 255.0).round() as u8 } else { 0 },
                }
            })
            .collect();
        Ok(PointSet { dims, factor: s, value_range: [lo, hi], error_scale, max_overestimate: f64::INFINITY, points })
    }
}

/// Central differences (one-sided at the grid's faces and beside a NaN
/// neighbour, 0 with NaN on both sides), in index space.
fn gradient<T: Sample>(g: &TypedGrid<'_, T>, ijk: [usize; 3]) -> [f64; 3] {
    let at = |p: [usize; 3]| g.at(p[0], p[1], p[2]);
    std::array::from_fn(|a| {
        let mut lo = ijk;
        let mut hi = ijk;
        lo[a] = ijk[a].saturating_sub(1);
        hi[a] = (ijk[a] + 1).min(g.dims[a] - 1);
        if at(lo).is_nan() {
            lo = ijk;
        }
        if at(hi).is_nan() {
            hi = ijk;
        }
        if hi[a] == lo[a] {
            return 0.0;
        }
        (at(hi) - at(lo)) / (hi[a] - lo[a]) as f64
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate as dataset, Dataset};

    fn options(select: PointSelect) -> PointOptions {
        PointOptions::new(2, select)
    }

    #[test]
    fn points_sit_where_the_low_resolution_error_exceeds_the_threshold() {
        let v = dataset(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let set = generate(&grid, &options(PointSelect::Threshold(0.1))).unwrap();
        assert!(!set.points.is_empty());
        let range = set.value_range[1] - set.value_range[0];
        let exact = |p: &Point| {
            let [i, j, k] = p.ijk.map(usize::from);
            grid.value(i, j, k)
        };
        for p in &set.points {
            // Every point's error exceeds the threshold, and its stored value is within half a quantisation step.
            assert!(set.error(p).abs() > 0.1 * range - set.error_scale / 254.0, "{p:?}");
            assert!((set.value(p) - exact(p)).abs() <= range / 510.0 + 1e-12);
            // Low-resolution samples (even coordinates on every axis) are reconstructed exactly: no point.
            assert!(p.ijk.iter().any(|c| c % 2 == 1), "a point on a low-resolution sample: {p:?}");
        }
        // A lower threshold keeps every point of a higher one.
        let more = generate(&grid, &options(PointSelect::Threshold(0.05))).unwrap();
        assert!(more.points.len() > set.points.len());
        assert!(set.points.iter().all(|p| more.points.iter().any(|q| q.ijk == p.ijk)));
    }

    #[test]
    fn a_budget_keeps_the_largest_errors_and_is_deterministic() {
        let v = dataset(Dataset::MarschnerLobb, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let all = generate(&grid, &options(PointSelect::Threshold(0.0))).unwrap();
        let some = generate(&grid, &options(PointSelect::Budget(500))).unwrap();
        assert_eq!(some.points.len(), 500);
        assert_eq!(some.error_scale, all.error_scale, "the largest error is always kept");
        // Same points on one thread and on all.
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        assert_eq!(pool.install(|| generate(&grid, &options(PointSelect::Budget(500))).unwrap()), some);
        let none = generate(&grid, &options(PointSelect::Budget(0))).unwrap();
        assert!(none.points.is_empty());
    }

    #[test]
    fn constant_fields_need_no_points_and_bad_options_are_clear_errors() {
        let v = dataset(Dataset::SheppLogan, 17, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        for (factor, select, says) in [
            (3, PointSelect::Threshold(0.1), "factor 3"),
            (2, PointSelect::Threshold(1.5), "threshold 1.5"),
            (2, PointSelect::Threshold(f64::NAN), "threshold NaN"),
        ] {
            let e = generate(&grid, &PointOptions::new(factor, select)).unwrap_err().to_string();
            assert!(e.contains(says), "{e}");
        }
        let small = dataset(Dataset::SheppLogan, 5, ScalarType::F32);
        let e = generate(&small.grid(None).unwrap(), &PointOptions::new(8, PointSelect::Budget(1)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("too small"), "{e}");
        let flat = vec![2.5f32; 9 * 9 * 9];
        let g = Grid::scalar(crate::data::grid::Samples::F32(&flat), [9, 9, 9]).unwrap();
        let set = generate(&g, &PointOptions::new(4, PointSelect::Threshold(0.0))).unwrap();
        assert!(set.points.is_empty() && set.error_scale == 0.0);
    }

    #[test]
    fn the_optimized_representation_turns_overestimates_into_points() {
        let v = dataset(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let plain = generate(&grid, &options(PointSelect::Threshold(0.05))).unwrap();
        let opts = PointOptions { max_overestimate: Some(0.02), ..options(PointSelect::Threshold(0.05)) };
        let (set, low) = generate_hybrid(&grid, &opts).unwrap();
        assert!(low.is_some());
        let range = set.value_range[1] - set.value_range[0];
        assert!((set.max_overestimate - 0.02 * range).abs() < 1e-12);
        // No point's error is below -bound (it would be an overestimate beyond it).
        assert!(set.points.iter().all(|p| set.error(p) >= -0.02 * range - set.error_scale / 254.0));
        assert!(plain.points.iter().any(|p| plain.error(p) < -0.02 * range), "plain has large overestimates");
        assert!(generate(&grid, &opts).unwrap_err().to_string().contains("generate_hybrid"));
        let bad = PointOptions { max_overestimate: Some(2.0), ..opts };
        assert!(generate_hybrid(&grid, &bad).unwrap_err().to_string().contains("bound 2"));
    }

    #[test]
    fn extreme_fields_give_finite_points_and_nan_gives_none() {
        // A checkerboard of +-1e30 on odd samples: every odd sample is off by 1e30 from T_2.
        let n = 9;
        let data: Vec<f64> = (0..n * n * n)
            .map(|i| {
                let (x, y, z) = (i % n, i / n % n, i / (n * n));
                if x % 2 == 1 && y % 2 == 1 && z % 2 == 1 {
                    if (x + y + z) % 4 == 1 {
                        1e30
                    } else {
                        -1e30
                    }
                } else {
                    0.0
                }
            })
            .collect();
        let g = Grid::scalar(crate::data::grid::Samples::F64(&data), [n; 3]).unwrap();
        let set = generate(&g, &options(PointSelect::Threshold(0.1))).unwrap();
        assert_eq!(set.points.len(), 4 * 4 * 4, "every odd sample");
        assert!(set.error_scale.is_finite() && set.points.iter().all(|p| set.value(p).is_finite()));
        assert!(set.points.iter().all(|p| (set.value(p).abs() - 1e30).abs() < 1e28));
        // A NaN lattice sample (4, 0, 0) is a corner of T_2 at (3, 1, 1) and (5, 1, 1): no data, no point.
        let mut holed = data.clone();
        holed[4] = f64::NAN;
        let g = Grid::scalar(crate::data::grid::Samples::F64(&holed), [n; 3]).unwrap();
        let set = generate(&g, &options(PointSelect::Threshold(0.1))).unwrap();
        assert_eq!(set.points.len(), 4 * 4 * 4 - 2);
        assert!(set.points.iter().all(|p| p.ijk[1] != 1 || p.ijk[2] != 1 || ![3, 5].contains(&p.ijk[0])));
        assert!(set.error_scale.is_finite() && set.points.iter().all(|p| set.value(p).is_finite()));
    }

    #[test]
    fn underestimates_only_keeps_the_points_of_positive_error() {
        let v = dataset(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let all = generate(&grid, &options(PointSelect::Threshold(0.05))).unwrap();
        let under =
            generate(&grid, &PointOptions { underestimates_only: true, ..options(PointSelect::Threshold(0.05)) })
                .unwrap();
        assert!(!under.points.is_empty() && under.points.len() < all.points.len());
        assert!(under.points.iter().all(|p| p.error > 0));
        let budget =
            generate(&grid, &PointOptions { underestimates_only: true, ..options(PointSelect::Budget(50)) }).unwrap();
        assert_eq!(budget.points.len(), 50);
        assert!(budget.points.iter().all(|p| p.error > 0));
    }
}
