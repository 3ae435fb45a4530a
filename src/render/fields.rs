//! The fields a sample of a volume with dependent components reads besides
//! the one its texture (or grid) holds, which gives its value and gradient:
//!
//! ```text
//! two fields:  texture = field 0 (colour function, gradient), Opacity = field 1 (opacity function)
//! RGBA:        texture = field 0 (red, gradient), Rgba = fields 1, 2 (green, blue) and 3 (opacity
//!              function at v'(field 3)); each read as VTK 9.2 reads it, crate::transfer::direct_colour
//! ```
//!
//! A sample with a NaN in any field it reads is no data: transparent.

use crate::transfer::direct_colour::RgbaScale;

/// The other fields of a sample (module documentation), as grids,
/// textures or one brick's texture `T`.
#[derive(Debug, Clone, Copy)]
pub(crate) enum OtherFields<T> {
    /// The opacity field of two dependent fields.
    Opacity(T),
    /// The green and blue fields and the alpha field of an RGBA volume
    /// (the texture's is red), and VTK's reading of them.
    Rgba([T; 2], T, RgbaScale),
}

impl<T: Copy> OtherFields<T> {
    /// The same fields through `f` (e.g. all textures to one brick's).
    pub(crate) fn map<U>(self, mut f: impl FnMut(T) -> U) -> OtherFields<U> {
        match self {
            OtherFields::Opacity(o) => OtherFields::Opacity(f(o)),
            OtherFields::Rgba([g, b], a, s) => OtherFields::Rgba([f(g), f(b)], f(a), s),
        }
    }

    /// [`Self::map`] through a fallible `f`.
    pub(crate) fn try_map<U, E>(self, mut f: impl FnMut(T) -> Result<U, E>) -> Result<OtherFields<U>, E> {
        Ok(match self {
            OtherFields::Opacity(o) => OtherFields::Opacity(f(o)?),
            OtherFields::Rgba([g, b], a, s) => OtherFields::Rgba([f(g)?, f(b)?], f(a)?, s),
        })
    }
}

/// The sample's colour and opacity, its colour `c` the transfer function's
/// at the value `value`, once the other fields are read through `at` (a field's
/// value at the sample): the opacity function at the opacity field, or an
/// RGBA volume's colour (`value` its red) and the opacity function at
/// `v'` of its alpha; transparent when a field read, or `value`, is NaN.
#[inline]
pub(crate) fn classify_other<T: Copy>(
    other: OtherFields<T>,
    value: f64,
    c: [f64; 3],
    opacity: impl Fn(f64) -> f64,
    at: impl Fn(T) -> f64,
) -> ([f64; 3], f64) {
    if value.is_nan() {
        return (c, 0.0);
    }
    match other {
        OtherFields::Opacity(o) => (c, opacity(at(o))),
        OtherFields::Rgba([g, b], alpha, s) => {
            let rgb = [s.rgb[0].apply(value), s.rgb[1].apply(at(g)), s.rgb[2].apply(at(b))];
            let v = s.opacity_value(at(alpha));
            if rgb.iter().any(|v| v.is_nan()) || v.is_nan() {
                (c, 0.0)
            } else {
                (rgb, opacity(v))
            }
        }
    }
}

/// The final clamp of an RGBA volume's shaded colour to `[0, 1]` (VTK's
/// `clamp(computeLighting(..), 0, 1)`); other colours unchanged.
#[inline]
pub(crate) fn clamp_rgb<T>(other: Option<&OtherFields<T>>, c: [f64; 3]) -> [f64; 3] {
    match other {
        Some(OtherFields::Rgba(..)) => c.map(|v| v.clamp(0.0, 1.0)),
        _ => c,
    }
}
