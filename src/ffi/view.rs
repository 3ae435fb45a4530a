//! The view a selection is made for ([`ViewDesc`]): the mapper's camera,
//! viewport and ViewSelection turned into the [`ViewImportance`] the
//! handle's `Selector` weighs nodes by (`plan::select::view`).
//!
//! The visibility importance (the transmittance in front of a node) needs
//! the opacity of a single field composited front to back: it is left out
//! (Visibility selects as Data, Both as Screen, and the summary names what
//! ran) for the other blend modes, for two dependent fields or an RGBA
//! volume, and where cropping, clipping planes or a slice remove samples
//! (an occluder removed would otherwise hide what the viewer sees). It
//! marches through a [`Medium`] made from the image ([`prepare_view`], once
//! per transfer function, kept in the handle) under the opacity
//!
//! ```text
//! alpha(v) = g_min * opacity(v)     (a layer d0 thick)
//! ```
//!
//! with `opacity` the scalar opacity points (0 without any), `d0` VTK's
//! ScalarOpacityUnitDistance and `g_min` the smallest factor of the
//! gradient opacity (1 without one); under a 2D transfer function `g_min =
//! 0` (any sample may be transparent; only an opaque isosurface then hides
//! anything).

use super::grid::{grid_unscanned, same_image};
use super::guard::{guarded, Bridged};
use super::octree::HybridOctreeHandle;
use super::render::{blend, camera, select_options};
use super::transfer::{opacity_function, vtk_gradient_opacity};
use super::{CameraDesc, GridDesc, SelectDesc, ViewDesc};
use crate::error::{Error, Result};
use crate::plan::select::{Medium, Occluder, ViewImportance, ViewInputs, ViewSelection};
use crate::plan::BlendMode;

/// What besides `desc.view` decides whether and how the visibility applies.
pub(crate) struct ViewScene {
    /// Composite blending of one field with no sample removed: the visibility applies.
    pub visibility: bool,
    /// `g_min` (module documentation).
    pub gradient_min: f64,
}

/// The [`ViewScene`] of a selection of `desc` from `octree`.
pub(crate) fn view_scene(octree: &HybridOctreeHandle, desc: &SelectDesc) -> Result<ViewScene> {
    let range = octree.volume().value_range();
    let gradient_opacity = vtk_gradient_opacity(&desc.gradient_opacity_points, &octree.shape, range)?;
    let transfer_2d = match octree.dependent {
        Some(_) => false,
        None => super::transfer2d::vtk_transfer_2d(desc, &octree.shape)?.is_some(),
    };
    let options = select_options(&octree.shape, desc, gradient_opacity.as_ref(), transfer_2d)?;
    let whole = octree.shape.dims.map(|d| (d - 1) as f64);
    let removes = options.slice.is_some() || options.region.is_some_and(|r| !r.keeps_box([0.0; 3], whole));
    let composite = blend(desc, range)?.mode == BlendMode::Composite;
    let gradient_min = match (transfer_2d, &gradient_opacity) {
        (true, _) => 0.0,
        (false, None) => 1.0,
        (false, Some(g)) => f64::from(g.min_opacity()),
    };
    Ok(ViewScene { visibility: composite && octree.dependent.is_none() && !removes, gradient_min })
}

/// The medium a handle keeps for its next selections, with what it was made from.
#[derive(Default)]
pub(crate) struct KeptMedium {
    made: Option<(MediumKey, Medium)>,
}

impl std::fmt::Debug for KeptMedium {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("KeptMedium").field("kept", &self.made.is_some()).finish_non_exhaustive()
    }
}

/// What a [`Medium`] depends on besides the image (compared exactly).
#[derive(PartialEq)]
struct MediumKey {
    opacity_points: Vec<f64>,
    gradient_min: f64,
    d0: f64,
    occluder: Option<(f64, f64)>,
}

/// The occluder of `desc`: its isosurface when drawn (surface opacity above 0).
fn occluder(desc: &SelectDesc) -> Option<Occluder> {
    (desc.has_isovalue && desc.view.surface_opacity > 0.0)
        .then_some(Occluder { isovalue: desc.isovalue, opacity: desc.view.surface_opacity })
}

fn medium_key(desc: &SelectDesc, scene: &ViewScene) -> MediumKey {
    MediumKey {
        opacity_points: desc.opacity_points.clone(),
        gradient_min: scene.gradient_min,
        d0: desc.view.opacity_unit_distance,
        occluder: occluder(desc).map(|o| (o.isovalue, o.opacity)),
    }
}

/// Whether a selection of `desc` in `scene` marches through a medium.
fn uses_medium(desc: &SelectDesc, scene: &ViewScene) -> Result<bool> {
    Ok(applied(check(&desc.view)?, scene).uses_visibility())
}

trait UsesVisibility {
    fn uses_visibility(self) -> bool;
}

impl UsesVisibility for ViewSelection {
    fn uses_visibility(self) -> bool {
        matches!(self, ViewSelection::Visibility | ViewSelection::Both)
    }
}

/// The medium of `desc` made from the image and kept in `octree`
/// (module documentation); nothing when `desc` does not need one.
pub(crate) fn prepare_view(
    octree: &HybridOctreeHandle,
    bytes: &[u8],
    grid: &GridDesc,
    desc: &SelectDesc,
) -> Bridged<()> {
    guarded(|| {
        let scene = view_scene(octree, desc)?;
        if !uses_medium(desc, &scene)? {
            return Ok(());
        }
        let key = medium_key(desc, &scene);
        let mut kept = octree.medium.lock().unwrap_or_else(|e| e.into_inner());
        if kept.made.as_ref().is_some_and(|(k, _)| *k == key) {
            return Ok(());
        }
        kept.made = None;
        let image = grid_unscanned(bytes, grid)?;
        same_image(&octree.shape, &image)?;
        let tf = opacity_function(&desc.opacity_points)?;
        let g = scene.gradient_min;
        let opacity = |v: f64| tf.as_ref().map_or(0.0, |tf| g * f64::from(tf.opacity(v)));
        let medium = Medium::new(octree.volume(), &image, &opacity, key.d0, occluder(desc))?;
        kept.made = Some((key, medium));
        Ok(())
    })
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
pub(crate) fn applied(asked: ViewSelection, scene: &ViewScene) -> ViewSelection {
    match asked {
        ViewSelection::Visibility if !scene.visibility => ViewSelection::Data,
        ViewSelection::Both if !scene.visibility => ViewSelection::Screen,
        mode => mode,
    }
}

/// The view importance of `desc` (of the handle's grid), with the
/// ViewSelection that ran; none for Data. The visibility marches through
/// the medium [`prepare_view`] kept for `desc`.
pub(crate) fn view_importance(
    octree: &HybridOctreeHandle,
    desc: &SelectDesc,
    scene: &ViewScene,
) -> Result<(ViewSelection, Option<ViewImportance>)> {
    let view = &desc.view;
    let mode = applied(check(view)?, scene);
    if mode == ViewSelection::Data {
        return Ok((mode, None));
    }
    let camera = camera(&view.camera)?;
    let kept = octree.medium.lock().unwrap_or_else(|e| e.into_inner());
    let medium = match &kept.made {
        Some((key, medium)) if *key == medium_key(desc, scene) => Some(medium),
        _ if mode.uses_visibility() => {
            return Err(Error::InvalidArgument(
                "view selection: the visibility estimate needs the image under this transfer function: call \
                 prepare_view (HybridOctree::PrepareView) with it before selecting"
                    .into(),
            ))
        }
        _ => None,
    };
    let inputs = ViewInputs {
        camera: &camera,
        width: view.viewport[0],
        height: view.viewport[1],
        shape: &octree.shape,
        min_texel_pixels: view.min_texel_pixels,
        medium,
    };
    Ok((mode, Some(ViewImportance::new(mode, &inputs)?)))
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
