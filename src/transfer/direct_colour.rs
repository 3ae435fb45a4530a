//! The colour and opacity of an RGBA volume with dependent components
//! (VTK's `IndependentComponentsOff` on a 4-component array; ParaView's
//! *Map Scalars* off with *Multi Components Mapping*), as VTK 9.2's GPU ray
//! caster computes them (`vtkOpenGLGPUVolumeRayCastMapper` passes
//! `in_volume_scale` 1 and `in_volume_bias` 0 for dependent RGBA, so the
//! shader's `scalar` is the texel as GL reads it; `computeColor` returns
//! `clamp(computeLighting(vec4(scalar.xyz, opacity), 0, 0), 0, 1)`;
//! `computeOpacity` reads the opacity table, made over component 3's
//! finite range `[lo, hi]`, at `scalar.w`).
//!
//! For a component value `v`, the texel `s(v)` (`vtkVolumeTexture`):
//!
//! ```text
//! u8:  v / 255      i8:  v / 127      u16: v / 65535      i16: v / 32767   (GL's normalized textures)
//! f32: v                                                                  (RGBA32F, as is)
//! u32, i32, f64: (v - lo_k) / (hi_k - lo_k)   (scaled to the component's range at upload;
//!                                              a constant component: (v - lo_k) 1e6)
//! ```
//!
//! The colour is `(s_0, s_1, s_2)`, clamped to `[0, 1]` after the shading;
//! the opacity is the scalar opacity function at the value the table holds
//! at coordinate `s_3`,
//!
//! ```text
//! v'(v) = lo + clamp(s_3(v), 0, 1) (hi - lo)
//! ```
//!
//! (the value itself for u8 data of range `[0, 255]`; `lo + v (hi - lo)`
//! for float data). `s` and `v'` are affine in `v` (up to the clamp): the
//! fields can be interpolated before or after.

use crate::data::grid::ScalarType;

/// `s(v) = scale v + bias` of one component (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComponentScale {
    /// The factor of `v`.
    pub scale: f64,
    /// The offset.
    pub bias: f64,
}

impl ComponentScale {
    /// VTK 9.2's texel of a component of type `scalar_type` whose finite
    /// values span `range` (module documentation).
    pub fn vtk(scalar_type: ScalarType, range: (f64, f64)) -> ComponentScale {
        let normalized = |n: f64| ComponentScale { scale: 1.0 / n, bias: 0.0 };
        match scalar_type {
            ScalarType::U8 => normalized(255.0),
            ScalarType::I8 => normalized(127.0),
            ScalarType::U16 => normalized(65535.0),
            ScalarType::I16 => normalized(32767.0),
            ScalarType::F32 => ComponentScale { scale: 1.0, bias: 0.0 },
            ScalarType::U32 | ScalarType::I32 | ScalarType::F64 => {
                let w = if range.1 == range.0 { 1e-6 } else { range.1 - range.0 };
                ComponentScale { scale: 1.0 / w, bias: -range.0 / w }
            }
        }
    }

    /// `s(v)`, unclamped (NaN for NaN).
    #[inline]
    pub fn apply(&self, v: f64) -> f64 {
        self.scale * v + self.bias
    }
}

/// VTK's reading of an RGBA volume's four components (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RgbaScale {
    /// The texels of components 0, 1, 2: the colour.
    pub rgb: [ComponentScale; 3],
    /// The texel of component 3.
    pub alpha: ComponentScale,
    /// Component 3's finite range `[lo, hi]`, the opacity table's.
    pub alpha_range: (f64, f64),
}

impl RgbaScale {
    /// VTK 9.2's reading of four components of type `scalar_type` whose
    /// finite values span `ranges`.
    pub fn vtk(scalar_type: ScalarType, ranges: [(f64, f64); 4]) -> RgbaScale {
        RgbaScale {
            rgb: [0, 1, 2].map(|k| ComponentScale::vtk(scalar_type, ranges[k])),
            alpha: ComponentScale::vtk(scalar_type, ranges[3]),
            alpha_range: ranges[3],
        }
    }

    /// `v'(v)`: the value the opacity function is read at for component 3's
    /// value `v` (NaN for NaN).
    #[inline]
    pub fn opacity_value(&self, v: f64) -> f64 {
        let (lo, hi) = self.alpha_range;
        lo + self.alpha.apply(v).clamp(0.0, 1.0) * (hi - lo)
    }

    /// `v'` as an affine map `v' = a v + b` before its clamp to `[lo, hi]`.
    pub fn opacity_affine(&self) -> (f64, f64) {
        let (lo, hi) = self.alpha_range;
        (self.alpha.scale * (hi - lo), lo + self.alpha.bias * (hi - lo))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The texels by type (normalized integers, raw floats, range-scaled
    /// wide types, a constant wide component), and the opacity value: the
    /// value itself for u8 over [0, 255], `lo + v (hi - lo)` for floats,
    /// clamped to the range.
    #[test]
    fn reads_as_vtk_9_2() {
        let u8s = ComponentScale::vtk(ScalarType::U8, (10.0, 200.0));
        assert!((u8s.apply(255.0) - 1.0).abs() < 1e-15 && u8s.apply(0.0) == 0.0);
        assert!((ComponentScale::vtk(ScalarType::I16, (0.0, 1.0)).apply(32767.0) - 1.0).abs() < 1e-15);
        let f = ComponentScale::vtk(ScalarType::F32, (-20.0, 80.0));
        assert_eq!((f.apply(-20.0), f.apply(0.5)), (-20.0, 0.5));
        let d = ComponentScale::vtk(ScalarType::F64, (-2.0, 6.0));
        assert_eq!((d.apply(-2.0), d.apply(2.0), d.apply(6.0)), (0.0, 0.5, 1.0));
        let constant = ComponentScale::vtk(ScalarType::I32, (3.0, 3.0));
        assert_eq!(constant.apply(3.0), 0.0);
        assert!(constant.apply(4.0) > 1.0);
        let full = RgbaScale::vtk(ScalarType::U8, [(0.0, 255.0); 4]);
        assert!((full.opacity_value(77.0) - 77.0).abs() < 1e-12);
        let part = RgbaScale::vtk(ScalarType::U8, [(0.0, 255.0), (0.0, 255.0), (0.0, 255.0), (10.0, 200.0)]);
        assert!((part.opacity_value(255.0) - 200.0).abs() < 1e-12);
        assert!((part.opacity_value(51.0) - (10.0 + 0.2 * 190.0)).abs() < 1e-12);
        let floats = RgbaScale::vtk(ScalarType::F32, [(0.0, 1.0), (0.0, 1.0), (0.0, 1.0), (0.0, 2.0)]);
        assert_eq!((floats.opacity_value(0.25), floats.opacity_value(1.5)), (0.5, 2.0));
        let (a, b) = floats.opacity_affine();
        assert_eq!((a * 0.25 + b, a, b), (0.5, 2.0, 0.0));
        assert!(floats.opacity_value(f64::NAN).is_nan());
    }
}
