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
}

impl BlendMode {
    /// Every mode, in VTK's order.
    pub const ALL: [BlendMode; 5] =
        [BlendMode::Composite, BlendMode::Mip, BlendMode::Minip, BlendMode::Average, BlendMode::Additive];

    /// The mode's name: `composite`, `mip`, `minip`, `average`, `additive`.
    pub fn name(self) -> &'static str {
        match self {
            BlendMode::Composite => "composite",
            BlendMode::Mip => "mip",
            BlendMode::Minip => "minip",
            BlendMode::Average => "average",
            BlendMode::Additive => "additive",
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
    /// 1 maximum, 2 minimum, 3 average, 4 additive); `None` for the others
    /// (5 isosurface, 6 slice) and unknown values.
    pub fn from_vtk(value: i32) -> Option<BlendMode> {
        BlendMode::ALL.get(usize::try_from(value).ok()?).copied()
    }

    /// True for the modes that reduce a ray to its largest or smallest value.
    pub fn is_extremum(self) -> bool {
        matches!(self, BlendMode::Mip | BlendMode::Minip)
    }
}

impl std::str::FromStr for BlendMode {
    type Err = crate::Error;
    fn from_str(s: &str) -> crate::Result<BlendMode> {
        BlendMode::ALL.into_iter().find(|m| m.name() == s).ok_or_else(|| {
            crate::Error::InvalidArgument(format!(
                "blend mode '{}': give one of composite, mip, minip, average, additive",
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
}

impl Default for Blend {
    fn default() -> Blend {
        Blend::new(BlendMode::Composite, [0.0, 1.0])
    }
}

impl Blend {
    /// `mode` over a volume of scalar range `scalar_range`, averaging every value.
    pub fn new(mode: BlendMode, scalar_range: [f64; 2]) -> Blend {
        Blend { mode, scalar_range, average_range: [f64::MIN, f64::MAX] }
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
    pub fn visible(&self, min: f64, max: f64, visible: &dyn Fn(f64, f64) -> bool) -> bool {
        let [lo, hi] = self.scalar_range;
        match self.mode {
            BlendMode::Composite | BlendMode::Additive => visible(min, max),
            BlendMode::Mip => visible(lo.min(min), max),
            BlendMode::Minip => visible(min, hi.max(max)),
            BlendMode::Average => !(max < self.average_range[0] || min > self.average_range[1]),
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
        assert_eq!(BlendMode::from_vtk(5), None);
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
    }
}
