//! The optimized low-resolution representation (paper 3, section 3.2):
//! "a parameter that specifies the minimum amount the low-resolution
//! representation can overestimate the original".
//!
//! The low-resolution volume is T_s of its lattice samples `v_c` (every `s`
//! samples, [`crate::octree::trilinear`]). Plain subsampling takes `v_c =
//! f(c)`. With an overestimation bound `b` (data units), every lattice value
//! is lowered to
//!
//! ```text
//! v_c = min( f(c),  min_{x in S(c)} f(x) + b ),    S(c) = { x : |x_a - c_a| < s on every axis }
//! ```
//!
//! `S(c)` holds every sample whose reconstruction uses `v_c`. T_s at a sample
//! `x` is a convex combination of the `v_c` of its cell's corners, each at most
//! `f(x) + b`, so
//!
//! ```text
//! T_s(x) - f(x) <= b      at every sample x
//! ```
//!
//! `b = 0` is the paper's "minimum function" (never overestimates); a large
//! `b` is plain subsampling. Since points only add opacity, a smaller `b`
//! turns overestimates (which no point corrects) into underestimates (which
//! points do), at the cost of more points.
//!
//! NaN is no data: the minimum skips it and a NaN lattice sample stays NaN
//! (the low resolution has the grid's holes).
//!
//! The result is a copy of the grid, `f32`, with the lattice samples lowered
//! (rounded down to `f32`) and the others kept: a uniform stride-`s`
//! selection of it textures exactly this low-resolution volume.

use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::data::volume::{SampleBuf, Volume};
use rayon::prelude::*;

/// The grid with its stride-`factor` lattice lowered so that T_factor never
/// overestimates it by more than `max_overestimate` (data units; see the
/// module documentation).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for a factor other than 2, 4 or 8 or a bound
/// that is negative or NaN.
pub fn low_resolution(grid: &Grid<'_>, factor: usize, max_overestimate: f64) -> Result<Volume> {
    if ![2, 4, 8].contains(&factor) {
        return Err(Error::InvalidArgument(format!(
            "the low-resolution factor {factor} is not supported: use 2, 4 or 8"
        )));
    }
    if max_overestimate.is_nan() || max_overestimate < 0.0 {
        return Err(Error::InvalidArgument(format!(
            "the overestimation bound {max_overestimate} must be zero or more (data units)"
        )));
    }
    let samples = grid.visit(Lower { factor, bound: max_overestimate });
    let shape = *grid.shape();
    Ok(Volume { samples: SampleBuf::F32(samples), shape, components: 1, name: "low resolution".into() })
}

struct Lower {
    factor: usize,
    bound: f64,
}

impl GridVisitor for Lower {
    type Output = Vec<f32>;

    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f32> {
        let [nx, ny, nz] = g.dims;
        let s = self.factor;
        let lattice = |c: usize, n: usize| c.is_multiple_of(s) || c == n - 1;
        let window = |c: usize, n: usize| c.saturating_sub(s - 1)..=(c + s - 1).min(n - 1);
        (0..nz)
            .into_par_iter()
            .flat_map_iter(|k| {
                let mut slice = Vec::with_capacity(nx * ny);
                for j in 0..ny {
                    for i in 0..nx {
                        let f = g.at(i, j, k);
                        if f.is_nan() || !(lattice(i, nx) && lattice(j, ny) && lattice(k, nz)) {
                            slice.push(f as f32);
                            continue;
                        }
                        let mut low = f64::INFINITY;
                        for z in window(k, nz) {
                            for y in window(j, ny) {
                                for x in window(i, nx) {
                                    low = low.min(g.at(x, y, z)); // f64::min skips NaN
                                }
                            }
                        }
                        slice.push(f32_at_most(f.min(low + self.bound)));
                    }
                }
                slice
            })
            .collect()
    }
}

/// The largest `f32` not above `v`.
fn f32_at_most(v: f64) -> f32 {
    let r = v as f32;
    if f64::from(r) > v {
        r.next_down()
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::trilinear;

    struct MaxOver<'a>(&'a Grid<'a>, usize);
    impl GridVisitor for MaxOver<'_> {
        type Output = f64;
        fn visit<T: Sample>(self, low: TypedGrid<'_, T>) -> f64 {
            let d = low.dims;
            let mut worst = f64::NEG_INFINITY;
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        worst = worst.max(trilinear::eval(&low, self.1, i, j, k) - self.0.value(i, j, k));
                    }
                }
            }
            worst
        }
    }

    #[test]
    fn the_bound_holds_at_every_sample() {
        let v = generate(Dataset::SheppLogan, 30, ScalarType::U8);
        let grid = v.grid(None).unwrap();
        for factor in [2, 4, 8] {
            let plain = low_resolution(&grid, factor, f64::INFINITY).unwrap();
            let plain_over = plain.grid(None).unwrap().visit(MaxOver(&grid, factor));
            assert!(plain_over > 10.0, "the phantom's edges are overestimated: {plain_over}");
            for bound in [0.0, 5.0, 20.0] {
                let low = low_resolution(&grid, factor, bound).unwrap();
                let over = low.grid(None).unwrap().visit(MaxOver(&grid, factor));
                assert!(over <= bound + 1e-9, "factor {factor} bound {bound}: overestimates by {over}");
            }
        }
        assert!(low_resolution(&grid, 3, 0.0).unwrap_err().to_string().contains("factor 3"));
        assert!(low_resolution(&grid, 2, -1.0).unwrap_err().to_string().contains("zero or more"));
    }
}
