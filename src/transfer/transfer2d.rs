//! The 2D transfer function (vtkVolumeProperty's TF_2D mode,
//! `GetTransferFunction2D()`; ParaView's *Use 2D Transfer Function*): one
//! RGBA table over (scalar value, gradient magnitude) that gives a sample's
//! colour and opacity together.
//!
//! The table is `width x height` texels, row-major, row `j` a gradient
//! magnitude, column `i` a scalar value (the layout of VTK's 4-component
//! float vtkImageData, x the scalar axis). It is read as VTK 9.2's GPU ray
//! caster reads its 2D texture (`texture2D` with linear filtering and
//! clamp-to-edge), texel centres at `(i + 1/2) / width`:
//!
//! ```text
//! x  = (v - lo) / (hi - lo)                 the scalar axis over [lo, hi] (hi = lo: hi - lo = 1e-6)
//! y  = min(|g| / g_max, 1)                  the gradient axis over [0, g_max]
//! tx = clamp(x width - 1/2, 0, width - 1),  ty = clamp(y height - 1/2, 0, height - 1)
//! T(v, |g|) = bilinear interpolation of the four texels around (tx, ty)
//! ```
//!
//! `|g| = |grad F|` is the gradient of `crate::render::shade`'s rule
//! (central differences one lattice step away, data units per world unit);
//! a value or a magnitude that is not a number counts as no data (transparent)
//! and 0 respectively, as for the 1D function and the gradient opacity.
//!
//! VTK ([`TransferFunction2D::from_vtk`]): `[lo, hi]` is the data array's
//! finite range (vtkVolumeTexture's ScalarRange, the scale and bias of its
//! texture), and the gradient axis is VTK's `computeGradient`,
//! `clamp(|g| s / (range / 4), 0, 1)` with `s` the mean spacing and a range
//! of 0 counted as 1: `g_max = (hi - lo) / (4 s)`. The table's own origin and
//! spacing are not read (VTK ignores them too).
//!
//! Opacity: the alpha here is the opacity of a layer `d0` thick
//! ([`crate::data::spacing::reference_spacing`]), the 1D function's
//! convention, and the renderers correct it as theirs, `a' = 1 - (1 -
//! a)^(d / d0)`. VTK takes the table's alpha as each sample's opacity with
//! no correction, at its own sample distance `d_vtk` (vtkGPUVolumeRayCastMapper
//! with AutoAdjustSampleDistances: the smallest spacing; ParaView's
//! vtkSmartVolumeMapper: about a third of a voxel): a host converts VTK's
//! alpha first, `1 - (1 - a)^(d0 / d_vtk)` (vtkHybridOctreeTransfer2D does).

use crate::base::error::{Error, Result};

/// The largest table side (texels), below every OpenGL 3.2 texture limit.
pub const MAX_SIDE: usize = 4096;

/// The span used for a scalar range of width 0 (VTK's `glRange[0] + 1e-6`).
const EMPTY_RANGE_SPAN: f64 = 1e-6;

/// A 2D transfer function (see the module documentation).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransferFunction2D {
    width: usize,
    height: usize,
    /// Row-major: texel `(i, j)` at `i + j width`.
    rgba: Vec<[f32; 4]>,
    scalar_range: [f64; 2],
    gradient_max: f64,
    /// Per column, the largest alpha over its rows (the visibility test).
    #[serde(skip)]
    column_alpha: Vec<f32>,
}

impl TransferFunction2D {
    /// A table of `width x height` texels `rgba` (row-major, rows by
    /// gradient magnitude), its scalar axis over `scalar_range = [lo, hi]`
    /// and its gradient axis over `[0, gradient_max]`.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a side of 0 or above [`MAX_SIDE`]
    /// (checked before anything is allocated), a texel count other than
    /// `width height`, a component that is not in `[0, 1]` (NaN included),
    /// a range that is not finite or has `lo > hi`, a `gradient_max` that is
    /// not a positive finite number.
    pub fn new(
        width: usize,
        height: usize,
        rgba: Vec<[f32; 4]>,
        scalar_range: [f64; 2],
        gradient_max: f64,
    ) -> Result<TransferFunction2D> {
        Self::check_sides(width, height)?;
        let bad = |message: String| Err(Error::InvalidArgument(format!("2D transfer function: {message}")));
        if rgba.len() != width * height {
            return bad(format!(
                "{} texels for a {width} x {height} table: give width x height = {} RGBA texels",
                rgba.len(),
                width * height
            ));
        }
        if let Some(k) = rgba.iter().position(|t| t.iter().any(|c| !(0.0..=1.0).contains(c))) {
            return bad(format!(
                "texel ({}, {}) is {:?}: every component must be a number in [0, 1]",
                k % width,
                k / width,
                rgba[k]
            ));
        }
        let [lo, hi] = scalar_range;
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return bad(format!("scalar range [{lo}, {hi}]: give two finite numbers, the first not above the second"));
        }
        if !(gradient_max > 0.0 && gradient_max.is_finite()) {
            return bad(format!("largest gradient magnitude {gradient_max}: give a positive finite number"));
        }
        let column_alpha =
            (0..width).map(|i| (0..height).map(|j| rgba[i + j * width][3]).fold(0.0, f32::max)).collect();
        Ok(TransferFunction2D { width, height, rgba, scalar_range, gradient_max, column_alpha })
    }

    /// Sides in `1 ..= MAX_SIDE`.
    pub fn check_sides(width: usize, height: usize) -> Result<()> {
        if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
            return Err(Error::InvalidArgument(format!(
                "2D transfer function: a {width} x {height} table: each side must be 1 to {MAX_SIDE} texels"
            )));
        }
        Ok(())
    }

    /// VTK 9.2's 2D transfer function for data of finite range `[lo, hi]`
    /// on a grid of `spacing` (module documentation): the scalar axis over
    /// `[lo, hi]`, the gradient axis up to `(hi - lo) / (4 s)`, `s` the mean
    /// spacing (a range of 0 counts as 1).
    ///
    /// # Errors
    ///
    /// As [`TransferFunction2D::new`], and for a spacing that is not positive.
    pub fn from_vtk(
        width: usize,
        height: usize,
        rgba: Vec<[f32; 4]>,
        (lo, hi): (f64, f64),
        spacing: [f64; 3],
    ) -> Result<TransferFunction2D> {
        let s = spacing.iter().sum::<f64>() / 3.0;
        if !(s > 0.0 && s.is_finite()) || spacing.iter().any(|&v| v <= 0.0 || v.is_nan()) {
            return Err(Error::InvalidArgument(format!(
                "2D transfer function: the grid's spacing {spacing:?} must be positive"
            )));
        }
        let range = if hi - lo != 0.0 && (hi - lo).is_finite() { hi - lo } else { 1.0 };
        TransferFunction2D::new(width, height, rgba, [lo, hi], 0.25 * range / s)
    }

    /// Table width (scalar axis), texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Table height (gradient axis), texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texels, row-major.
    pub fn texels(&self) -> &[[f32; 4]] {
        &self.rgba
    }

    /// The scalar axis `[lo, hi]`.
    pub fn scalar_range(&self) -> [f64; 2] {
        self.scalar_range
    }

    /// The gradient axis' end `g_max` (larger magnitudes read the last row).
    pub fn gradient_max(&self) -> f64 {
        self.gradient_max
    }

    /// The continuous column of value `v` (`tx`, unclamped).
    fn column(&self, v: f64) -> f64 {
        let [lo, hi] = self.scalar_range;
        let span = if hi > lo { hi - lo } else { EMPTY_RANGE_SPAN };
        (v - lo) / span * self.width as f64 - 0.5
    }

    /// The continuous row of magnitude `g` (`ty`, unclamped; NaN as 0).
    fn row(&self, g: f64) -> f64 {
        let g = if g.is_nan() { 0.0 } else { g };
        (g / self.gradient_max).min(1.0) * self.height as f64 - 0.5
    }

    /// `T(v, |g|)` (module documentation); `[0; 4]` for a NaN value.
    pub fn eval(&self, value: f64, magnitude: f64) -> [f32; 4] {
        if value.is_nan() {
            return [0.0; 4];
        }
        let (tx, ty) = (self.column(value), self.row(magnitude));
        let split = |t: f64, n: usize| {
            let t = t.clamp(0.0, (n - 1) as f64);
            let i = (t.floor() as usize).min(n - 1);
            (i, (i + 1).min(n - 1), (t - i as f64) as f32)
        };
        let ((i0, i1, fx), (j0, j1, fy)) = (split(tx, self.width), split(ty, self.height));
        let at = |i: usize, j: usize| self.rgba[i + j * self.width];
        let lerp = |a: [f32; 4], b: [f32; 4], f: f32| std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f);
        lerp(lerp(at(i0, j0), at(i1, j0), fx), lerp(at(i0, j1), at(i1, j1), fx), fy)
    }

    /// The columns whose texels can weigh in a value in `[min, max]`.
    fn columns(&self, min: f64, max: f64) -> std::ops::RangeInclusive<usize> {
        let last = (self.width - 1) as f64;
        let (a, b) = (self.column(min).clamp(0.0, last), self.column(max).clamp(0.0, last));
        (a.floor() as usize)..=(b.ceil() as usize)
    }

    /// An upper bound of the opacity over values `[min, max]` and gradient
    /// magnitudes `[g_min, g_max]`: the largest alpha of the texels whose
    /// bilinear weights can be non-zero there (a lookup is a convex
    /// combination of them), exact 0 when they are all 0.
    pub fn max_opacity(&self, min: f64, max: f64, g_min: f64, g_max: f64) -> f32 {
        if min.is_nan() || max.is_nan() || min > max {
            return 0.0;
        }
        let last = (self.height - 1) as f64;
        let (a, b) = (self.row(g_min.max(0.0)).clamp(0.0, last), self.row(g_max.max(0.0)).clamp(0.0, last));
        let rows = (a.floor() as usize)..=(b.ceil() as usize);
        let mut best = 0.0f32;
        for j in rows {
            for i in self.columns(min, max) {
                best = best.max(self.rgba[i + j * self.width][3]);
            }
        }
        best
    }

    /// True when every sample with a value in `[min, max]` is transparent,
    /// whatever its gradient: the table's alpha is 0 in every row over the
    /// columns those values read. The gradient bound is `[0, infinity)`
    /// (every row): a node's range does not bound the gradients of its
    /// samples, which read values one lattice step outside it.
    pub fn is_transparent_over(&self, min: f64, max: f64) -> bool {
        if min.is_nan() || max.is_nan() || min > max {
            return true;
        }
        self.columns(min, max).all(|i| self.column_alpha[i] <= 0.0)
    }

    /// Per column, the largest alpha over the gradient axis: a 1D opacity
    /// that is 0 exactly where the table is 0 at every gradient.
    pub fn column_opacity(&self) -> &[f32] {
        &self.column_alpha
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(width: usize, height: usize, f: impl Fn(usize, usize) -> [f32; 4]) -> Vec<[f32; 4]> {
        (0..height).flat_map(|j| (0..width).map(move |i| (i, j))).map(|(i, j)| f(i, j)).collect()
    }

    /// Texel centres give their texel, between them it is bilinear, outside clamped.
    #[test]
    fn reads_as_a_linear_clamped_texture() {
        let t = TransferFunction2D::new(
            4,
            2,
            table(4, 2, |i, j| [i as f32 / 3.0, j as f32, 0.5, if j == 1 { 0.8 } else { 0.0 }]),
            [0.0, 4.0],
            2.0,
        )
        .unwrap();
        // Column i's centre is at v = i + 1/2, row j's at |g| = (j + 1/2).
        assert_eq!(t.eval(1.5, 0.5), [1.0 / 3.0, 0.0, 0.5, 0.0]);
        assert_eq!(t.eval(2.5, 1.5), [2.0 / 3.0, 1.0, 0.5, 0.8]);
        let mid = t.eval(2.0, 1.0);
        assert!((mid[0] - 0.5).abs() < 1e-6 && (mid[1] - 0.5).abs() < 1e-6 && (mid[3] - 0.4).abs() < 1e-6);
        assert_eq!(t.eval(-10.0, 99.0), t.eval(0.5, 1.5));
        assert_eq!(t.eval(10.0, -1.0), t.eval(3.5, 0.5));
        assert_eq!(t.eval(f64::NAN, 1.0), [0.0; 4]);
        assert_eq!(t.eval(1.5, f64::NAN), t.eval(1.5, 0.0));
        // A one-valued range: the value itself is column 0.
        let flat = TransferFunction2D::new(2, 1, vec![[0.1; 4], [0.9; 4]], [3.0, 3.0], 1.0).unwrap();
        assert_eq!(flat.eval(3.0, 0.0), [0.1; 4]);
    }

    /// Transparent means 0 in every row over the value's columns; one visible
    /// row (high gradient only) keeps the node.
    #[test]
    fn visibility_over_every_gradient() {
        // Alpha 1 in columns 6..8 only at the highest rows.
        let t = TransferFunction2D::new(
            10,
            8,
            table(10, 8, |i, j| [1.0, 1.0, 1.0, if (6..8).contains(&i) && j >= 6 { 1.0 } else { 0.0 }]),
            [0.0, 10.0],
            4.0,
        )
        .unwrap();
        assert!(t.is_transparent_over(0.0, 5.0), "columns 0..=5 are 0 in every row");
        assert!(!t.is_transparent_over(6.2, 6.8), "visible at high gradient");
        assert!(!t.is_transparent_over(0.0, 10.0));
        assert!(t.is_transparent_over(f64::NAN, f64::NAN));
        assert_eq!(t.max_opacity(6.2, 6.8, 0.0, 2.0), 0.0, "no low-gradient row is visible there");
        assert_eq!(t.max_opacity(6.2, 6.8, 3.5, 100.0), 1.0);
        // Exact: a sample anywhere in a transparent node's range reads alpha 0.
        for k in 0..=500 {
            let v = 5.0 * k as f64 / 500.0;
            assert_eq!(t.eval(v, 100.0)[3], 0.0, "{v}");
        }
        assert_eq!(t.column_opacity()[6], 1.0);
    }

    #[test]
    fn bad_tables_are_refused_with_reasons() {
        let msg = |w, h, rgba: Vec<[f32; 4]>, r: [f64; 2], g: f64| {
            TransferFunction2D::new(w, h, rgba, r, g).unwrap_err().to_string()
        };
        assert!(msg(0, 1, vec![], [0.0, 1.0], 1.0).contains("1 to 4096"));
        assert!(msg(1, usize::MAX, vec![], [0.0, 1.0], 1.0).contains("1 to 4096"));
        assert!(msg(2, 2, vec![[0.0; 4]; 3], [0.0, 1.0], 1.0).contains("3 texels for a 2 x 2 table"));
        assert!(msg(1, 1, vec![[0.0, f32::NAN, 0.0, 0.0]], [0.0, 1.0], 1.0).contains("texel (0, 0)"));
        assert!(msg(2, 1, vec![[0.0; 4], [0.0, 0.0, 0.0, 1.5]], [0.0, 1.0], 1.0).contains("texel (1, 0)"));
        assert!(msg(1, 1, vec![[0.0; 4]], [1.0, 0.0], 1.0).contains("scalar range"));
        assert!(msg(1, 1, vec![[0.0; 4]], [0.0, f64::INFINITY], 1.0).contains("scalar range"));
        assert!(msg(1, 1, vec![[0.0; 4]], [0.0, 1.0], 0.0).contains("gradient magnitude"));
        assert!(msg(1, 1, vec![[0.0; 4]], [0.0, 1.0], f64::NAN).contains("gradient magnitude"));
        let e = TransferFunction2D::from_vtk(1, 1, vec![[0.0; 4]], (0.0, 1.0), [1.0, 0.0, 1.0]).unwrap_err();
        assert!(e.to_string().contains("spacing"));
    }

    /// VTK's axes: the data range, and `|g| s / (range / 4)` clamped.
    #[test]
    fn vtk_axes() {
        let t = TransferFunction2D::from_vtk(1, 1, vec![[0.0; 4]], (-20.0, 180.0), [0.5, 1.0, 1.5]).unwrap();
        assert_eq!(t.scalar_range(), [-20.0, 180.0]);
        assert_eq!(t.gradient_max(), 50.0);
        let t = TransferFunction2D::from_vtk(1, 1, vec![[0.0; 4]], (2.0, 2.0), [2.0; 3]).unwrap();
        assert_eq!(t.gradient_max(), 0.125);
    }
}
