//! View importance: what the viewer sees of a node, for the current camera.
//!
//! ```text
//! Imp(n)     = Imp_roi(n) * Imp_view(n)
//! Imp_view(n) = W_s(n) * T(n)^2
//! p_max(n)   = min(L - k, max brick level, L - k - log2 S_min(n))
//! ```
//!
//! `W_s` and `S_min` come from [`ScreenSpace`], `T` from [`Transmittance`];
//! either may be left out (1 and no cap). `T` is squared because the error
//! mass is a sum of squared errors: a sample's error reaches the pixel
//! through the transmittance in front of it, its square through `T^2`, as
//! its pixel area `W_s` already is a square.

use super::screen::ScreenSpace;
use super::visibility::Transmittance;
use crate::octree::NodeRef;

/// The view importance of one frame (module documentation).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ViewImportance {
    /// Screen-space importance, or none (`W_s = 1`, no cap).
    pub screen: Option<ScreenSpace>,
    /// Visibility importance, or none (`T = 1`).
    pub visibility: Option<Transmittance>,
}

impl ViewImportance {
    /// `Imp_view(n)`.
    pub fn weight(&self, n: &NodeRef<'_>) -> f64 {
        let w = self.screen.as_ref().map_or(1.0, |s| s.weight(n.lo, n.hi));
        let t = self.visibility.as_ref().map_or(1.0, |v| v.at(n.level, n.coords));
        w * t * t
    }

    /// `log2 S_min(n)`: the levels below full resolution where refinement stops.
    pub fn coarsest_levels(&self, n: &NodeRef<'_>) -> usize {
        self.screen.as_ref().map_or(0, |s| s.finest_stride(n.lo, n.hi).trailing_zeros() as usize)
    }

    /// Neither screen space nor visibility: the data-space selection.
    pub fn is_empty(&self) -> bool {
        self.screen.is_none() && self.visibility.is_none()
    }
}
