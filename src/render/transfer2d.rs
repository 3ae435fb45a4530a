//! The 2D transfer function in the renderers (the plan's effect
//! `transfer-2d`, [`crate::transfer::transfer2d`]): a sample's colour and
//! opacity from its value `v` and the magnitude of its gradient `g` (the
//! rule of `super::shade`, the same gradient the shading then uses):
//!
//! ```text
//! [r, g, b, a] = T(v, |g|)
//! ```
//!
//! in place of the 1D function's `(c(v), a(v))`; the opacity is then
//! corrected for the slice spacing and the colour shaded as the 1D
//! function's.

use crate::geometry::vec3::dot;
use crate::transfer::TransferFunction2D;

/// `T(v, |g|)` of the sample of value `value` and gradient `g`, in f64.
#[inline]
pub(crate) fn classify(t: &TransferFunction2D, value: f64, g: [f64; 3]) -> [f64; 4] {
    t.eval(value, dot(g, g).sqrt()).map(f64::from)
}
