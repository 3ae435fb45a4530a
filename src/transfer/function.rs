//! Transfer functions: a piecewise-linear colour (RGB points, as VTK's
//! vtkColorTransferFunction) and a piecewise-linear scalar opacity (as
//! vtkPiecewiseFunction).
//!
//! Each function is a list of points `(x_i, y_i)` sorted by value (equal
//! values make a step). Between two points it is linear, outside the end
//! points it keeps the end value:
//!
//! ```text
//! f(v) = y_0                                               v <  x_0
//!      = y_i + (y_{i+1} - y_i) (v - x_i) / (x_{i+1} - x_i)  x_i <= v < x_{i+1}
//!      = y_last                                            v >= x_last
//! ```
//!
//! The opacity is the opacity of a layer one reference spacing `d0` thick
//! (see [`crate::render::blend::correct_opacity`]).
//!
//! NaN is no data (see [`crate::data::grid`]): `f(NaN)` is `[0, 0, 0, 0]`,
//! transparent black, whatever the points; a sample that interpolates a NaN
//! corner is NaN, so this one rule makes it contribute nothing in every
//! renderer that looks its colour up here.

use crate::base::error::{Error, Result};

/// A colour and an opacity transfer function (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction {
    colors: Vec<(f64, [f32; 3])>,
    opacities: Vec<(f64, f32)>,
}

/// `f(v)` of the module documentation over points `(x, y)` sorted by `x`
/// (at a step, the value right of it).
pub(super) fn piecewise<P, const N: usize>(points: &[P], v: f64, get: impl Fn(&P) -> (f64, [f32; N])) -> [f32; N] {
    let i = points.partition_point(|p| get(p).0 <= v);
    if i == 0 {
        return get(&points[0]).1;
    }
    if i == points.len() {
        return get(&points[i - 1]).1;
    }
    let ((x0, y0), (x1, y1)) = (get(&points[i - 1]), get(&points[i]));
    // x0 <= v < x1, so x1 > x0; halves when x1 - x0 overflows (points of
    // opposite sign near f64::MAX).
    let t = if (x1 - x0).is_finite() { (v - x0) / (x1 - x0) } else { (v / 2.0 - x0 / 2.0) / (x1 / 2.0 - x0 / 2.0) };
    let t = t as f32;
    std::array::from_fn(|k| y0[k] + (y1[k] - y0[k]) * t)
}

pub(super) fn check<const N: usize>(what: &str, points: &[(f64, [f32; N])]) -> Result<()> {
    let bad = |message: String| Err(Error::InvalidArgument(format!("transfer function: {message}")));
    if points.is_empty() {
        return bad(format!("the {what} function has no points: give at least one (value, {what}) point"));
    }
    for (i, (x, y)) in points.iter().enumerate() {
        if !x.is_finite() {
            return bad(format!("{what} point {i} has value {x}: values must be finite numbers"));
        }
        if y.iter().any(|c| !(0.0..=1.0).contains(c)) {
            return bad(format!("{what} point {i} (value {x}) is {y:?}: every {what} component must be in [0, 1]"));
        }
        if i > 0 && *x < points[i - 1].0 {
            return bad(format!(
                "{what} point {i} has value {x}, below the previous point's {}: give the points in increasing value order",
                points[i - 1].0
            ));
        }
    }
    Ok(())
}

impl TransferFunction {
    /// A transfer function from colour points `(value, [r, g, b])` and opacity
    /// points `(value, opacity)`: at least one of each, values finite and in
    /// non-decreasing order, colours and opacities in `[0, 1]`.
    pub fn new(colors: Vec<(f64, [f32; 3])>, opacities: Vec<(f64, f32)>) -> Result<TransferFunction> {
        check("colour", &colors)?;
        let as_arrays: Vec<(f64, [f32; 1])> = opacities.iter().map(|&(x, a)| (x, [a])).collect();
        check("opacity", &as_arrays)?;
        Ok(TransferFunction { colors, opacities })
    }

    /// The default for a data range `[min, max]`: grey (0.3) to white, and an
    /// opacity (per reference spacing) that is 0 over the lowest 15 % of the
    /// range, then rises piecewise linearly through 0.002 at 20 %, 0.03 at
    /// 30 %, 0.08 at 60 % to 0.12 at `max`. Made for the Shepp-Logan phantom
    /// (air and ventricles 0, brain 0.2, inner structures 0.3-0.6, skull 1)
    /// at 128^3: the brain stays faint over its ~100 voxels, the inner
    /// structures show through the skull, which lets ~60 % of the light
    /// through. (A ramp up to 0.8 makes the few voxels of skull opaque: the
    /// picture is then only the skull's outside.)
    pub fn ramp(min: f64, max: f64) -> TransferFunction {
        let (lo, hi) = match (min.is_finite() && max.is_finite(), min <= max) {
            (false, _) => (0.0, 1.0),
            (true, true) => (min, max),
            (true, false) => (max, min),
        };
        // lo + f (hi - lo), or lo (1 - f) + hi f when hi - lo overflows.
        let at =
            |f: f64| if (hi - lo).is_finite() { lo + f * (hi - lo) } else { (lo * (1.0 - f) + hi * f).clamp(lo, hi) };
        let opacities = [(0.0, 0.0), (0.15, 0.0), (0.2, 0.002), (0.3, 0.03), (0.6, 0.08), (1.0, 0.12)];
        TransferFunction {
            colors: vec![(lo, [0.3; 3]), (hi, [1.0; 3])],
            opacities: opacities.iter().map(|&(f, a)| (at(f), a)).collect(),
        }
    }

    /// The colour points `(value, [r, g, b])`.
    pub fn colors(&self) -> &[(f64, [f32; 3])] {
        &self.colors
    }

    /// The opacity points `(value, opacity)`.
    pub fn opacities(&self) -> &[(f64, f32)] {
        &self.opacities
    }

    /// Opacity at `value`; 0 for NaN (no data).
    pub fn opacity(&self, value: f64) -> f32 {
        if value.is_nan() {
            return 0.0;
        }
        piecewise(&self.opacities, value, |&(x, a)| (x, [a]))[0]
    }

    /// Straight `[r, g, b, opacity]` at `value`; `[0, 0, 0, 0]` for NaN (no data).
    pub fn eval(&self, value: f64) -> [f32; 4] {
        if value.is_nan() {
            return [0.0; 4];
        }
        let [r, g, b] = piecewise(&self.colors, value, |&p| p);
        [r, g, b, self.opacity(value)]
    }

    /// True when the opacity is 0 over the whole `[min, max]` (the bounds in
    /// either order). Exact for a piecewise-linear function: its maximum over
    /// an interval is at an end or at a point inside. The empty range
    /// `(+inf, -inf)` of a box of NaN only (and a NaN bound) holds no data:
    /// transparent.
    pub fn is_transparent_over(&self, min: f64, max: f64) -> bool {
        if (min == f64::INFINITY && max == f64::NEG_INFINITY) || min.is_nan() || max.is_nan() {
            return true;
        }
        let (lo, hi) = if min <= max { (min, max) } else { (max, min) };
        self.opacity(lo) == 0.0
            && self.opacity(hi) == 0.0
            && self.opacities.iter().filter(|p| lo < p.0 && p.0 < hi).all(|p| p.1 == 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tf() -> TransferFunction {
        TransferFunction::new(
            vec![(0.0, [0.0, 0.0, 1.0]), (1.0, [1.0, 0.0, 0.0])],
            vec![(0.2, 0.0), (0.4, 0.0), (0.6, 1.0), (0.6, 0.5), (0.8, 0.0)],
        )
        .unwrap()
    }

    #[test]
    fn evaluates_piecewise_linearly_and_clamps() {
        let t = tf();
        assert_eq!(t.eval(-5.0), [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(t.eval(5.0), [1.0, 0.0, 0.0, 0.0]);
        let v = t.eval(0.25);
        assert!((v[0] - 0.25).abs() < 1e-6 && (v[2] - 0.75).abs() < 1e-6 && v[3] == 0.0);
        assert!((t.eval(0.5)[3] - 0.5).abs() < 1e-6);
        assert_eq!(t.eval(0.6)[3], 0.5); // right of the step
        assert!((t.eval(0.7)[3] - 0.25).abs() < 1e-6);
    }

    #[test]
    fn transparency_over_a_range_is_exact() {
        let t = tf();
        assert!(t.is_transparent_over(0.0, 0.4));
        assert!(t.is_transparent_over(0.8, 3.0));
        assert!(t.is_transparent_over(0.4, 0.2));
        assert!(!t.is_transparent_over(0.3, 0.41));
        assert!(!t.is_transparent_over(0.0, 1.0)); // only the point 0.6 inside is opaque
        let spike = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)]).unwrap();
        assert!(!spike.is_transparent_over(0.1, 0.9)); // ends transparent, the point inside is not
    }

    #[test]
    fn nan_is_transparent_black_and_an_empty_range_is_transparent() {
        let opaque = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(0.0, 1.0)]).unwrap();
        assert_eq!(opaque.eval(f64::NAN), [0.0; 4]);
        assert_eq!(opaque.opacity(f64::NAN), 0.0);
        assert!(opaque.is_transparent_over(f64::INFINITY, f64::NEG_INFINITY));
        assert!(!opaque.is_transparent_over(f64::NEG_INFINITY, f64::INFINITY));
        assert!(!opaque.is_transparent_over(0.0, 0.0));
    }

    #[test]
    fn bad_points_are_refused_with_reasons() {
        let msg = |c: Vec<(f64, [f32; 3])>, o: Vec<(f64, f32)>| TransferFunction::new(c, o).unwrap_err().to_string();
        let grey = vec![(0.0, [0.5; 3])];
        assert!(msg(vec![], vec![(0.0, 1.0)]).contains("no points"));
        assert!(msg(grey.clone(), vec![]).contains("opacity function has no points"));
        assert!(msg(grey.clone(), vec![(1.0, 0.1), (0.5, 0.2)]).contains("increasing value order"));
        assert!(msg(grey.clone(), vec![(f64::NAN, 0.1)]).contains("finite"));
        assert!(msg(grey.clone(), vec![(0.0, 1.5)]).contains("[0, 1]"));
        assert!(msg(vec![(0.0, [0.5, f32::NAN, 0.0])], vec![(0.0, 0.5)]).contains("[0, 1]"));
    }

    #[test]
    fn ramp_is_transparent_at_the_bottom_only() {
        let r = TransferFunction::ramp(0.0, 1.0);
        assert_eq!(r.eval(0.0), [0.3, 0.3, 0.3, 0.0]);
        assert_eq!(r.eval(1.0), [1.0, 1.0, 1.0, 0.12]);
        assert!(r.is_transparent_over(-1.0, 0.15) && !r.is_transparent_over(0.0, 0.16));
        let mut last = 0.0;
        for i in 0..=100 {
            let a = r.eval(i as f64 / 100.0)[3];
            assert!(a >= last);
            last = a;
        }
        assert_eq!(TransferFunction::ramp(2.0, -2.0).eval(-2.0)[3], 0.0);
        assert_eq!(TransferFunction::ramp(3.0, 3.0).eval(3.0)[3], 0.12);
    }
}
