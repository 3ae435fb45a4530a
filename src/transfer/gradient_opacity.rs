//! Gradient opacity (vtkVolumeProperty's GradientOpacity): a piecewise-linear
//! function of the gradient magnitude that multiplies a sample's scalar
//! opacity, so that homogeneous regions fade and boundaries stay.
//!
//! Its points `(g_i, a_i)` are sorted by gradient magnitude; between two
//! points it is linear, outside the end points it keeps the end value
//! (vtkPiecewiseFunction with clamping, as [`super::function`]). `g` is the
//! magnitude of the gradient of the field, data units per world unit:
//!
//! ```text
//! |g| = |grad F|,   grad F from central differences (crate::render::shade's rule)
//! a   = a_scalar(v) * a_grad(|g|)      the opacity of a layer one reference spacing d0 thick,
//! a'  = 1 - (1 - a)^(d / d0)           then corrected for the slice spacing d
//! ```
//!
//! A magnitude that is not a number (a difference touching no data) counts
//! as 0, as the shading takes a zero normal there.
//!
//! VTK 9.2's GPU ray caster measures the gradient per average voxel
//! (`|g| avg(spacing)`), clamps it to a quarter of the scalar range and
//! multiplies the opacity after its sample-distance correction
//! ([`GradientOpacity::from_vtk`] takes the first two; the correction order
//! differs only at second order in the opacity). Only Composite uses it.

use crate::base::error::{Error, Result};

/// A gradient opacity function (see the module documentation).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct GradientOpacity {
    points: Vec<(f64, f32)>,
}

impl GradientOpacity {
    /// A function from points `(gradient magnitude, opacity)`: at least one,
    /// magnitudes finite and non-decreasing, opacities in `[0, 1]`.
    pub fn new(points: Vec<(f64, f32)>) -> Result<GradientOpacity> {
        let bad = |message: String| Err(Error::InvalidArgument(format!("gradient opacity: {message}")));
        if points.is_empty() {
            return bad("no points: give at least one (gradient magnitude, opacity) point".into());
        }
        for (i, &(g, a)) in points.iter().enumerate() {
            if !g.is_finite() {
                return bad(format!("point {i} has gradient magnitude {g}: magnitudes must be finite numbers"));
            }
            if !(0.0..=1.0).contains(&a) {
                return bad(format!("point {i} (magnitude {g}) has opacity {a}: opacities must be in [0, 1]"));
            }
            if i > 0 && g < points[i - 1].0 {
                return bad(format!(
                    "point {i} has magnitude {g}, below the previous point's {}: give the points in increasing \
                     magnitude order",
                    points[i - 1].0
                ));
            }
        }
        Ok(GradientOpacity { points })
    }

    /// VTK 9.2's gradient opacity for a grid of `spacing` and scalar range
    /// `[lo, hi]`: VTK looks the function up at `min(|g| s, (hi - lo) / 4)`,
    /// `s` the mean spacing (vtkOpenGLVolumeGradientOpacityTable over `[0,
    /// (hi - lo) / 4]`; a range of 0 counts as 1). The same function of `|g|`:
    /// the points below the clamp divided by `s`, then the clamp's value
    /// held from `(hi - lo) / (4 s)` on.
    ///
    /// # Errors
    ///
    /// As [`GradientOpacity::new`], and for a spacing that is not positive.
    pub fn from_vtk(points: Vec<(f64, f32)>, spacing: [f64; 3], (lo, hi): (f64, f64)) -> Result<GradientOpacity> {
        let vtk = GradientOpacity::new(points)?;
        let s = spacing.iter().sum::<f64>() / 3.0;
        if !(s > 0.0 && s.is_finite()) || spacing.iter().any(|&v| v <= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "gradient opacity: the grid's spacing {spacing:?} must be positive"
            )));
        }
        let range = if hi - lo != 0.0 && (hi - lo).is_finite() { hi - lo } else { 1.0 };
        let clamp = 0.25 * range;
        let mut points: Vec<(f64, f32)> = vtk.points.iter().filter(|p| p.0 < clamp).map(|&(g, a)| (g / s, a)).collect();
        points.push((clamp / s, vtk.eval(clamp)));
        GradientOpacity::new(points)
    }

    /// The points `(gradient magnitude, opacity)`.
    pub fn points(&self) -> &[(f64, f32)] {
        &self.points
    }

    /// `a_grad(|g|)`; a magnitude that is not a number counts as 0.
    pub fn eval(&self, magnitude: f64) -> f32 {
        let g = if magnitude.is_nan() { 0.0 } else { magnitude };
        super::function::piecewise(&self.points, g, |&(x, a)| (x, [a]))[0]
    }

    /// The smallest factor over every magnitude `|g| >= 0`: `a_grad(0)` or
    /// a point right of 0 (piecewise linear, constant past the last point).
    pub fn min_opacity(&self) -> f32 {
        self.points.iter().filter(|p| p.0 > 0.0).map(|p| p.1).fold(self.eval(0.0), f32::min)
    }

    /// `Some(c)` when the function is `c` at every magnitude `|g| >= 0`
    /// (`c = a_grad(0)` and every point right of 0 has opacity `c`): it then
    /// needs no gradient.
    pub fn constant(&self) -> Option<f32> {
        let c = self.eval(0.0);
        self.points.iter().filter(|p| p.0 > 0.0).all(|p| p.1 == c).then_some(c)
    }

    /// The function sampled at `n >= 2` magnitudes `k hi / (n - 1)`, `k = 0
    /// .. n`, for a GPU table over `[0, hi]`.
    pub fn table(&self, hi: f64, n: usize) -> Vec<f32> {
        let n = n.max(2);
        (0..n).map(|k| self.eval(hi * k as f64 / (n - 1) as f64)).collect()
    }

    /// The end of a table that holds the whole function: its largest point
    /// magnitude (past it the function is constant), 1 when that is not
    /// positive.
    pub fn table_end(&self) -> f64 {
        let last = self.points[self.points.len() - 1].0;
        if last > 0.0 {
            last
        } else {
            1.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn evaluates_piecewise_linearly_and_clamps() {
        let f = GradientOpacity::new(vec![(0.1, 0.0), (0.3, 1.0), (0.5, 0.5)]).unwrap();
        assert_eq!(f.eval(0.0), 0.0);
        assert_eq!(f.eval(-1.0), 0.0);
        assert!((f.eval(0.2) - 0.5).abs() < 1e-6);
        assert!((f.eval(0.4) - 0.75).abs() < 1e-6);
        assert_eq!(f.eval(10.0), 0.5);
        assert_eq!(f.eval(f64::INFINITY), 0.5);
        assert_eq!(f.eval(f64::NAN), f.eval(0.0));
        assert_eq!(f.constant(), None);
        assert_eq!(GradientOpacity::new(vec![(0.0, 0.4), (9.0, 0.4)]).unwrap().constant(), Some(0.4));
        let table = f.table(0.5, 6);
        assert_eq!(table.len(), 6);
        assert!((table[2] - 0.5).abs() < 1e-6 && table[5] == 0.5);
        assert_eq!(f.table_end(), 0.5);
        // Only magnitudes >= 0 count: a step at 0 to 1 is 1 everywhere.
        assert_eq!(GradientOpacity::new(vec![(-1.0, 0.0), (0.0, 0.0), (0.0, 1.0)]).unwrap().constant(), Some(1.0));
        assert_eq!(GradientOpacity::new(vec![(0.0, 1.0)]).unwrap().table_end(), 1.0);
    }

    /// The smallest factor over the magnitudes: at 0, at a point, or past
    /// the last one; points left of 0 are never reached.
    #[test]
    fn min_opacity_over_every_magnitude() {
        let g = |p: Vec<(f64, f32)>| GradientOpacity::new(p).unwrap().min_opacity();
        assert_eq!(g(vec![(0.0, 0.2), (10.0, 1.0)]), 0.2);
        assert_eq!(g(vec![(0.0, 1.0), (5.0, 0.3), (10.0, 0.9)]), 0.3);
        assert_eq!(g(vec![(-5.0, 0.0), (0.0, 0.6), (10.0, 0.7)]), 0.6);
    }

    #[test]
    fn bad_points_are_refused_with_reasons() {
        let msg = |p: Vec<(f64, f32)>| GradientOpacity::new(p).unwrap_err().to_string();
        assert!(msg(vec![]).contains("no points"));
        assert!(msg(vec![(0.0, 1.5)]).contains("[0, 1]"));
        assert!(msg(vec![(0.0, f32::NAN)]).contains("[0, 1]"));
        assert!(msg(vec![(f64::INFINITY, 0.5)]).contains("finite"));
        assert!(msg(vec![(1.0, 0.5), (0.5, 0.5)]).contains("increasing magnitude order"));
        let spacing = GradientOpacity::from_vtk(vec![(0.0, 1.0)], [1.0, 0.0, 1.0], (0.0, 1.0));
        assert!(spacing.unwrap_err().to_string().contains("spacing"));
    }

    /// VTK's lookup `f(min(|g| s, range / 4))` is the converted function of `|g|`.
    #[test]
    fn vtk_convention_is_the_same_function_of_the_gradient() {
        let points = vec![(0.0, 0.0), (10.0, 0.2), (40.0, 1.0), (200.0, 0.0)];
        let vtk = GradientOpacity::new(points.clone()).unwrap();
        let (spacing, range) = ([0.5, 1.0, 1.5], (-20.0, 180.0)); // s = 1, clamp 50
        let ours = GradientOpacity::from_vtk(points.clone(), spacing, range).unwrap();
        for k in 0..=400 {
            let g = k as f64 * 0.25;
            let expected = vtk.eval((g * 1.0).min(50.0));
            assert!((ours.eval(g) - expected).abs() < 1e-6, "{g}: {} vs {expected}", ours.eval(g));
        }
        let scaled = GradientOpacity::from_vtk(points, [2.0; 3], (0.0, 0.0)).unwrap(); // s = 2, range 0 -> 1
        assert_eq!(scaled.points(), &[(0.0, 0.0), (0.125, vtk.eval(0.25))]);
    }
}
