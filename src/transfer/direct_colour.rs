//! The colour of an RGBA volume with dependent components (VTK's
//! `IndependentComponentsOff` on a 4-component array; ParaView's *Map
//! Scalars* off with *Multi Components Mapping* on): components 0, 1, 2
//! are the red, green and blue themselves, each scaled as VTK 9.2's GPU ray
//! caster scales a texel before the shader reads it (`vtkVolumeTexture`:
//! the texture holds the value normalised by its GL type, and the shader's
//! `scalar * in_volume_scale + in_volume_bias` maps the component's finite
//! range `[lo, hi]` to `[0, 1]`; `computeColor` returns
//! `clamp(computeLighting(vec4(scalar.xyz, opacity), 3, 0), 0, 1)`).
//!
//! For a component value `v` (`vtkVolumeTexture::GetScaleAndBias`):
//!
//! ```text
//! t      = v / n                        (the GL texel: n = 255 for u8, 127 for i8,
//!                                        65535 for u16, 32767 for i16, 1 for others)
//! [a, b] = [lo, hi] g                   (the range in GL units: g = 1/256 for u8,
//!                                        1/128 for i8, 1/65536 for u16, 1/32768 for i16, 1 for others)
//! w      = b - a, or 1e-6 when b == a   (a constant component)
//! s(v)   = (t - a) / w = v (1 / (n w)) - a / w
//! ```
//!
//! so a u8 component of range `[0, 255]` gives `s = 256 v / 255^2`, 1.0039
//! at 255 (VTK's `VTK_UNSIGNED_CHAR_MAX + 1` against GL's 255), and a
//! constant one gives 0 where `v g = a`, else a large value the final clamp
//! makes 1 (a constant u8 component `v > 0`: `(v/255 - v/256) 1e6 > 1`).
//! The colour is clamped to `[0, 1]` after the shading.

use crate::data::grid::ScalarType;

/// `s(v) = scale v + bias` of one colour component (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComponentScale {
    /// `1 / (n w)`.
    pub scale: f64,
    /// `-a / w`.
    pub bias: f64,
}

impl ComponentScale {
    /// VTK 9.2's scaling of a component of type `scalar_type` whose finite
    /// values span `range` (module documentation).
    pub fn vtk(scalar_type: ScalarType, range: (f64, f64)) -> ComponentScale {
        let (n, g) = match scalar_type {
            ScalarType::U8 => (255.0, 1.0 / 256.0),
            ScalarType::I8 => (127.0, 1.0 / 128.0),
            ScalarType::U16 => (65535.0, 1.0 / 65536.0),
            ScalarType::I16 => (32767.0, 1.0 / 32768.0),
            _ => (1.0, 1.0),
        };
        let (a, b) = (range.0 * g, range.1 * g);
        let w = if b == a { 1e-6 } else { b - a };
        ComponentScale { scale: 1.0 / (n * w), bias: -a / w }
    }

    /// `s(v)`, unclamped (NaN for NaN).
    #[inline]
    pub fn apply(&self, v: f64) -> f64 {
        self.scale * v + self.bias
    }
}

/// The scalings of the red, green and blue components.
pub type RgbScale = [ComponentScale; 3];

#[cfg(test)]
mod tests {
    use super::*;

    /// u8 over `[0, 255]`: 256 v / 255^2 (1.0039 at 255); a float range maps
    /// to `[0, 1]` exactly; constant components give 0 at a float value and
    /// more than 1 (clamped to 1) at a u8 value above 0; i16's snorm scaling.
    #[test]
    fn scales_as_vtk_volume_texture() {
        let u8s = ComponentScale::vtk(ScalarType::U8, (0.0, 255.0));
        assert!((u8s.apply(255.0) - 256.0 / 255.0).abs() < 1e-12);
        assert_eq!(u8s.apply(0.0), 0.0);
        assert!((u8s.apply(128.0) - 128.0 * 256.0 / (255.0 * 255.0)).abs() < 1e-12);
        let part = ComponentScale::vtk(ScalarType::U8, (10.0, 200.0));
        assert!((part.apply(10.0) - (10.0 * 256.0 / 255.0 - 10.0) / 190.0).abs() < 1e-12);
        let f = ComponentScale::vtk(ScalarType::F32, (-2.0, 6.0));
        assert_eq!((f.apply(-2.0), f.apply(2.0), f.apply(6.0)), (0.0, 0.5, 1.0));
        let constant = ComponentScale::vtk(ScalarType::F64, (3.0, 3.0));
        assert_eq!(constant.apply(3.0), 0.0);
        let constant_u8 = ComponentScale::vtk(ScalarType::U8, (40.0, 40.0));
        assert!(constant_u8.apply(40.0) > 1.0);
        assert!(ComponentScale::vtk(ScalarType::U8, (0.0, 0.0)).apply(0.0).abs() < 1e-9);
        let i16s = ComponentScale::vtk(ScalarType::I16, (-100.0, 100.0));
        let expect = |v: f64| (v / 32767.0 - (-100.0 / 32768.0)) / (200.0 / 32768.0);
        assert!((i16s.apply(50.0) - expect(50.0)).abs() < 1e-9);
        assert!(f.apply(f64::NAN).is_nan());
    }
}
