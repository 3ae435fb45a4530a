//! The rendering half of the bridge: a selection made from a Hybrid Octree,
//! its DrawList for a VTK camera, its bricks' texels, and the CPU
//! compositor's picture, for `vtkHybridOctreeVolumeMapper`.
//!
//! The selection, the DrawList and the texel layout are those of the CLI:
//! [`select`] with the transfer function's visibility test,
//! [`HybridOctree::draw_list`](crate::hybrid::HybridOctree::draw_list) (the
//! octree's surface at an opacity, the selection's [`SlabPolygons`] made once
//! per selection and surface), [`brick_texels_f32_into`] (the layout of
//! [`crate::render::texture`]).

use super::grid::{grid_of, grid_unscanned, same_image};
use super::guard::{guarded, write_pixels, Bridged};
use super::octree::HybridOctreeHandle;
use super::transfer::{opacity_function, transfer_function, vtk_gradient_opacity};
use super::view::{view_importance, view_scene};
use super::{CameraDesc, DrawListOutput, GridDesc, RegionDesc, SelectDesc, SelectionSummary, ShadingDesc};
use crate::camera::{Camera, Projection};
use crate::error::{Error, Result};
use crate::grid::{GridShape, ScalarType};
use crate::plan::crop::{ClippingPlane, Cropping, KeptRegion};
use crate::plan::dependent::{rgba_texel_bytes, Fields};
use crate::plan::point_slabs::add_points;
use crate::plan::select::{Roi, SelectOptions, Selection, ViewSelection};
use crate::plan::slab::SlabPolygons;
use crate::plan::texel_format::{TexelEncoding, TexelFormat};
use crate::plan::{
    needs_gradients, plan, recrop, replan_effects, replan_transfer_2d, Blend, BlendMode, DrawList, Scene, SurfacePass,
};
use crate::points::Footprint;
use crate::points::PointSet;
use crate::render::texture::{
    brick_texels_f32_bordered_into, brick_texels_for_blend_f32_into, encoded::brick_texels_encoded_into,
};
use crate::transfer::direct_colour::RgbaScale;
use crate::transfer::lighting::{Light, LightSpace, Lighting, Lights, Material};
use crate::transfer::{GradientOpacity, TransferFunction2D};
use std::sync::{Arc, Mutex};

/// Cells of the gradient opacity table a DrawList carries
/// ([`super::DrawListOutput::gradient_opacity_table`]).
const GRADIENT_OPACITY_TABLE: usize = 4096;

/// A selection, with the octree and grid it was made from.
#[derive(Debug)]
pub struct SelectionHandle {
    pub(crate) selection: Selection,
    pub(crate) octree_id: u64,
    pub(crate) shape: GridShape,
    /// The octree's value range (what 32-bit float texels must resolve).
    pub(crate) value_range: (f64, f64),
    /// The SlabPolygons of the last translucent surface drawn, with its id.
    polygons: Mutex<Option<(u64, SlabPolygons)>>,
    /// The points the selection spent bytes on (the octree held points).
    points: Option<Arc<PointSet>>,
    /// The shading of its DrawLists ([`SelectionHandle::set_shading`]).
    lighting: Mutex<Option<Lighting>>,
    /// The blend mode it was selected for, over the octree's value range.
    pub(crate) blend: Blend,
    /// The gradient opacity of its DrawLists ([`SelectionHandle::set_gradient_opacity`]).
    gradient_opacity: Mutex<Option<GradientOpacity>>,
    /// The cropping and clipping planes it was selected for, world
    /// coordinates: its DrawLists keep only their samples.
    region: Option<KeptRegion>,
    /// The 2D transfer function it was selected for (its DrawLists classify
    /// by it under Composite).
    transfer_2d: Option<TransferFunction2D>,
    /// The brick textures' texel format, resolved for the data (its bytes
    /// are what the selection counted).
    pub(crate) texel: TexelEncoding,
    /// Selected from two dependent fields: its DrawLists plan them (`plan::dependent`).
    pub(crate) dependent: bool,
    /// Selected from an RGBA volume: its DrawLists plan it (`plan::dependent`,
    /// `rgba-components`), its colour components scaled so.
    pub(crate) rgba: Option<RgbaScale>,
    /// The image's scalar type (an RGBA volume's textures: RGBA8 for u8).
    scalar_type: crate::data::grid::ScalarType,
    /// Whether its DrawLists jitter ([`SelectionHandle::set_jittering`]).
    jittering: std::sync::atomic::AtomicBool,
    /// The ray sample distance of the aliasing effects, as `f64` bits (0: none;
    /// [`SelectionHandle::set_sample_distance`]).
    sample_distance: std::sync::atomic::AtomicU64,
    /// The volumetric scattering of its DrawLists (`super::scattering`).
    pub(crate) scattering: Mutex<Option<crate::transfer::Scattering>>,
    /// The view importance it was weighed by (`super::view`).
    view_selection: ViewSelection,
    /// Its slices' least spacing in multiples of `d0` (1: the strides'),
    /// as a frame-time target chose it (`super::timed`).
    pub(crate) slice_factor: std::sync::atomic::AtomicU32,
    /// The bricks drawn while some of a store's are still loading: the
    /// selection with stand-ins for those (`super::loading`); `None`: the
    /// selection itself.
    pub(crate) stand_ins: Mutex<Option<Arc<Selection>>>,
}

/// The cropping and clipping planes of `desc` (`None` when neither is on), checked.
pub(crate) fn region(desc: &RegionDesc) -> Result<Option<KeptRegion>> {
    let planes = &desc.clipping_planes;
    if !planes.len().is_multiple_of(6) {
        return Err(Error::InvalidArgument(format!(
            "{} clipping plane values: give 6 per plane (origin x, y, z, normal x, y, z)",
            planes.len()
        )));
    }
    let planes: Vec<ClippingPlane> = planes
        .chunks_exact(6)
        .map(|p| ClippingPlane { origin: [p[0], p[1], p[2]], normal: [p[3], p[4], p[5]] })
        .collect();
    let cropping = desc.cropping.then_some(Cropping { planes: desc.cropping_planes, flags: desc.cropping_flags });
    if cropping.is_none() && planes.is_empty() {
        return Ok(None);
    }
    KeptRegion::new(cropping, &planes).map(Some)
}

/// `region` as the bridge describes it (cropping off and no planes for `None`).
fn region_desc(region: Option<&KeptRegion>) -> RegionDesc {
    let cropping = region.and_then(|r| r.cropping);
    RegionDesc {
        cropping: cropping.is_some(),
        cropping_planes: cropping.map_or([0.0; 6], |c| c.planes),
        cropping_flags: cropping.map_or(0, |c| c.flags),
        clipping_planes: region
            .iter()
            .flat_map(|r| r.planes())
            .flat_map(|p| p.origin.into_iter().chain(p.normal))
            .collect(),
    }
}

/// The lighting of `desc` (`None` when it does not shade), checked.
pub(crate) fn lighting(desc: &ShadingDesc) -> Result<Option<Lighting>> {
    if !desc.shade {
        return Ok(None);
    }
    let count = desc.light_directions.len() / 3;
    let lists = [&desc.light_directions, &desc.light_ambient, &desc.light_diffuse, &desc.light_specular];
    if lists.iter().any(|l| l.len() != 3 * count) || count == 0 {
        return Err(Error::InvalidArgument(format!(
            "shading: {} light directions and {}, {}, {} ambient, diffuse, specular values: give 3 of each per light, \
             at least one light (a renderer without a switched-on light shades nothing: turn Shade off)",
            desc.light_directions.len(),
            desc.light_ambient.len(),
            desc.light_diffuse.len(),
            desc.light_specular.len()
        )));
    }
    let v = |l: &Vec<f64>, i: usize| [l[3 * i], l[3 * i + 1], l[3 * i + 2]];
    let material = Material {
        ambient: desc.ambient,
        diffuse: desc.diffuse,
        specular: desc.specular,
        specular_power: desc.specular_power,
    };
    let lights = if desc.headlight {
        Lights::Headlight { diffuse: v(&desc.light_diffuse, 0), specular: v(&desc.light_specular, 0) }
    } else {
        Lights::Directional(
            (0..count)
                .map(|i| Light {
                    direction: v(&desc.light_directions, i),
                    space: LightSpace::World,
                    ambient: v(&desc.light_ambient, i),
                    diffuse: v(&desc.light_diffuse, i),
                    specular: v(&desc.light_specular, i),
                })
                .collect(),
        )
    };
    let lighting = Lighting { material, lights, two_sided: desc.two_sided };
    lighting.check()?;
    Ok(Some(lighting))
}

/// The select options of `desc` for a grid of `shape`: the ROI from world
/// to index space (centre through origin and spacing, radius divided by the
/// smallest spacing).
pub(crate) fn select_options(
    shape: &GridShape,
    desc: &SelectDesc,
    gradient_opacity: Option<&GradientOpacity>,
    transfer_2d: bool,
) -> Result<SelectOptions> {
    let roi = if desc.has_roi {
        let (c, r) = (desc.roi_center, desc.roi_radius);
        if c.iter().any(|v| !v.is_finite()) || !(r > 0.0 && r.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "region of interest (centre {c:?}, radius {r}, world units) needs a finite centre and a radius > 0"
            )));
        }
        let min_spacing = shape.spacing.iter().copied().fold(f64::INFINITY, f64::min);
        Some(Roi { center: [0, 1, 2].map(|a| (c[a] - shape.origin[a]) / shape.spacing[a]), radius: r / min_spacing })
    } else {
        None
    };
    Ok(SelectOptions {
        roi,
        pooled: blend_mode(desc.blend_mode)?.is_extremum(),
        // Isosurface reads the sample before a brick's first one, in the border.
        gradient_border: desc.gradient_border
            || blend_mode(desc.blend_mode)? == BlendMode::Isosurface
            || needs_gradients(None, gradient_opacity, transfer_2d, blend_mode(desc.blend_mode)?),
        region: region(&desc.region)?.map(|r| r.to_index(shape)),
        slice: super::slice::slice_plane(desc)?.map(|p| p.to_index(shape)),
        ..SelectOptions::new(desc.budget_bytes, desc.tolerance)
    })
}

/// The blend mode of VTK's value `mode` (0 to 5).
fn blend_mode(mode: i32) -> Result<BlendMode> {
    BlendMode::from_vtk(mode).ok_or_else(|| {
        Error::InvalidArgument(format!(
            "blend mode {mode}: give 0 (composite), 1 (maximum intensity), 2 (minimum intensity), 3 (average \
             intensity), 4 (additive), 5 (isosurface) or 6 (slice)"
        ))
    })
}

/// The blend of `desc` over `value_range` (the octree's), its average range checked.
pub(crate) fn blend(desc: &SelectDesc, value_range: (f64, f64)) -> Result<Blend> {
    let [lo, hi] = desc.average_range;
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return Err(Error::InvalidArgument(format!(
            "average intensity range [{lo}, {hi}]: give two numbers, the first not above the second"
        )));
    }
    let mode = blend_mode(desc.blend_mode)?;
    let mut blend = if mode == BlendMode::Isosurface {
        Blend::isosurfaces(&desc.isosurface_values, [value_range.0, value_range.1])?
    } else if let Some(plane) = super::slice::slice_plane(desc)? {
        Blend::slice(plane, [value_range.0, value_range.1])?
    } else {
        Blend::new(mode, [value_range.0, value_range.1])
    };
    blend.average_range = [lo, hi];
    Ok(blend)
}

/// The CLI's visibility test (`scene::visible`): a node shows unless the
/// opacity is 0 over its whole range or the gradient opacity is 0
/// everywhere (under Composite with a 2D transfer function: unless the
/// table is 0 over its range at every gradient), or when it holds the
/// isovalue; with the octree's points, bytes go to textures or points
/// ([`select_with_points`]). Also the 2D transfer function it read and
/// the texel format it resolved (float32 for dependent components).
pub(crate) fn select_with(
    octree: &HybridOctreeHandle,
    desc: &SelectDesc,
) -> Result<(Selection, Option<TransferFunction2D>, TexelEncoding, ViewSelection)> {
    prepared_with(octree, desc, |p| {
        let selection = p.selector.select_in_view(p.tree, p.options, p.visible, p.points, p.view)?;
        Ok((selection, p.transfer_2d.clone(), p.texel, p.mode))
    })
}

/// What a selection of `desc` is made from, made ready by [`prepared_with`]:
/// the handle's kept selector, the tree, the options, the visibility test,
/// the points' mass, the view importance, and what its handle keeps.
pub(crate) struct Prepared<'a> {
    pub(crate) selector: &'a mut crate::plan::select::Selector,
    pub(crate) tree: &'a crate::octree::VolumeOctree,
    pub(crate) options: &'a SelectOptions,
    pub(crate) visible: &'a dyn Fn(f64, f64) -> bool,
    pub(crate) points: Option<&'a crate::points::PointMass>,
    pub(crate) view: Option<&'a crate::plan::select::ViewImportance>,
    pub(crate) transfer_2d: &'a Option<TransferFunction2D>,
    pub(crate) texel: TexelEncoding,
    pub(crate) mode: ViewSelection,
}

/// Runs `run` on what a selection of `desc` from `octree` is made from
/// (the options checked, the visibility test, the kept selector locked).
pub(crate) fn prepared_with<R>(
    octree: &HybridOctreeHandle,
    desc: &SelectDesc,
    run: impl FnOnce(Prepared<'_>) -> Result<R>,
) -> Result<R> {
    let gradient_opacity =
        vtk_gradient_opacity(&desc.gradient_opacity_points, &octree.shape, octree.volume().value_range())?;
    // A 2D transfer function classifies one field: not two dependent ones (`plan::dependent`).
    let transfer_2d = match octree.dependent {
        Some(_) => None,
        None => super::transfer2d::vtk_transfer_2d(desc, &octree.shape)?,
    };
    let mut options = select_options(&octree.shape, desc, gradient_opacity.as_ref(), transfer_2d.is_some())?;
    // Two dependent fields: two f32 texels a sample, the combined tree (see `dependent.rs`).
    let tree = octree.dependent.as_ref().unwrap_or(octree.volume());
    let range = octree.volume().value_range();
    let texel = match octree.dependent {
        Some(_) => TexelEncoding::float32(octree.scalar_type, range),
        None => TexelEncoding::resolve(
            TexelFormat::from_vtk(desc.texel_format)?,
            octree.scalar_type,
            range,
            octree.nan_samples,
        )?,
    };
    // Bytes as uploaded: two f32 fields, or an RGBA volume's RGBA8 (u8) or RGBA32F texel.
    options.bytes_per_texel = match (&octree.dependent, octree.rgba) {
        (Some(_), Some(_)) => rgba_texel_bytes(octree.scalar_type),
        (Some(_), None) => 2 * texel.bytes(),
        (None, _) => texel.bytes(),
    };
    options.texel_error = texel.normalized_error(range);
    let hidden = gradient_opacity.as_ref().is_some_and(|g| g.constant() == Some(0.0));
    let tf = opacity_function(&desc.opacity_points)?;
    let iso = desc.has_isovalue.then_some(desc.isovalue);
    if iso.is_some_and(|v| !v.is_finite()) {
        return Err(Error::InvalidArgument(format!("isovalue {} must be a finite number", desc.isovalue)));
    }
    let blend = blend(desc, octree.volume().value_range())?;
    // Gradient opacity applies in Composite only.
    let hidden = hidden && blend.mode == BlendMode::Composite;
    let classifies = transfer_2d.as_ref().filter(|_| blend.mode == BlendMode::Composite);
    let shows = |min: f64, max: f64| match classifies {
        Some(t) => !t.is_transparent_over(min, max),
        None => !hidden && tf.as_ref().is_none_or(|tf| !tf.is_transparent_over(min, max)),
    };
    let visible = |min: f64, max: f64| blend.visible(min, max, &shows) || iso.is_some_and(|v| min < v && v <= max);
    // The handle's kept selector (a panic while it was held leaves it poisoned: start afresh).
    let mut kept = octree.selector.lock().unwrap_or_else(|poisoned| {
        let mut kept = poisoned.into_inner();
        *kept = Default::default();
        kept
    });
    octree.selector.clear_poison();
    let scene = view_scene(octree, desc)?;
    let (mode, view) = view_importance(octree, desc, &scene)?;
    let selector = kept.for_desc(desc);
    let points = octree.hybrid.points.as_ref().filter(|_| octree.dependent.is_none()).map(|p| &p.mass);
    run(Prepared {
        selector,
        tree,
        options: &options,
        visible: &visible,
        points,
        view: view.as_ref(),
        transfer_2d: &transfer_2d,
        texel,
        mode,
    })
}

/// The checked camera of `desc`.
pub(crate) fn camera(desc: &CameraDesc) -> Result<Camera> {
    let projection = if desc.parallel {
        Projection::Parallel { scale: desc.parallel_scale }
    } else {
        Projection::Perspective { view_angle_deg: desc.view_angle }
    };
    Camera::new(desc.position, desc.focal_point, desc.view_up, projection)
}

/// `list` flattened (see [`DrawListOutput`]); a brick's index is its place in `selection`.
fn flatten(list: &DrawList, selection: &Selection) -> DrawListOutput {
    let n = list.bricks.len();
    let mut out = DrawListOutput {
        brick: Vec::with_capacity(n),
        node_id: Vec::with_capacity(n),
        bounds: Vec::with_capacity(6 * n),
        texels: Vec::with_capacity(3 * n),
        stride: Vec::with_capacity(n),
        slice_spacing: Vec::with_capacity(n),
        opacity_ratio: Vec::with_capacity(n),
        slice_offsets: Vec::with_capacity(n + 1),
        slices: Vec::new(),
        passes: list.plan.passes.join(","),
        effects: list.plan.effects.join(","),
        transfer_2d_axes: list.transfer_2d.as_ref().map_or([0.0; 3], |t| {
            let [lo, hi] = t.scalar_range();
            [lo, hi, t.gradient_max()]
        }),
        gradients: list.plan.gradients(),
        bordered: list.plan.bordered(),
        blend_mode: list.plan.blend.mode.to_vtk(),
        shading: list.plan.shading,
        texel_format: TexelFormat::ALL.iter().position(|f| *f == list.texel.format).unwrap_or(1) as i32,
        texel_scale: list.texel.scale,
        texel_bias: list.texel.bias,
        texel_bytes: list.texel.bytes() * if list.plan.dependent { 2 } else { 1 },
        rgba_reading: Vec::new(),
        opacity_scale: list.plan.opacity_scale,
        gradient_opacity_table: Vec::new(),
        gradient_opacity_end: 0.0,
        region: region_desc(list.region.as_ref()),
        slice_plane: super::slice::plane_values(list.plan.blend.mode, list.plan.blend.slice.as_ref()),
        reference_spacing: list.reference_spacing,
        forward: list.camera.forward(),
        batch_offsets: Vec::with_capacity(n + 1),
        batch_slab: Vec::new(),
        batch_first: Vec::new(),
        batch_end: Vec::new(),
        batch_clip: Vec::new(),
        opaque_triangles: list.opaque_triangles.len(),
        bucket_offsets: Vec::new(),
        bucket_slab: Vec::new(),
        bucket_point_offsets: Vec::new(),
        bucket_points: Vec::new(),
    };
    if let Some(f) = list.gradient_opacity.as_ref().filter(|_| list.plan.gradient_opacity) {
        out.gradient_opacity_end = f.table_end();
        out.gradient_opacity_table = f.table(out.gradient_opacity_end, GRADIENT_OPACITY_TABLE);
    }
    out.slice_offsets.push(0);
    out.batch_offsets.push(0);
    if list.plan.passes.iter().any(|p| p == "points") {
        out.bucket_offsets.push(0);
        out.bucket_point_offsets.push(0);
        for d in &list.bricks {
            for bucket in &d.points {
                out.bucket_slab.push(bucket.slab);
                out.bucket_points.extend_from_slice(&bucket.points);
                out.bucket_point_offsets.push(out.bucket_points.len());
            }
            out.bucket_offsets.push(out.bucket_slab.len());
        }
    }
    for d in &list.bricks {
        // Bricks are sorted by node id in the selection.
        let index = selection.bricks.binary_search_by_key(&d.brick.node, |b| b.node).expect("a selected brick");
        out.brick.push(index);
        out.node_id.push(d.brick.node.0);
        let (lo, hi) = (d.world_lo, d.world_hi);
        out.bounds.extend_from_slice(&[lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]);
        out.texels.extend_from_slice(&d.brick.texels);
        out.stride.push(d.brick.stride);
        out.slice_spacing.push(d.slice_spacing);
        out.opacity_ratio.push(d.slice_spacing / list.reference_spacing);
        out.slices.extend_from_slice(&d.slices);
        out.slice_offsets.push(out.slices.len());
        for b in &d.batches {
            out.batch_slab.push(b.slab);
            out.batch_first.push(b.triangles.start);
            out.batch_end.push(b.triangles.end);
            let (near, far) = b.clip.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
            out.batch_clip.extend_from_slice(&[near, far]);
        }
        out.batch_offsets.push(out.batch_slab.len());
    }
    out
}

/// Refuses data whose differences 32-bit float texels cannot resolve: a
/// value of magnitude `m` is off by up to `m 2^-24` in an `f32`; when that is
/// more than one cell of a 4096-cell table, `(max - min) / 4096` (e.g. a
/// `1e-3` range on a `1e9` offset), the GPU picture would be noise. Only
/// `f64`, `i32` and `u32` grids can be inexact; a constant image has no
/// differences to lose.
pub(crate) fn check_f32_resolution(scalar_type: ScalarType, (lo, hi): (f64, f64)) -> Result<()> {
    use crate::grid::ScalarType::{F64, I32, U32};
    let m = lo.abs().max(hi.abs());
    let range = hi - lo;
    if matches!(scalar_type, F64 | I32 | U32) && range > 0.0 && m * 2f64.powi(-24) > range / 4096.0 {
        return Err(Error::InvalidArgument(format!(
            "the values span {range:.3e} on magnitudes up to {m:.3e}: a GPU texture's 32-bit float keeps only \
             {:.3e} at that magnitude, more than 1/4096 of the range; subtract the offset (e.g. with \
             vtkImageShiftScale), or draw with CompositeOnCPU, which keeps 64-bit values",
            m * 2f64.powi(-24)
        )));
    }
    Ok(())
}

/// The footprint the bridge's flag names.
fn footprint(gaussian: bool) -> Footprint {
    if gaussian {
        Footprint::Gaussian
    } else {
        Footprint::Square
    }
}

/// The `[r, g, b, opacity]` of the bridge's surface colour.
fn surface_rgba(rgba: &[f64]) -> Result<[f64; 4]> {
    rgba.try_into()
        .map_err(|_| Error::InvalidArgument(format!("{} surface colour values: give r, g, b and opacity", rgba.len())))
}

impl HybridOctreeHandle {
    pub(crate) fn prepare_view(&self, bytes: &[u8], desc: &GridDesc, options: &SelectDesc) -> Bridged<()> {
        super::view::prepare_view(self, bytes, desc, options)
    }

    pub(crate) fn select_bricks(&self, desc: &SelectDesc) -> Bridged<Box<SelectionHandle>> {
        guarded(|| {
            let (selection, transfer_2d, texel, view_selection) = select_with(self, desc)?;
            self.selection_handle(desc, selection, transfer_2d, texel, view_selection).map(Box::new)
        })
    }

    /// The handle of `selection`, made of this octree for `desc`.
    pub(crate) fn selection_handle(
        &self,
        desc: &SelectDesc,
        selection: Selection,
        transfer_2d: Option<TransferFunction2D>,
        texel: TexelEncoding,
        view_selection: ViewSelection,
    ) -> Result<SelectionHandle> {
        let blend = blend(desc, self.volume().value_range())?;
        Ok(SelectionHandle {
            blend,
            selection,
            octree_id: self.id,
            shape: self.shape,
            value_range: self.volume().value_range(),
            polygons: Mutex::new(None),
            points: self.hybrid.points.as_ref().filter(|_| self.dependent.is_none()).map(|p| Arc::clone(&p.set)),
            lighting: Mutex::new(None),
            gradient_opacity: Mutex::new(None),
            region: region(&desc.region)?,
            transfer_2d,
            texel,
            dependent: self.dependent.is_some() && self.rgba.is_none(),
            rgba: self.rgba,
            scalar_type: self.scalar_type,
            jittering: Default::default(),
            sample_distance: Default::default(),
            scattering: Mutex::new(None),
            view_selection,
            slice_factor: std::sync::atomic::AtomicU32::new(1),
            stand_ins: Mutex::new(None),
        })
    }
}

impl SelectionHandle {
    pub(crate) fn summary(&self) -> Bridged<SelectionSummary> {
        guarded(|| {
            let s = &self.selection;
            Ok(SelectionSummary {
                bricks: s.bricks.len(),
                texture_bytes: s.texture_bytes,
                budget_bytes: s.budget_bytes,
                estimated_error: s.estimated_error,
                estimated_rms_error: s.estimated_rms_error,
                skipped: s.skipped,
                warning: s.warning.clone().unwrap_or_default(),
                points: s.bricks.iter().map(|b| b.point_count).sum(),
                point_bytes: s.point_bytes,
                view_selection: self.view_selection.name().to_string(),
            })
        })
    }

    /// The DrawList itself (for the bridge and the tests): the octree's
    /// surface at `surface_opacity`, and the points bought bucketed into the slabs.
    pub(crate) fn list(
        &self,
        octree: &HybridOctreeHandle,
        camera_desc: &CameraDesc,
        surface_opacity: f64,
    ) -> Result<DrawList> {
        let mut list = self.volume_list(octree, camera_desc, surface_opacity)?;
        if let Some(set) = &self.points {
            add_points(&mut list, &octree.shape, set)?;
        }
        let lighting = self.lighting.lock().unwrap_or_else(|e| e.into_inner()).clone();
        let gradient_opacity = self.gradient_opacity.lock().unwrap_or_else(|e| e.into_inner()).clone();
        let list = replan_transfer_2d(list, self.transfer_2d.as_ref());
        let list = replan_effects(list, lighting.as_ref(), gradient_opacity.as_ref())?;
        let fields = match (self.dependent, self.rgba.is_some()) {
            (_, true) => Fields::Rgba,
            (true, false) => Fields::Two,
            (false, false) => Fields::One,
        };
        let mut list = crate::plan::dependent::plan_fields(list, fields);
        list.texel = self.texel;
        let scattering = *self.scattering.lock().unwrap_or_else(|e| e.into_inner());
        let list = crate::plan::scattering::plan_scattering(list, lighting.as_ref(), scattering.as_ref())?;
        let list = recrop(list, self.region.as_ref(), &octree.shape);
        let s = f64::from_bits(self.sample_distance.load(std::sync::atomic::Ordering::Relaxed));
        let list = crate::plan::sampling::plan_sample_distance(list, Some(s).filter(|&s| s > 0.0));
        let list = crate::plan::jitter::plan_jitter(list, self.jittering.load(std::sync::atomic::Ordering::Relaxed));
        let factor = self.slice_factor.load(std::sync::atomic::Ordering::Relaxed);
        Ok(if factor > 1 { crate::plan::cost::widen_slices(list, factor) } else { list })
    }

    /// [`Self::list`] without the points.
    fn volume_list(
        &self,
        octree: &HybridOctreeHandle,
        camera_desc: &CameraDesc,
        surface_opacity: f64,
    ) -> Result<DrawList> {
        if octree.id != self.octree_id {
            return Err(Error::InvalidArgument(
                "this selection was made from another octree: select again from this one".into(),
            ));
        }
        let camera = camera(camera_desc)?;
        if !(0.0..=1.0).contains(&surface_opacity) {
            return Err(Error::InvalidArgument(format!("surface opacity {surface_opacity} must be between 0 and 1")));
        }
        let hybrid = &octree.hybrid;
        let scene = Scene { blend: self.blend, ..hybrid.scene(surface_opacity) };
        let stand_ins = self.drawn();
        let drawn = stand_ins.as_deref().unwrap_or(&self.selection);
        if plan(drawn, &scene).surface != SurfacePass::Translucent {
            return hybrid.draw_list(&octree.shape, drawn, &camera, surface_opacity, self.blend, None);
        }
        if stand_ins.is_some() {
            // The slab polygons kept are those of the selection's own strides.
            let polygons = hybrid.slab_polygons(&octree.shape, drawn);
            return hybrid.draw_list(&octree.shape, drawn, &camera, surface_opacity, self.blend, polygons.as_ref());
        }
        let mut cache = self.polygons.lock().unwrap_or_else(|e| e.into_inner());
        if cache.as_ref().is_none_or(|(id, _)| *id != octree.surface_id) {
            *cache = hybrid.slab_polygons(&octree.shape, &self.selection).map(|made| (octree.surface_id, made));
        }
        let polygons = cache.as_ref().map(|(_, p)| p);
        hybrid.draw_list(&octree.shape, &self.selection, &camera, surface_opacity, self.blend, polygons)
    }

    /// The selection with its stand-ins, when some of its bricks are drawn by one.
    pub(crate) fn drawn(&self) -> Option<Arc<Selection>> {
        self.stand_ins.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// `f` of the bricks as drawn: the selection with its stand-ins, or the selection.
    fn with_drawn<R>(&self, f: impl FnOnce(&Selection) -> R) -> R {
        f(self.drawn().as_deref().unwrap_or(&self.selection))
    }

    pub(crate) fn draw_list(
        &self,
        octree: &HybridOctreeHandle,
        camera_desc: &CameraDesc,
        surface_opacity: f64,
    ) -> Bridged<DrawListOutput> {
        guarded(|| {
            let list = self.list(octree, camera_desc, surface_opacity)?;
            let mut out = self.with_drawn(|drawn| flatten(&list, drawn));
            if let (true, Some(scale)) = (list.plan.rgba, &self.rgba) {
                // Uploaded as RGBA8 (u8: alpha decoded as 255 t) or RGBA32F.
                let u8s = self.scalar_type == ScalarType::U8;
                out.texel_bytes = rgba_texel_bytes(self.scalar_type);
                let format = if u8s { TexelFormat::Unorm8 } else { TexelFormat::Float32 };
                out.texel_format = TexelFormat::ALL.iter().position(|f| *f == format).unwrap_or(1) as i32;
                (out.texel_scale, out.texel_bias) = (if u8s { 255.0 } else { 1.0 }, 0.0);
                out.rgba_reading = super::rgba::texel_reading(scale, self.scalar_type);
            }
            Ok(out)
        })
    }

    /// The CPU compositor on this selection's DrawList: the transfer function
    /// from `(colors, opacities)` tuples, the points bought drawn with their
    /// footprint, the octree's surface with its `[r, g, b, opacity]` (hidden
    /// at opacity 0).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn composite(
        &self,
        octree: &HybridOctreeHandle,
        camera_desc: &CameraDesc,
        bytes: &[u8],
        desc: &GridDesc,
        colors: &[f64],
        opacities: &[f64],
        gaussian_points: bool,
        surface_colour: &[f64],
        width: usize,
        height: usize,
        rgba: &mut [f32],
    ) -> Bridged<()> {
        guarded(|| {
            let colour = surface_rgba(surface_colour)?;
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let tf = transfer_function(colors, opacities)?;
            let list = self.list(octree, camera_desc, colour[3])?;
            let surface = octree.hybrid.surface.as_ref().filter(|_| colour[3] > 0.0);
            let drawn = surface.map(|s| (s, colour.map(|v| v as f32)));
            if list.plan.dependent {
                return super::dependent::composite_into(&list, bytes, desc, &tf, width, height, rgba);
            }
            if let (true, Some(scale)) = (list.plan.rgba, self.rgba) {
                return super::rgba::composite_into(&list, scale, bytes, desc, &tf, width, height, rgba);
            }
            let textures = crate::render::texture::upload(&grid, &list)?;
            let shades = match self.points.as_deref() {
                Some(set) => crate::points::shade(&grid, set, &tf)?,
                None => Vec::new(),
            };
            let points = self.points.as_deref().map(|set| (set, shades.as_slice(), footprint(gaussian_points)));
            let shadow = crate::render::scattering::shadow_for(&grid, &list)?;
            let image = crate::render::compositor::composite_shadowed(
                &textures,
                shadow.as_ref(),
                &list,
                &tf,
                width,
                height,
                drawn,
                points,
            )?;
            write_pixels(&image.rgba, rgba)
        })
    }

    /// The shading of the DrawLists made after this call.
    pub(crate) fn set_shading(&self, desc: &ShadingDesc) -> Bridged<()> {
        guarded(|| {
            let made = lighting(desc)?;
            *self.lighting.lock().unwrap_or_else(|e| e.into_inner()) = made;
            Ok(())
        })
    }

    /// Jittering of the DrawLists made after this call ([`crate::plan::jitter`]).
    pub(crate) fn set_jittering(&self, on: bool) -> Bridged<()> {
        guarded(|| {
            self.jittering.store(on, std::sync::atomic::Ordering::Relaxed);
            Ok(())
        })
    }

    /// The ray sample distance of the DrawLists made after this call
    /// ([`crate::plan::sampling`]; 0: the stride's slices).
    pub(crate) fn set_sample_distance(&self, distance: f64) -> Bridged<()> {
        guarded(|| {
            if !(distance >= 0.0 && distance.is_finite()) {
                return Err(crate::Error::InvalidArgument(format!(
                    "sample distance {distance}: give a positive number of world units, or 0 for one slice a lattice step"
                )));
            }
            self.sample_distance.store(distance.to_bits(), std::sync::atomic::Ordering::Relaxed);
            Ok(())
        })
    }

    /// The gradient opacity of the DrawLists made after this call (VTK's
    /// points for this selection's grid and value range).
    pub(crate) fn set_gradient_opacity(&self, points: &[f64]) -> Bridged<()> {
        guarded(|| {
            let made = vtk_gradient_opacity(points, &self.shape, self.value_range)?;
            *self.gradient_opacity.lock().unwrap_or_else(|e| e.into_inner()) = made;
            Ok(())
        })
    }

    pub(crate) fn brick_texels(&self, bytes: &[u8], desc: &GridDesc, brick: usize, texels: &mut [f32]) -> Bridged<()> {
        self.texels(bytes, desc, brick, false, texels)
    }

    pub(crate) fn brick_texels_bordered(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        brick: usize,
        texels: &mut [f32],
    ) -> Bridged<()> {
        self.texels(bytes, desc, brick, true, texels)
    }

    /// Brick `brick` as drawn (its stand-in while it loads), or an error
    /// naming how many there are.
    pub(crate) fn selected_brick(&self, brick: usize) -> Result<crate::plan::select::Brick> {
        self.with_drawn(|drawn| {
            drawn.bricks.get(brick).copied().ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "brick {brick} does not exist: the selection has {} bricks",
                    drawn.bricks.len()
                ))
            })
        })
    }

    /// Brick `brick`'s texels in the selection's texel format (see the bridge's declaration).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn brick_texels_encoded(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        brick: usize,
        bordered: bool,
        decoded: &mut [f32],
        encoded: &mut [u8],
    ) -> Bridged<()> {
        guarded(|| {
            let grid = grid_unscanned(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let b = &self.selected_brick(brick)?;
            let how = (usize::from(bordered), self.blend.mode);
            brick_texels_encoded_into(&grid, b, how, &self.texel, decoded, encoded)?;
            // The shader decodes in f32: the values must be f32-resolvable, as f32 texels must.
            check_f32_resolution(grid.samples().scalar_type(), self.value_range)?;
            finite_texels(brick, grid.samples().scalar_type(), decoded)
        })
    }

    /// Brick `brick`'s texels, with the gradient border when `bordered`.
    fn texels(&self, bytes: &[u8], desc: &GridDesc, brick: usize, bordered: bool, texels: &mut [f32]) -> Bridged<()> {
        guarded(|| {
            // One brick of many: scanning the whole image for infinities per
            // brick would cost a full pass each; the octree's build scanned it,
            // and only this brick's texels are checked here. NaN is no data:
            // it goes to the texture, where the shader skips it.
            let grid = grid_unscanned(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let b = &self.selected_brick(brick)?;
            if bordered {
                brick_texels_f32_bordered_into(&grid, b, texels)?;
            } else {
                brick_texels_for_blend_f32_into(&grid, b, self.blend.mode, texels)?;
            }
            check_f32_resolution(grid.samples().scalar_type(), self.value_range)?;
            finite_texels(brick, grid.samples().scalar_type(), texels)
        })
    }
}

/// Brick `brick`'s texels (of an image of type `scalar`) hold no infinity:
/// an f64 beyond a GPU texture's 32-bit float, or an image changed since
/// the octree was built (its build refused infinities).
pub(crate) fn finite_texels(brick: usize, scalar: ScalarType, texels: &[f32]) -> Result<()> {
    let Some(i) = texels.iter().position(|v| v.is_infinite()) else { return Ok(()) };
    let why = if scalar == ScalarType::F64 {
        format!(
            "a value beyond the range of a GPU texture's 32-bit float (|value| above 3.4e38), texel {i}: scale the \
             data into that range (e.g. with vtkImageShiftScale), or draw with CompositeOnCPU, which keeps 64-bit values"
        )
    } else {
        format!("an infinite value (texel {i}): the image changed since the octree was built; fix the values and rebuild it")
    };
    Err(Error::InvalidArgument(format!("brick {brick} holds {why}")))
}
