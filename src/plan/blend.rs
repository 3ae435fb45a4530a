//! VTK's blend modes (`vtkVolumeMapper::SetBlendMode`): how the samples
//! along a ray become a pixel. Composite blends them front to back; the
//! other four reduce the ray to one value first (VTK 9.2,
//! `vtkVolumeShaderComposer.h`, `ShadingInit` / `ShadingSingleInput` /
//! `RenderToImage` of the one-component case):
//!
//! ```text
//! maximum intensity:  m = max_i v_i,   pixel = (a(m) c(m), a(m))             no sample: nothing
//! minimum intensity:  m = min_i v_i,   pixel = (a(m) c(m), a(m))             no sample: nothing
//! average intensity:  g = sum_i w_i a(v_i) n(v_i) / sum_i w_i  over the v_i in AverageIPScalarRange,
//!                     pixel = (g, g, g, 1), g clamped to [0, 1]              no such sample: nothing
//! additive:           g = sum_i w_i a(v_i) n(v_i),  pixel = (g, g, g, 1), g clamped to [0, 1]
//! ```
//!
//! `c, a` are the transfer function's colour and opacity (opacity for the
//! reference spacing d0, not corrected: one value stands for the ray), `n(v)
//! = (v - lo) / (hi - lo)` the value normalised to the volume's scalar range
//! (VTK's `in_scalarsRange`; 0 for a constant volume), and `w_i = l_i / d0`
//! the sample's length in reference spacings: VTK's samples are all one
//! spacing apart, ours are `d = min(stride, c) d0` apart in a coarse brick
//! (and `d0 / 4` in the reference caster), so a sample stands for `d / d0`
//! of VTK's. Maximum and minimum are order independent, sums too: the bricks
//! combine by max, min or sum in any order. An additive pixel is opaque
//! (alpha 1) wherever its ray crosses the volume's box, as VTK's: its
//! proxy geometry is that box.
//!
//! Isosurface (VTK's `ISOSURFACE_BLEND`, ParaView's *Blend Mode* Isosurface
//! with *Isosurfaces*) composites front to back like Composite, but a
//! sample shows only the isovalues the ray crossed since the sample before
//! it (one lattice step `s` nearer the eye):
//!
//! ```text
//! the c_k crossed from v(p - s) = v0 to v(p) = v1:  v0 < c_k <= v1 or v1 <= c_k < v0,
//! each composited, nearest v0 first, as (c(c_k), a(c_k)), shaded at p when Shade is on
//! ```
//!
//! (VTK's `findIsoSurfaceIndex` walk takes the same crossings, one a step
//! when a jump crosses several), the opacity not corrected for the
//! spacing: one crossing is one surface.
//!
//! Slice (VTK's `SLICE_BLEND`, ParaView's *Blend Mode* Slice with its
//! *Slice Function*) draws one sample a ray, where it meets a plane
//! ([`super::slice`]): `(a(v) c(v), a(v))`, the opacity not corrected,
//! shaded with Shade.
//!
//! VTK's opacities are per ScalarOpacityUnitDistance `U`; the renderers'
//! (the DrawList's, the reference caster's) per `d0`. VTK 9.2 corrects its
//! opacity table for the sample distance `s` by the blend mode
//! (`vtkOpenGLVolumeOpacityTable::InternalUpdate`): Composite `1 - (1 -
//! a)^(s / U)`, Additive `a s / U`, the other modes not at all. A table
//! per `U` becomes one per `d0` by the same rule with `s = d0`
//! ([`BlendMode::opacity_per_reference`]); the renderers' own rules above
//! then give VTK's picture at any spacing:
//!
//! ```text
//! Composite:  a_d0 = 1 - (1 - a)^(d0 / U)   corrected per sample to 1 - (1 - a)^(d / U)
//! Additive:   a_d0 = a d0 / U               weighed d / d0 per sample: a d / U
//! the others: a_d0 = a                      (Isosurface, Slice, and the reductions: a(m), a(v_i))
//! ```

/// A blend mode, named as the plan's passes and the CLI's `--blend` name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BlendMode {
    /// Front-to-back compositing (`COMPOSITE_BLEND`).
    #[default]
    Composite,
    /// Maximum intensity projection (`MAXIMUM_INTENSITY_BLEND`).
    Mip,
    /// Minimum intensity projection (`MINIMUM_INTENSITY_BLEND`).
    Minip,
    /// Average intensity (`AVERAGE_INTENSITY_BLEND`).
    Average,
    /// Additive (`ADDITIVE_BLEND`).
    Additive,
    /// Isosurfaces of the given values (`ISOSURFACE_BLEND`).
    Isosurface,
    /// The volume on a plane (`SLICE_BLEND`).
    Slice,
}

impl BlendMode {
    /// Every mode, in VTK's order.
    pub const ALL: [BlendMode; 7] = [
        BlendMode::Composite,
        BlendMode::Mip,
        BlendMode::Minip,
        BlendMode::Average,
        BlendMode::Additive,
        BlendMode::Isosurface,
        BlendMode::Slice,
    ];

    /// The mode's name: `composite`, `mip`, `minip`, `average`, `additive`, `isosurface`, `slice`.
    pub fn name(self) -> &'static str {
        match self {
            BlendMode::Composite => "composite",
            BlendMode::Mip => "mip",
            BlendMode::Minip => "minip",
            BlendMode::Average => "average",
            BlendMode::Additive => "additive",
            BlendMode::Isosurface => "isosurface",
            BlendMode::Slice => "slice",
        }
    }

    /// The volume pass of the plan: `volume` (Composite) or `volume-<name>`.
    pub fn pass(self) -> String {
        match self {
            BlendMode::Composite => "volume".to_string(),
            other => format!("volume-{}", other.name()),
        }
    }

    /// The mode of VTK's `vtkVolumeMapper::BlendModes` value (0 composite,
    /// 1 maximum, 2 minimum, 3 average, 4 additive, 5 isosurface, 6 slice);
    /// `None` for unknown values.
    pub fn from_vtk(value: i32) -> Option<BlendMode> {
        BlendMode::ALL.get(usize::try_from(value).ok()?).copied()
    }

    /// VTK's value of the mode (`vtkVolumeMapper::BlendModes`): the inverse of [`Self::from_vtk`].
    pub fn to_vtk(self) -> i32 {
        BlendMode::ALL.iter().position(|&m| m == self).map_or(0, |i| i as i32)
    }

    /// True for the modes that reduce a ray to its largest or smallest value.
    pub fn is_extremum(self) -> bool {
        matches!(self, BlendMode::Mip | BlendMode::Minip)
    }

    /// True for the modes that composite samples front to back (Composite,
    /// Isosurface): shading and a translucent surface in the slabs apply.
    pub fn composites(self) -> bool {
        matches!(self, BlendMode::Composite | BlendMode::Isosurface)
    }

    /// True for the modes VTK shades with Shade (Composite, Isosurface, Slice).
    pub fn shades(self) -> bool {
        self.composites() || self == BlendMode::Slice
    }

    /// The opacity per reference spacing `d0` of VTK's table opacity `a`
    /// per ScalarOpacityUnitDistance `U` under this mode, `ratio = d0 / U`
    /// (see the module documentation): Composite `1 - (1 - a)^ratio`,
    /// Additive `min(1, a ratio)` (a transfer function's opacity is at
    /// most 1), the others `a`. `a` is clamped to `[0, 1]`; a `ratio` that
    /// is not positive and finite leaves `a` as it is.
    pub fn opacity_per_reference(self, a: f64, ratio: f64) -> f64 {
        let a = a.clamp(0.0, 1.0);
        if !(ratio > 0.0 && ratio.is_finite()) {
            return a;
        }
        match self {
            BlendMode::Composite if a < 1.0 => 1.0 - (1.0 - a).powf(ratio),
            BlendMode::Additive => (a * ratio).min(1.0),
            _ => a,
        }
    }
}

impl std::str::FromStr for BlendMode {
    type Err = crate::Error;
    fn from_str(s: &str) -> crate::Result<BlendMode> {
        BlendMode::ALL.into_iter().find(|m| m.name() == s).ok_or_else(|| {
            crate::Error::InvalidArgument(format!(
                "blend mode '{}': give one of composite, mip, minip, average, additive, isosurface, slice",
                crate::base::limits::excerpt(s)
            ))
        })
    }
}

/// A blend mode with the ranges its reduction needs (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Blend {
    /// The mode.
    pub mode: BlendMode,
    /// The volume's scalar range `[lo, hi]`, what `n(v)` normalises by
    /// (average and additive).
    pub scalar_range: [f64; 2],
    /// VTK's AverageIPScalarRange: the values an average counts (default
    /// everything, VTK's `[VTK_DOUBLE_MIN, VTK_DOUBLE_MAX]`).
    pub average_range: [f64; 2],
    /// The isosurface values (Isosurface), increasing; the first
    /// `isovalue_count` are used.
    pub isovalues: [f64; MAX_ISOVALUES],
    /// How many of `isovalues` are set.
    pub isovalue_count: usize,
    /// The plane of the Slice mode (`None` for the others; Slice without
    /// one draws nothing).
    pub slice: Option<super::slice::SlicePlane>,
}

/// The most isosurface values a blend takes.
pub const MAX_ISOVALUES: usize = 16;

impl Default for Blend {
    fn default() -> Blend {
        Blend::new(BlendMode::Composite, [0.0, 1.0])
    }
}

impl Blend {
    /// `mode` over a volume of scalar range `scalar_range`, averaging every value.
    pub fn new(mode: BlendMode, scalar_range: [f64; 2]) -> Blend {
        Blend {
            mode,
            scalar_range,
            average_range: [f64::MIN, f64::MAX],
            isovalues: [0.0; MAX_ISOVALUES],
            isovalue_count: 0,
            slice: None,
        }
    }

    /// The Slice mode on `plane` (data coordinates) over a volume of scalar
    /// range `scalar_range`.
    ///
    /// # Errors
    ///
    /// [`crate::Error::InvalidArgument`] for a bad plane ([`super::slice::SlicePlane::check`]).
    pub fn slice(plane: super::slice::SlicePlane, scalar_range: [f64; 2]) -> crate::Result<Blend> {
        plane.check()?;
        Ok(Blend { slice: Some(plane), ..Blend::new(BlendMode::Slice, scalar_range) })
    }

    /// Isosurfaces of `values` (any order, repeats merged) over a volume of
    /// scalar range `scalar_range`.
    ///
    /// # Errors
    ///
    /// [`crate::Error::InvalidArgument`] for no value, more than
    /// [`MAX_ISOVALUES`], or a value that is not finite.
    pub fn isosurfaces(values: &[f64], scalar_range: [f64; 2]) -> crate::Result<Blend> {
        let mut sorted = values.to_vec();
        if let Some(bad) = sorted.iter().find(|v| !v.is_finite()) {
            return Err(crate::Error::InvalidArgument(format!("isosurface value {bad}: give finite numbers")));
        }
        sorted.sort_by(f64::total_cmp);
        sorted.dedup();
        if sorted.is_empty() || sorted.len() > MAX_ISOVALUES {
            return Err(crate::Error::InvalidArgument(format!(
                "{} isosurface values: give 1 to {MAX_ISOVALUES} (the Isosurface blend mode draws the surfaces of \
                 those values)",
                sorted.len()
            )));
        }
        let mut blend = Blend::new(BlendMode::Isosurface, scalar_range);
        blend.isovalues[..sorted.len()].copy_from_slice(&sorted);
        blend.isovalue_count = sorted.len();
        Ok(blend)
    }

    /// The isosurface values in use, increasing.
    pub fn isovalues(&self) -> &[f64] {
        &self.isovalues[..self.isovalue_count.min(MAX_ISOVALUES)]
    }

    /// The isovalues the ray crosses going from value `v0` to `v1` (see the
    /// module documentation), nearest `v0` first: `v0 < c <= v1` or
    /// `v1 <= c < v0`; none when either is NaN.
    #[inline]
    pub fn crossings(&self, v0: f64, v1: f64) -> impl Iterator<Item = f64> + '_ {
        let values = self.isovalues();
        let rising = values.iter().copied().filter(move |&c| v0 < v1 && v0 < c && c <= v1);
        let falling = values.iter().rev().copied().filter(move |&c| v1 < v0 && v1 <= c && c < v0);
        rising.chain(falling)
    }

    /// `n(v) = (v - lo) / (hi - lo)`, 0 when `hi <= lo`.
    #[inline]
    pub fn normalise(&self, v: f64) -> f64 {
        let [lo, hi] = self.scalar_range;
        if hi > lo {
            (v - lo) / (hi - lo)
        } else {
            0.0
        }
    }

    /// True when an average counts `v` (`v` in AverageIPScalarRange, closed).
    #[inline]
    pub fn averages(&self, v: f64) -> bool {
        self.average_range[0] <= v && v <= self.average_range[1]
    }

    /// The selection's transparency test under this mode: whether a node of
    /// values `[min, max]` can change a picture, given `visible`, the
    /// transfer function's test on a value range.
    ///
    /// - Composite, additive: the node's own range (`a = 0` adds nothing).
    /// - Maximum: a left-out node changes a ray's max `m` only when it held
    ///   it; the ray's max without it is still in `[lo, m]`, so it is
    ///   invisible when `a = 0` on `[lo, max]` (lo the volume's minimum).
    /// - Minimum: likewise on `[min, hi]`.
    /// - Average: a sample counts whatever its opacity: only a node of no
    ///   value in AverageIPScalarRange is left out.
    /// - Isosurface: a crossing shows in the brick of the sample after it,
    ///   which need not hold the isovalue itself: every node is kept unless
    ///   no isovalue is visible (`a(c) = 0` for each).
    /// - Slice: the node's own range (its box meeting the plane is the
    ///   selection's other test, [`super::select::SelectOptions::slice`]);
    ///   nothing without a plane.
    pub fn visible(&self, min: f64, max: f64, visible: &dyn Fn(f64, f64) -> bool) -> bool {
        let [lo, hi] = self.scalar_range;
        match self.mode {
            BlendMode::Composite | BlendMode::Additive => visible(min, max),
            BlendMode::Mip => visible(lo.min(min), max),
            BlendMode::Minip => visible(min, hi.max(max)),
            BlendMode::Average => !(max < self.average_range[0] || min > self.average_range[1]),
            BlendMode::Isosurface => self.isovalues().iter().any(|&c| visible(c, c)),
            BlendMode::Slice => self.slice.is_some() && visible(min, max),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_vtk_values_map() {
        for (i, m) in BlendMode::ALL.into_iter().enumerate() {
            assert_eq!(m.name().parse::<BlendMode>().unwrap(), m);
            assert_eq!(BlendMode::from_vtk(i as i32), Some(m));
        }
        assert_eq!(BlendMode::from_vtk(7), None);
        assert_eq!(BlendMode::Slice.pass(), "volume-slice");
        assert_eq!(BlendMode::from_vtk(-1), None);
        assert_eq!(BlendMode::Mip.pass(), "volume-mip");
        assert_eq!(BlendMode::Composite.pass(), "volume");
        let e = "max".parse::<BlendMode>().unwrap_err().to_string();
        assert!(e.contains("'max'") && e.contains("mip"), "{e}");
    }

    /// A node above the opaque band still decides a MIP (its max hides the
    /// band's values behind a transparent one); below it, it cannot.
    #[test]
    fn transparency_test_per_mode() {
        let band = |a: f64, b: f64| b >= 0.3 && a <= 0.5; // opacity > 0 on [0.3, 0.5]
        let mip = Blend::new(BlendMode::Mip, [0.0, 1.0]);
        assert!(mip.visible(0.8, 1.0, &band) && !mip.visible(0.0, 0.2, &band));
        let minip = Blend::new(BlendMode::Minip, [0.0, 1.0]);
        assert!(minip.visible(0.0, 0.2, &band) && !minip.visible(0.8, 1.0, &band));
        let composite = Blend::default();
        assert!(!composite.visible(0.8, 1.0, &band) && !composite.visible(0.0, 0.2, &band));
        let mut average = Blend::new(BlendMode::Average, [0.0, 1.0]);
        assert!(average.visible(0.8, 1.0, &band));
        average.average_range = [0.25, 0.75];
        assert!(!average.visible(0.8, 1.0, &band) && average.visible(0.7, 1.0, &band));
        assert_eq!(Blend::new(BlendMode::Average, [2.0, 2.0]).normalise(2.0), 0.0);
        let iso = Blend::isosurfaces(&[0.4, 0.9], [0.0, 1.0]).unwrap();
        assert!(iso.visible(0.0, 0.1, &band), "a crossing may show in a brick without the value");
        assert!(!Blend::isosurfaces(&[0.9], [0.0, 1.0]).unwrap().visible(0.0, 1.0, &band));
    }

    /// VTK's table rule: Composite by the power, Additive linearly, the others as given.
    #[test]
    fn opacity_per_reference_follows_vtk_per_mode() {
        let (a, ratio) = (0.3, 0.2);
        let composite = BlendMode::Composite.opacity_per_reference(a, ratio);
        assert!((composite - (1.0 - 0.7f64.powf(0.2))).abs() < 1e-15);
        // Five layers of d0 = U / 5 are one layer of U.
        assert!((1.0 - (1.0 - composite).powi(5) - a).abs() < 1e-12);
        assert!((BlendMode::Additive.opacity_per_reference(a, ratio) - 0.06).abs() < 1e-15);
        assert_eq!(BlendMode::Additive.opacity_per_reference(0.5, 4.0), 1.0);
        for mode in [BlendMode::Mip, BlendMode::Minip, BlendMode::Average, BlendMode::Isosurface, BlendMode::Slice] {
            assert_eq!(mode.opacity_per_reference(a, ratio), a, "{mode:?}");
        }
        assert_eq!(BlendMode::Composite.opacity_per_reference(1.0, 0.2), 1.0);
        assert_eq!(BlendMode::Composite.opacity_per_reference(a, 0.0), a);
        assert_eq!(BlendMode::Composite.opacity_per_reference(1.5, f64::NAN), 1.0);
    }

    /// Every value crossed in a step, nearest where the ray comes from first.
    #[test]
    fn crossings() {
        let iso = Blend::isosurfaces(&[0.7, 0.3, 0.5, 0.3], [0.0, 1.0]).unwrap();
        assert_eq!(iso.isovalues(), &[0.3, 0.5, 0.7]);
        let all = |v0, v1| iso.crossings(v0, v1).collect::<Vec<f64>>();
        assert_eq!(all(0.2, 0.6), vec![0.3, 0.5]);
        assert_eq!(all(0.6, 0.2), vec![0.5, 0.3]);
        assert_eq!(all(0.3, 0.4), Vec::<f64>::new(), "leaving a value is no crossing");
        assert_eq!(all(0.2, 0.3), vec![0.3], "reaching it is");
        assert_eq!(all(0.5, 0.5), Vec::<f64>::new());
        assert_eq!(all(f64::NAN, 0.5), Vec::<f64>::new());
        assert_eq!(all(0.5, f64::NAN), Vec::<f64>::new());
        assert!(Blend::isosurfaces(&[], [0.0, 1.0]).is_err());
        assert!(Blend::isosurfaces(&[f64::NAN], [0.0, 1.0]).unwrap_err().to_string().contains("finite"));
        let many: Vec<f64> = (0..20).map(f64::from).collect();
        assert!(Blend::isosurfaces(&many, [0.0, 1.0]).unwrap_err().to_string().contains("20 isosurface values"));
    }
}
