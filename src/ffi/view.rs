//! The view a selection is made for ([`ViewDesc`]): the mapper's camera,
//! viewport and ViewSelection turned into the [`ViewImportance`] the
//! handle's `Selector` weighs nodes by (`plan::select::view`).
//!
//! The visibility importance (the transmittance in front of a node) needs
//! the opacity of a single field composited front to back: it is left out
//! (Visibility selects as Data, Both as Screen, and the summary names what
//! ran) for the other blend modes, for two dependent fields or an RGBA
//! volume, and where cropping, clipping planes or a slice remove samples
//! (an occluder removed would otherwise hide what the viewer sees). The
//! smallest opacity of a node is that of the scalar opacity points over
//! its range,
//!
//! ```text
//! alpha_min(n) = g * min over [min(n), max(n)] of opacity(v)     (a layer d0 thick)
//! ```
//!
//! with `d0` VTK's ScalarOpacityUnitDistance and `g` a constant gradient
//! opacity (1 without one); a gradient opacity that varies, or a 2D transfer
//! function that classifies, may make any sample transparent: `alpha_min = 0`
//! (only an opaque isosurface then hides anything).

use super::guard::{guarded, Bridged};
use super::octree::HybridOctreeHandle;
use super::render::camera;
use super::transfer::opacity_function;
use super::{CameraDesc, SelectDesc, ViewDesc};
use crate::error::{Error, Result};
use crate::octree::VolumeOctree;
use crate::plan::select::{Occluder, ViewImportance, ViewInputs, ViewSelection};
use crate::transfer::GradientOpacity;

/// What besides `desc.view` decides whether the visibility importance applies.
pub(crate) struct ViewScene<'a> {
    /// The blend mode is Composite.
    pub composite: bool,
    /// One scalar field (not two dependent ones, not an RGBA volume).
    pub single_field: bool,
    /// Cropping, clipping planes or a slice remove samples.
    pub removes_samples: bool,
    /// The gradient opacity of the frame, if any.
    pub gradient_opacity: Option<&'a GradientOpacity>,
    /// A 2D transfer function classifies.
    pub transfer_2d: bool,
}

/// The checked view of `desc`: its ViewSelection, camera, viewport, smallest
/// texel, surface opacity and opacity unit distance.
pub(crate) fn check(view: &ViewDesc) -> Result<ViewSelection> {
    let mode = ViewSelection::from_index(view.view_selection)?;
    camera(&view.camera)?;
    let [w, h] = view.viewport;
    if w == 0 || h == 0 {
        return Err(Error::InvalidArgument(format!(
            "view selection: viewport {w}x{h} has no pixel; give the renderer's size, at least 1x1"
        )));
    }
    let m = view.min_texel_pixels;
    if !(m >= 0.0 && m.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "smallest texel {m} pixels: give a finite number >= 0 (1: stop refining below a pixel)"
        )));
    }
    if !(0.0..=1.0).contains(&view.surface_opacity) {
        return Err(Error::InvalidArgument(format!(
            "view selection: surface opacity {} must be between 0 and 1",
            view.surface_opacity
        )));
    }
    let d0 = view.opacity_unit_distance;
    if !(d0 > 0.0 && d0.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "view selection: opacity unit distance {d0}: give VTK's ScalarOpacityUnitDistance, a positive number"
        )));
    }
    Ok(mode)
}

/// The ViewSelection that runs for `asked` in `scene`: without visibility
/// where it does not apply (module documentation).
pub(crate) fn applied(asked: ViewSelection, scene: &ViewScene<'_>) -> ViewSelection {
    let visibility = scene.composite && scene.single_field && !scene.removes_samples;
    match asked {
        ViewSelection::Visibility if !visibility => ViewSelection::Data,
        ViewSelection::Both if !visibility => ViewSelection::Screen,
        mode => mode,
    }
}

/// The view importance of `desc` over `tree` (the octree's, of the
/// handle's grid), with the ViewSelection that ran; none for Data.
pub(crate) fn view_importance(
    octree: &HybridOctreeHandle,
    tree: &VolumeOctree,
    desc: &SelectDesc,
    scene: &ViewScene<'_>,
) -> Result<(ViewSelection, Option<ViewImportance>)> {
    let view = &desc.view;
    let mode = applied(check(view)?, scene);
    if mode == ViewSelection::Data {
        return Ok((mode, None));
    }
    let tf = opacity_function(&desc.opacity_points)?;
    let scale = match (scene.transfer_2d, scene.gradient_opacity) {
        (true, _) => 0.0,
        (false, None) => 1.0,
        (false, Some(g)) => g.constant().map_or(0.0, f64::from),
    };
    let min_opacity = |lo: f64, hi: f64| tf.as_ref().map_or(0.0, |tf| scale * f64::from(tf.min_opacity_over(lo, hi)));
    let occluder = (desc.has_isovalue && view.surface_opacity > 0.0)
        .then_some(Occluder { isovalue: desc.isovalue, opacity: view.surface_opacity });
    let camera = camera(&view.camera)?;
    let inputs = ViewInputs {
        camera: &camera,
        width: view.viewport[0],
        height: view.viewport[1],
        shape: &octree.shape,
        min_texel_pixels: view.min_texel_pixels,
        min_opacity: &min_opacity,
        d0: view.opacity_unit_distance,
        occluder,
        has_nan: octree.nan_samples > 0,
    };
    Ok((mode, Some(ViewImportance::new(mode, tree, &inputs)?)))
}

/// [`crate::plan::select::view_change_degrees`] of two bridge cameras, checked.
pub(crate) fn view_change_degrees(a: &CameraDesc, b: &CameraDesc, centre: &[f64]) -> Bridged<f64> {
    guarded(|| {
        let centre: [f64; 3] = match <[f64; 3]>::try_from(centre) {
            Ok(c) if c.iter().all(|v| v.is_finite()) => c,
            _ => {
                return Err(Error::InvalidArgument(format!(
                    "view change around {centre:?}: give a finite centre, x, y and z"
                )))
            }
        };
        Ok(crate::plan::select::view_change_degrees(&camera(a)?, &camera(b)?, centre))
    })
}
