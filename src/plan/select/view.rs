//! View importance: what the viewer sees of a node, for the current camera.
//!
//! ```text
//! Imp(n)     = Imp_roi(n) * Imp_view(n)
//! Imp_view(n) = W_s(n) * T(n)
//! p_max(n)   = min(L - k, max brick level, L - k - log2 S_min(n))
//! ```
//!
//! `W_s` and `S_min` come from [`ScreenSpace`], `T` from [`Transmittance`];
//! either may be left out (1 and no cap). A sample's error reaches its
//! pixel through the transmittance in front of it, so the error mass could
//! take `T^2`; `T` itself is what `bench render` measured best (RMSE
//! against the full-resolution picture of an 8-bit MRI at the stride-4
//! budget: 0.55 of uniform with `T`, 0.59 with `T^2`, 0.68 with `T^3`),
//! the estimate of `T` being coarse: a node a little more hidden than the
//! estimate says keeps its share.

use super::screen::ScreenSpace;
use super::visibility::{Medium, Transmittance};
use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::geometry::camera::{Camera, Projection};
use crate::octree::{Layout, NodeId, NodeRef};

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
        w * t
    }

    /// `T(n)` of node `id` of an octree laid out by `layout` (1 without a visibility estimate).
    pub fn transmittance(&self, layout: &Layout, id: NodeId) -> f64 {
        self.visibility.as_ref().map_or(1.0, |t| {
            let (level, coords) = layout.locate(id);
            t.at(level, coords)
        })
    }

    /// `log2 S_min(n)`: the levels below full resolution where refinement stops.
    pub fn coarsest_levels(&self, n: &NodeRef<'_>) -> usize {
        self.screen.as_ref().map_or(0, |s| s.finest_stride(n.lo, n.hi).trailing_zeros() as usize)
    }

    /// Whether [`ViewImportance::coarsest_levels`] is above 0 for some node
    /// (a screen space with a pixel cap).
    pub fn caps(&self) -> bool {
        self.screen.as_ref().is_some_and(ScreenSpace::caps)
    }

    /// Neither screen space nor visibility: the data-space selection.
    pub fn is_empty(&self) -> bool {
        self.screen.is_none() && self.visibility.is_none()
    }
}

/// Which importance a selection weighs nodes by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum ViewSelection {
    /// The data alone: nodal errors and the region of interest.
    #[default]
    Data,
    /// And the screen-space importance ([`ScreenSpace`]).
    Screen,
    /// And the visibility importance ([`Transmittance`]).
    Visibility,
    /// And both.
    Both,
}

impl ViewSelection {
    /// Every mode, in the order of [`ViewSelection::from_index`].
    pub const ALL: [ViewSelection; 4] =
        [ViewSelection::Data, ViewSelection::Screen, ViewSelection::Visibility, ViewSelection::Both];

    /// 0 data, 1 screen, 2 visibility, 3 both (the mapper's setting).
    pub fn from_index(i: i32) -> Result<ViewSelection> {
        usize::try_from(i).ok().and_then(|i| Self::ALL.get(i).copied()).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "view selection {i}: give 0 (data), 1 (screen space), 2 (visibility) or 3 (both)"
            ))
        })
    }

    /// The name the CLI and the benchmarks use.
    pub fn name(self) -> &'static str {
        match self {
            ViewSelection::Data => "data",
            ViewSelection::Screen => "screen",
            ViewSelection::Visibility => "visibility",
            ViewSelection::Both => "both",
        }
    }
}

impl std::str::FromStr for ViewSelection {
    type Err = Error;
    fn from_str(s: &str) -> Result<ViewSelection> {
        Self::ALL.into_iter().find(|m| m.name() == s).ok_or_else(|| {
            Error::InvalidArgument(format!("view selection '{s}': give data, screen, visibility or both"))
        })
    }
}

/// What a view importance is made from: the camera and image, the grid,
/// and for the visibility the medium of the transfer function.
pub struct ViewInputs<'a> {
    /// The camera.
    pub camera: &'a Camera,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// The grid the octree was built on.
    pub shape: &'a GridShape,
    /// Refinement stops below texels of this many pixels (0: never, the CLI's and the mapper's default).
    pub min_texel_pixels: f64,
    /// The coarse opacities the visibility marches through (made once per
    /// transfer function); none: nothing hides anything (every blend mode
    /// but Composite, where each sample counts whatever lies in front).
    pub medium: Option<&'a Medium>,
}

impl ViewImportance {
    /// The view importance `mode` asks for (none for [`ViewSelection::Data`];
    /// no visibility without a medium).
    pub fn new(mode: ViewSelection, inputs: &ViewInputs<'_>) -> Result<ViewImportance> {
        let screen = matches!(mode, ViewSelection::Screen | ViewSelection::Both)
            .then(|| {
                ScreenSpace::new(inputs.camera, inputs.width, inputs.height, inputs.shape, inputs.min_texel_pixels)
            })
            .transpose()?;
        let visibility = match (mode, inputs.medium) {
            (ViewSelection::Visibility | ViewSelection::Both, Some(m)) => {
                Some(Transmittance::estimate(m, inputs.shape, inputs.camera))
            }
            _ => None,
        };
        Ok(ViewImportance { screen, visibility })
    }
}

/// How far the view moved from camera `a` to camera `b` around `centre`
/// (world), in degrees: the angle between the directions from `centre` to
/// the two eyes, or a zoom counted as `|ln(d_b / d_a)|` radians (the
/// distance to `centre`, or the parallel scale), whichever is larger. A
/// selection made for `a` is redone for `b` when this passes a threshold.
pub fn view_change_degrees(a: &Camera, b: &Camera, centre: [f64; 3]) -> f64 {
    use crate::geometry::vec3::{dot, norm, sub};
    let (da, db) = (sub(a.position, centre), sub(b.position, centre));
    let (la, lb) = (norm(da), norm(db));
    let turn = if la > 0.0 && lb > 0.0 { (dot(da, db) / (la * lb)).clamp(-1.0, 1.0).acos() } else { 0.0 };
    let zoom = |x: f64, y: f64| if x > 0.0 && y > 0.0 { (y / x).ln().abs() } else { 0.0 };
    let scale = match (a.projection, b.projection) {
        (Projection::Parallel { scale: x }, Projection::Parallel { scale: y }) => zoom(x, y),
        (Projection::Perspective { view_angle_deg: x }, Projection::Perspective { view_angle_deg: y }) => {
            zoom(x, y).max(zoom(la, lb))
        }
        _ => std::f64::consts::PI,
    };
    let look = |c: &Camera| c.forward();
    let aim = dot(look(a), look(b)).clamp(-1.0, 1.0).acos();
    turn.max(scale).max(aim).to_degrees()
}
