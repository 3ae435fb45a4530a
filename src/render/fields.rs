//! The fields a sample of a volume with dependent components reads besides
//! the one its texture (or grid) holds, which gives its value and gradient:
//!
//! ```text
//! two fields:  texture = field 0 (colour function, gradient), Opacity = field 1 (opacity function)
//! RGBA:        texture = field 3 (opacity function, gradient), Rgb = fields 0, 1, 2 (the colour,
//!              each s(v) = scale v + bias as VTK scales it, crate::transfer::direct_colour)
//! ```
//!
//! A sample with a NaN in any field it reads is no data: transparent.

use crate::transfer::direct_colour::RgbScale;

/// The other fields of a sample (module documentation), as grids,
/// textures or one brick's texture `T`.
#[derive(Debug, Clone, Copy)]
pub(crate) enum OtherFields<T> {
    /// The opacity field of two dependent fields.
    Opacity(T),
    /// The red, green and blue fields of an RGBA volume, and their scaling.
    Rgb([T; 3], RgbScale),
}

impl<T: Copy> OtherFields<T> {
    /// The same fields through `f` (e.g. all textures to one brick's).
    pub(crate) fn map<U>(self, mut f: impl FnMut(T) -> U) -> OtherFields<U> {
        match self {
            OtherFields::Opacity(o) => OtherFields::Opacity(f(o)),
            OtherFields::Rgb(t, s) => OtherFields::Rgb(t.map(f), s),
        }
    }

    /// [`Self::map`] through a fallible `f`.
    pub(crate) fn try_map<U, E>(self, mut f: impl FnMut(T) -> Result<U, E>) -> Result<OtherFields<U>, E> {
        Ok(match self {
            OtherFields::Opacity(o) => OtherFields::Opacity(f(o)?),
            OtherFields::Rgb([r, g, b], s) => OtherFields::Rgb([f(r)?, f(g)?, f(b)?], s),
        })
    }
}

/// The sample's colour `c` and opacity `a` (the transfer function's at the
/// value `value`) once the other fields are read through `at` (a field's
/// value at the sample): the opacity function at the opacity field, or the
/// scaled RGB components; transparent when a field read, or `value`, is NaN.
#[inline]
pub(crate) fn classify_other<T: Copy>(
    other: OtherFields<T>,
    value: f64,
    c: [f64; 3],
    a: f64,
    opacity: impl Fn(f64) -> f64,
    at: impl Fn(T) -> f64,
) -> ([f64; 3], f64) {
    if value.is_nan() {
        return (c, 0.0);
    }
    match other {
        OtherFields::Opacity(o) => (c, opacity(at(o))),
        OtherFields::Rgb(t, s) => {
            let rgb = [0, 1, 2].map(|k| s[k].apply(at(t[k])));
            if rgb.iter().any(|v| v.is_nan()) {
                (c, 0.0)
            } else {
                (rgb, a)
            }
        }
    }
}

/// The final clamp of an RGBA volume's shaded colour to `[0, 1]` (VTK's
/// `clamp(computeLighting(..), 0, 1)`); other colours unchanged.
#[inline]
pub(crate) fn clamp_rgb<T>(other: Option<&OtherFields<T>>, c: [f64; 3]) -> [f64; 3] {
    match other {
        Some(OtherFields::Rgb(..)) => c.map(|v| v.clamp(0.0, 1.0)),
        _ => c,
    }
}
