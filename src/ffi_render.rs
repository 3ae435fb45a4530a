//! The rendering half of the bridge's Rust side (declared in [`crate::ffi`],
//! the only `#[cxx::bridge]`): a selection made from a
//! [`VolumeOctreeHandle`], its DrawList for a VTK camera, and its bricks'
//! texels, for `vtkHybridOctreeVolumeMapper`.
//!
//! The selection, the DrawList and the texel layout are those of the CLI:
//! [`select`] with the transfer function's visibility test, [`draw_list`]
//! (with a kept isosurface, a [`SurfaceHandle`], and the selection's
//! [`SlabPolygons`] made once per selection and surface),
//! [`brick_texels_f32`] (the layout of [`crate::render::texture`]).

use crate::camera::{Camera, Projection};
use crate::error::{Error, Result};
use crate::ffi::{
    grid_of, guarded, same_image, CameraDesc, DrawListOutput, GridDesc, SelectDesc, SelectionSummary, SurfaceMode,
    SurfaceOutput, VolumeOctreeHandle,
};
use crate::ffi_points::PointsHandle;
use crate::grid::GridShape;
use crate::plan::select::{select, select_with_points, Roi, SelectOptions, Selection};
use crate::plan::slab::SlabPolygons;
use crate::plan::{draw_list, plan, DrawList, Scene, SurfacePass};
use crate::points::draw::Footprint;
use crate::points::mass::PointMass;
use crate::points::{add_points, PointSet};
use crate::render::texture::brick_texels_f32;
use crate::surface::Surface;
use crate::transfer::TransferFunction;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// What a bridge function returns: an error crosses as its message.
type Bridged<T> = std::result::Result<T, String>;

/// A selection, with the octree and grid it was made from.
#[derive(Debug)]
pub struct SelectionHandle {
    pub(crate) selection: Selection,
    octree_id: u64,
    shape: GridShape,
    /// The octree's value range (what 32-bit float texels must resolve).
    value_range: (f64, f64),
    /// The SlabPolygons of the last translucent surface drawn, with its id.
    polygons: Mutex<Option<(u64, SlabPolygons)>>,
    /// The points the selection spent bytes on (a selection made with points).
    points: Option<Arc<PointSet>>,
}

/// An isosurface kept for drawing, with the octree it was extracted from.
#[derive(Debug)]
pub struct SurfaceHandle {
    pub(crate) surface: Surface,
    octree_id: u64,
    id: u64,
}

static NEXT_SURFACE_ID: AtomicU64 = AtomicU64::new(1);

/// The select options of `desc` for a grid of `shape`: the ROI from world
/// to index space (centre through origin and spacing, radius divided by the
/// smallest spacing).
pub(crate) fn select_options(shape: &GridShape, desc: &SelectDesc) -> Result<SelectOptions> {
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
    Ok(SelectOptions { roi, ..SelectOptions::new(desc.budget_bytes, desc.tolerance) })
}

/// The transfer function of `desc`'s opacity points (a white colour: only the
/// opacity matters here); `None` when there are none.
fn opacity_function(desc: &SelectDesc) -> Result<Option<TransferFunction>> {
    let p = &desc.opacity_points;
    if p.is_empty() {
        return Ok(None);
    }
    if p.len() % 2 != 0 {
        return Err(Error::InvalidArgument(format!(
            "{} opacity values: give (value, opacity) pairs, flattened",
            p.len()
        )));
    }
    let points: Vec<(f64, f32)> = p.chunks(2).map(|v| (v[0], v[1] as f32)).collect();
    TransferFunction::new(vec![(0.0, [1.0; 3])], points).map(Some)
}

/// The CLI's visibility test (`scene::visible`): a node shows unless the
/// opacity is 0 over its whole range, or when it holds the isovalue; with
/// `points`, bytes go to textures or points ([`select_with_points`]).
pub(crate) fn select_with(
    octree: &VolumeOctreeHandle,
    desc: &SelectDesc,
    points: Option<&PointMass>,
) -> Result<Selection> {
    let options = select_options(&octree.shape, desc)?;
    let tf = opacity_function(desc)?;
    let iso = desc.has_isovalue.then_some(desc.isovalue);
    if iso.is_some_and(|v| !v.is_finite()) {
        return Err(Error::InvalidArgument(format!("isovalue {} must be a finite number", desc.isovalue)));
    }
    let visible = |min: f64, max: f64| {
        tf.as_ref().is_none_or(|tf| !tf.is_transparent_over(min, max)) || iso.is_some_and(|v| min < v && v <= max)
    };
    match points {
        Some(mass) => select_with_points(&octree.octree, &options, visible, mass),
        None => select(&octree.octree, &options, visible),
    }
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

/// `list` flattened (see [`DrawListOutput`]); `index` maps a node to its brick index in the selection.
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

/// The transfer function of `(value, r, g, b)` and `(value, opacity)` tuples, flattened.
pub(crate) fn transfer_function(colors: &[f64], opacities: &[f64]) -> Result<TransferFunction> {
    if colors.len() % 4 != 0 || opacities.len() % 2 != 0 {
        return Err(Error::InvalidArgument(format!(
            "{} colour and {} opacity values: give (value, r, g, b) and (value, opacity) tuples, flattened",
            colors.len(),
            opacities.len()
        )));
    }
    let c = colors.chunks(4).map(|v| (v[0], [v[1] as f32, v[2] as f32, v[3] as f32])).collect();
    let o = opacities.chunks(2).map(|v| (v[0], v[1] as f32)).collect();
    TransferFunction::new(c, o)
}

/// Refuses data whose differences 32-bit float texels cannot resolve: a
/// value of magnitude `m` is off by up to `m 2^-24` in an `f32`; when that is
/// more than one cell of a 4096-cell table, `(max - min) / 4096` (e.g. a
/// `1e-3` range on a `1e9` offset), the GPU picture would be noise. Only
/// `f64`, `i32` and `u32` grids can be inexact; a constant image has no
/// differences to lose.
fn check_f32_resolution(scalar_type: crate::grid::ScalarType, (lo, hi): (f64, f64)) -> Result<()> {
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

impl VolumeOctreeHandle {
    pub(crate) fn select_bricks(&self, desc: &SelectDesc) -> Bridged<Box<SelectionHandle>> {
        guarded(|| Ok(self.selection_handle(select_with(self, desc, None)?, None)))
    }

    /// `selection` of this octree kept for drawing, with the points it bought.
    fn selection_handle(&self, selection: Selection, points: Option<Arc<PointSet>>) -> Box<SelectionHandle> {
        Box::new(SelectionHandle {
            selection,
            octree_id: self.id,
            shape: self.shape,
            value_range: self.octree.value_range(),
            polygons: Mutex::new(None),
            points,
        })
    }

    pub(crate) fn select_bricks_with_points(
        &self,
        desc: &SelectDesc,
        points: &PointsHandle,
    ) -> Bridged<Box<SelectionHandle>> {
        guarded(|| {
            if points.octree_id != self.id {
                return Err(Error::InvalidArgument(
                    "the points were made for another octree: make them again from this one".into(),
                ));
            }
            let selection = select_with(self, desc, Some(&points.mass))?;
            Ok(self.selection_handle(selection, Some(Arc::clone(&points.set))))
        })
    }
}

impl VolumeOctreeHandle {
    pub(crate) fn surface_for_drawing(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        isovalue: f64,
        mode: SurfaceMode,
    ) -> Bridged<Box<SurfaceHandle>> {
        guarded(|| {
            let surface = self.extract(&grid_of(bytes, desc)?, isovalue, mode)?;
            let id = NEXT_SURFACE_ID.fetch_add(1, Ordering::Relaxed);
            Ok(Box::new(SurfaceHandle { surface, octree_id: self.id, id }))
        })
    }
}

impl SurfaceHandle {
    fn check_octree(&self, octree: &VolumeOctreeHandle) -> Result<()> {
        if self.octree_id == octree.id {
            Ok(())
        } else {
            Err(Error::InvalidArgument(
                "the surface was extracted from another octree: extract it from this one".into(),
            ))
        }
    }

    pub(crate) fn mesh(&self, octree: &VolumeOctreeHandle) -> Bridged<SurfaceOutput> {
        guarded(|| {
            self.check_octree(octree)?;
            Ok(octree.surface_output(&self.surface, -1.0, -1.0))
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
                skipped: s.skipped,
                warning: s.warning.clone().unwrap_or_default(),
                points: s.bricks.iter().map(|b| b.point_count).sum(),
                point_bytes: s.point_bytes,
            })
        })
    }

    /// The DrawList itself (for the bridge and the tests), with `surface`
    /// at an opacity, and the points bought bucketed into the slabs.
    pub(crate) fn list(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        surface: Option<(&SurfaceHandle, f64)>,
    ) -> Result<DrawList> {
        let mut list = self.volume_list(octree, camera_desc, surface)?;
        if let Some(set) = &self.points {
            add_points(&mut list, &octree.shape, set)?;
        }
        Ok(list)
    }

    /// [`Self::list`] without the points.
    fn volume_list(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        surface: Option<(&SurfaceHandle, f64)>,
    ) -> Result<DrawList> {
        if octree.id != self.octree_id {
            return Err(Error::InvalidArgument(
                "this selection was made from another octree: select again from this one".into(),
            ));
        }
        let camera = camera(camera_desc)?;
        let Some((s, surface_opacity)) = surface else {
            let scene = Scene { surface: None, surface_opacity: 1.0, shading: false };
            return draw_list(&octree.octree, &octree.shape, &self.selection, &camera, &scene, None);
        };
        s.check_octree(octree)?;
        if !(0.0..=1.0).contains(&surface_opacity) {
            return Err(Error::InvalidArgument(format!("surface opacity {surface_opacity} must be between 0 and 1")));
        }
        let scene = Scene { surface: Some(&s.surface), surface_opacity, shading: false };
        if plan(&self.selection, &scene).surface != SurfacePass::Translucent {
            return draw_list(&octree.octree, &octree.shape, &self.selection, &camera, &scene, None);
        }
        let mut cache = self.polygons.lock().unwrap_or_else(|e| e.into_inner());
        if cache.as_ref().is_none_or(|(id, _)| *id != s.id) {
            let made = SlabPolygons::new(&octree.octree, &s.surface, &octree.shape, &self.selection);
            *cache = Some((s.id, made));
        }
        let polygons = cache.as_ref().map(|(_, p)| p);
        draw_list(&octree.octree, &octree.shape, &self.selection, &camera, &scene, polygons)
    }

    pub(crate) fn draw_list(&self, octree: &VolumeOctreeHandle, camera_desc: &CameraDesc) -> Bridged<DrawListOutput> {
        guarded(|| Ok(flatten(&self.list(octree, camera_desc, None)?, &self.selection)))
    }

    pub(crate) fn draw_list_with_surface(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        surface: &SurfaceHandle,
        surface_opacity: f64,
    ) -> Bridged<DrawListOutput> {
        guarded(|| Ok(flatten(&self.list(octree, camera_desc, Some((surface, surface_opacity)))?, &self.selection)))
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn composite(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        bytes: &[u8],
        desc: &GridDesc,
        colors: &[f64],
        opacities: &[f64],
        gaussian_points: bool,
        width: usize,
        height: usize,
    ) -> Bridged<Vec<f32>> {
        guarded(|| {
            let tf = (colors, opacities);
            self.composite_scene(octree, camera_desc, bytes, desc, tf, footprint(gaussian_points), None, width, height)
        })
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn composite_with_surface(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        bytes: &[u8],
        desc: &GridDesc,
        colors: &[f64],
        opacities: &[f64],
        gaussian_points: bool,
        surface: &SurfaceHandle,
        surface_rgba: &[f64],
        width: usize,
        height: usize,
    ) -> Bridged<Vec<f32>> {
        guarded(|| {
            let rgba: [f64; 4] = surface_rgba.try_into().map_err(|_| {
                Error::InvalidArgument(format!(
                    "{} surface colour values: give r, g, b and opacity",
                    surface_rgba.len()
                ))
            })?;
            let surface = Some((surface, rgba));
            let (tf, kind) = ((colors, opacities), footprint(gaussian_points));
            self.composite_scene(octree, camera_desc, bytes, desc, tf, kind, surface, width, height)
        })
    }

    /// The CPU compositor on this selection's DrawList: the transfer function
    /// from `(colors, opacities)` tuples, the points bought drawn with
    /// `footprint`, `surface` with its `[r, g, b, opacity]`.
    #[allow(clippy::too_many_arguments)]
    fn composite_scene(
        &self,
        octree: &VolumeOctreeHandle,
        camera_desc: &CameraDesc,
        bytes: &[u8],
        desc: &GridDesc,
        (colors, opacities): (&[f64], &[f64]),
        footprint: Footprint,
        surface: Option<(&SurfaceHandle, [f64; 4])>,
        width: usize,
        height: usize,
    ) -> Result<Vec<f32>> {
        let grid = grid_of(bytes, desc)?;
        same_image(&self.shape, &grid)?;
        let tf = transfer_function(colors, opacities)?;
        let list = self.list(octree, camera_desc, surface.map(|(s, rgba)| (s, rgba[3])))?;
        let drawn = surface.map(|(s, rgba)| (&s.surface, rgba.map(|v| v as f32)));
        let textures = crate::render::texture::upload(&grid, &list)?;
        let shades = match self.points.as_deref() {
            Some(set) => crate::points::shade(&grid, set, &tf)?,
            None => Vec::new(),
        };
        let points = self.points.as_deref().map(|set| (set, shades.as_slice(), footprint));
        let image =
            crate::render::compositor::composite_with_points(&textures, &list, &tf, width, height, drawn, points)?;
        Ok(image.rgba.iter().flatten().copied().collect())
    }

    pub(crate) fn brick_texels(&self, bytes: &[u8], desc: &GridDesc, brick: usize) -> Bridged<Vec<f32>> {
        guarded(|| {
            // One brick of many: scanning the whole image for infinities per
            // brick would cost a full pass each; the octree's build scanned it,
            // and only this brick's texels are checked here. NaN is no data:
            // it goes to the texture, where the shader skips it.
            let grid = crate::ffi::grid_unscanned(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let Some(b) = self.selection.bricks.get(brick) else {
                return Err(Error::InvalidArgument(format!(
                    "brick {brick} does not exist: the selection has {} bricks",
                    self.selection.bricks.len()
                )));
            };
            let texels = brick_texels_f32(&grid, b)?;
            check_f32_resolution(grid.samples().scalar_type(), self.value_range)?;
            if let Some(i) = texels.iter().position(|v| v.is_infinite()) {
                let why = if grid.samples().scalar_type() == crate::grid::ScalarType::F64 {
                    "a value beyond the range of a GPU texture's 32-bit float (|value| above 3.4e38), texel {i}: \
                     scale the data into that range (e.g. with vtkImageShiftScale), or draw with CompositeOnCPU, \
                     which keeps 64-bit values"
                } else {
                    "an infinite value (texel {i}): the image changed since the octree was built; fix the values \
                     and rebuild it"
                };
                return Err(Error::InvalidArgument(format!(
                    "brick {brick} holds {}",
                    why.replace("{i}", &i.to_string())
                )));
            }
            Ok(texels)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::{build_volume_octree, ScalarType};
    use crate::grid::{Grid, Samples};
    use crate::plan;

    const N: usize = 21;

    /// A ball: values 1 - r/10 around (10, 9, 11), spacing (1, 1.5, 0.5), origin (-3, 2, 5).
    fn data() -> Vec<f32> {
        (0..N * N * N)
            .map(|i| {
                let (x, y, z) = ((i % N) as f32 - 10.0, ((i / N) % N) as f32 - 9.0, (i / (N * N)) as f32 - 11.0);
                1.0 - (x * x + y * y + z * z).sqrt() / 10.0
            })
            .collect()
    }

    fn bytes(data: &[f32]) -> &[u8] {
        // SAFETY: f32 has no padding; the byte view covers exactly the slice's storage.
        unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, std::mem::size_of_val(data)) }
    }

    fn desc() -> GridDesc {
        GridDesc {
            scalar_type: ScalarType::F32,
            dims: [N; 3],
            spacing: [1.0, 1.5, 0.5],
            origin: [-3.0, 2.0, 5.0],
            components: 1,
            component: -1,
        }
    }

    fn options(budget_bytes: usize) -> SelectDesc {
        crate::ffi::select_desc(budget_bytes)
    }

    fn cameras() -> Vec<CameraDesc> {
        vec![
            CameraDesc {
                position: [7.0, 17.0, -40.0],
                focal_point: [7.0, 17.0, 10.0],
                view_up: [0.0, 1.0, 0.0],
                parallel: true,
                parallel_scale: 20.0,
                view_angle: 30.0,
            },
            CameraDesc {
                position: [60.0, 70.0, 60.0],
                focal_point: [7.0, 17.0, 10.0],
                view_up: [0.0, 0.0, 1.0],
                parallel: false,
                parallel_scale: 1.0,
                view_angle: 30.0,
            },
        ]
    }

    #[test]
    fn selects_within_the_budget_and_reports_it() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h.select_bricks(&options(12_000)).unwrap();
        let sum = s.summary().unwrap();
        assert!(sum.bricks >= 1 && sum.texture_bytes <= 12_000 && sum.budget_bytes == 12_000, "{sum:?}");
        assert_eq!(sum.bricks, s.selection.bricks.len());
        assert!(sum.warning.contains("above the tolerance 0"), "{sum:?}");
        let loose = h.select_bricks(&SelectDesc { tolerance: 0.1, ..options(12_000) }).unwrap().summary().unwrap();
        assert!(loose.warning.is_empty() && loose.estimated_error <= 0.1, "{loose:?}");
        // The same selection as select() called directly.
        let direct = select(&h.octree, &SelectOptions::new(12_000, 0.0), |_, _| true).unwrap();
        assert_eq!(s.selection, direct);
        // Too small a budget: the coarsest selection and a warning.
        let tiny = h.select_bricks(&options(8)).unwrap().summary().unwrap();
        assert!(!tiny.warning.is_empty() && tiny.texture_bytes > 8, "{tiny:?}");
    }

    #[test]
    fn bad_options_are_clear_errors() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let err = |o: SelectDesc| h.select_bricks(&o).map(|_| ()).unwrap_err();
        assert!(err(options(0)).contains("budget is 0 bytes"));
        assert!(err(SelectDesc { tolerance: f64::NAN, ..options(1000) }).contains("error tolerance NaN"));
        let roi = |c: [f64; 3], r: f64| SelectDesc { has_roi: true, roi_center: c, roi_radius: r, ..options(1000) };
        assert!(err(roi([1.0; 3], 0.0)).contains("region of interest"));
        assert!(err(roi([f64::NAN, 1.0, 1.0], 2.0)).contains("region of interest"));
        let odd = SelectDesc { opacity_points: vec![0.0, 1.0, 2.0], ..options(1000) };
        assert!(err(odd).contains("(value, opacity) pairs"));
        let above_one = SelectDesc { opacity_points: vec![0.0, 2.0], ..options(1000) };
        assert!(err(above_one).contains("opacity"));
        assert!(err(SelectDesc { has_isovalue: true, isovalue: f64::INFINITY, ..options(1000) }).contains("isovalue"));
    }

    #[test]
    fn roi_is_given_in_world_coordinates() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        // World (2, 5, 6) is index ((2 + 3) / 1, (5 - 2) / 1.5, (6 - 5) / 0.5) = (5, 2, 2); radius 3 / 0.5 = 6.
        let o = SelectDesc { has_roi: true, roi_center: [2.0, 5.0, 6.0], roi_radius: 3.0, ..options(30_000) };
        let s = h.select_bricks(&o).unwrap();
        let roi = Some(Roi { center: [5.0, 2.0, 2.0], radius: 6.0 });
        let direct = select(&h.octree, &SelectOptions { roi, ..SelectOptions::new(30_000, 0.0) }, |_, _| true).unwrap();
        assert_eq!(s.selection, direct);
        assert_ne!(s.selection, select(&h.octree, &SelectOptions::new(30_000, 0.0), |_, _| true).unwrap());
    }

    #[test]
    fn transparent_nodes_are_skipped_as_the_cli_does() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        // Opaque only above 0.5 (the ball's core).
        let points = vec![-1.0, 0.0, 0.5, 0.0, 1.0, 1.0];
        let s = h.select_bricks(&SelectDesc { opacity_points: points, ..options(20_000) }).unwrap();
        let tf = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(-1.0, 0.0), (0.5, 0.0), (1.0, 1.0)]).unwrap();
        let direct = select(&h.octree, &SelectOptions::new(20_000, 0.0), |a, b| !tf.is_transparent_over(a, b)).unwrap();
        assert!(direct.skipped > 0);
        assert_eq!(s.selection, direct);
        // With an isosurface at 0.2 the nodes holding it show too.
        let with_iso = SelectDesc {
            opacity_points: vec![-1.0, 0.0, 0.5, 0.0, 1.0, 1.0],
            has_isovalue: true,
            isovalue: 0.2,
            ..options(20_000)
        };
        let s = h.select_bricks(&with_iso).unwrap();
        assert!(s.selection.skipped < direct.skipped, "{} {}", s.selection.skipped, direct.skipped);
    }

    #[test]
    fn draw_list_through_the_bridge_is_plan_draw_list() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h
            .select_bricks(&SelectDesc {
                has_roi: true,
                roi_center: [0.0, 5.0, 6.0],
                roi_radius: 1.0,
                ..options(30_000)
            })
            .unwrap();
        for c in cameras() {
            let out = s.draw_list(&h, &c).unwrap();
            let scene = Scene { surface: None, surface_opacity: 1.0, shading: false };
            let direct =
                plan::draw_list(&h.octree, &h.shape, &s.selection, &camera(&c).unwrap(), &scene, None).unwrap();
            assert_eq!(direct, s.list(&h, &c, None).unwrap());
            let n = direct.bricks.len();
            assert!(n > 1 && n == s.selection.bricks.len(), "{n} bricks");
            assert_eq!(out.passes, "volume");
            assert_eq!(out.reference_spacing, 0.5);
            assert_eq!(out.forward, direct.camera.forward());
            assert_eq!(
                (out.brick.len(), out.bounds.len(), out.texels.len(), out.slice_offsets.len()),
                (n, 6 * n, 3 * n, n + 1)
            );
            for (i, b) in direct.bricks.iter().enumerate() {
                assert_eq!(s.selection.bricks[out.brick[i]], b.brick);
                assert_eq!(out.node_id[i], b.brick.node.0);
                let (lo, hi) = (b.world_lo, b.world_hi);
                assert_eq!(out.bounds[6 * i..6 * i + 6], [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]);
                assert_eq!(out.texels[3 * i..3 * i + 3], b.brick.texels);
                assert_eq!((out.stride[i], out.slice_spacing[i]), (b.brick.stride, b.slice_spacing));
                assert_eq!(out.opacity_ratio[i], b.slice_spacing / 0.5);
                assert_eq!(out.slices[out.slice_offsets[i]..out.slice_offsets[i + 1]], b.slices[..]);
            }
        }
    }

    #[test]
    fn draw_list_errors() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let other = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h.select_bricks(&options(12_000)).unwrap();
        let c = &cameras()[0];
        assert!(s.draw_list(&other, c).unwrap_err().contains("another octree"));
        let at_focus = CameraDesc { position: c.focal_point, ..cameras().remove(0) };
        assert!(s.draw_list(&h, &at_focus).unwrap_err().contains("camera"));
        let zero_scale = CameraDesc { parallel_scale: 0.0, ..cameras().remove(0) };
        assert!(s.draw_list(&h, &zero_scale).unwrap_err().contains("parallel scale"));
    }

    /// f64 values beyond the f32 range cannot be GPU texels: refused with
    /// what to do, not handed over as infinities.
    #[test]
    fn texels_beyond_f32_are_refused() {
        let d: Vec<f64> = data().iter().map(|&v| v as f64 * 1e308).collect();
        // SAFETY: f64 has no padding; the byte view covers exactly the slice's storage.
        let b = unsafe { std::slice::from_raw_parts(d.as_ptr() as *const u8, std::mem::size_of_val(&d[..])) };
        let desc = GridDesc { scalar_type: ScalarType::F64, ..desc() };
        let h = build_volume_octree(b, &desc, 4).unwrap();
        let s = h.select_bricks(&options(1_000_000)).unwrap();
        let e = (0..s.selection.bricks.len()).find_map(|i| s.brick_texels(b, &desc, i).err()).unwrap();
        assert!(e.to_string().contains("32-bit float") && e.to_string().contains("CompositeOnCPU"), "{e}");
    }

    /// A 1e-3 range on a 1e9 offset is noise in 32-bit float: refused with
    /// what to do; the same range near 0, and f32 data, are drawn.
    #[test]
    fn texels_that_f32_cannot_resolve_are_refused() {
        let texels = |offset: f64, scalar_type: ScalarType| {
            let d: Vec<f64> = data().iter().map(|&v| offset + v as f64 * 1e-3).collect();
            let desc = GridDesc { scalar_type, ..desc() };
            let bytes: Vec<u8> = match scalar_type {
                ScalarType::F64 => d.iter().flat_map(|v| v.to_ne_bytes()).collect(),
                _ => d.iter().flat_map(|&v| (v as f32).to_ne_bytes()).collect(),
            };
            let h = build_volume_octree(&bytes, &desc, 4).unwrap();
            let s = h.select_bricks(&options(1_000_000)).unwrap();
            s.brick_texels(&bytes, &desc, 0).map(drop)
        };
        let e = texels(1e9, ScalarType::F64).unwrap_err().to_string();
        assert!(e.contains("32-bit float") && e.contains("subtract the offset"), "{e}");
        assert!(texels(0.0, ScalarType::F64).is_ok());
        assert!(texels(1e3, ScalarType::F32).is_ok());
    }

    #[test]
    fn brick_texels_are_the_image_at_the_texel_positions() {
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h.select_bricks(&options(12_000)).unwrap();
        let grid = grid_of(bytes(&d), &desc()).unwrap();
        assert!(s.selection.bricks.iter().any(|b| b.stride > 1));
        for (i, b) in s.selection.bricks.iter().enumerate() {
            let t = s.brick_texels(bytes(&d), &desc(), i).unwrap();
            assert_eq!(t.len(), b.texels.iter().product::<usize>());
            let mut expected = Vec::new();
            for z in b.texel_positions(2) {
                for y in b.texel_positions(1) {
                    for x in b.texel_positions(0) {
                        expected.push(grid.value(x, y, z) as f32);
                    }
                }
            }
            assert_eq!(t, expected, "brick {i}");
        }
        let n = s.selection.bricks.len();
        assert!(s.brick_texels(bytes(&d), &desc(), n).unwrap_err().contains("does not exist"));
        let moved = GridDesc { origin: [0.0; 3], ..desc() };
        assert!(s.brick_texels(bytes(&d), &moved, 0).unwrap_err().contains("image changed"));
        // An infinity written after the build: the brick that reads it says so,
        // the others still load. A NaN is no data: its texel is NaN.
        let roi = SelectDesc { has_roi: true, roi_center: [0.0, 5.0, 6.0], roi_radius: 1.0, ..options(30_000) };
        let s = h.select_bricks(&roi).unwrap();
        assert!(s.selection.bricks.len() > 1);
        let b = &s.selection.bricks[0];
        let mut changed = d.clone();
        changed[b.lo[0] + N * (b.lo[1] + N * b.lo[2])] = f32::NAN;
        assert!(s.brick_texels(bytes(&changed), &desc(), 0).unwrap()[0].is_nan());
        changed[b.lo[0] + N * (b.lo[1] + N * b.lo[2])] = f32::INFINITY;
        let e = s.brick_texels(bytes(&changed), &desc(), 0).unwrap_err();
        assert!(e.contains("infinite value (texel 0)"), "{e}");
        let far = s.selection.bricks.iter().position(|o| (0..3).any(|a| o.lo[a] > b.lo[a] || o.hi[a] < b.lo[a]));
        let far = far.expect("a brick away from the NaN");
        assert!(s.brick_texels(bytes(&changed), &desc(), far).is_ok());
    }

    #[test]
    fn f64_texels_are_rounded_to_f32() {
        // 0.1 steps: not exact in f32, resolved by it (differences far above 2^-24).
        let d: Vec<f64> = (0..27).map(|i| 1.0 + i as f64 * 0.1).collect();
        // SAFETY: f64 has no padding; the byte view covers exactly the vector's storage.
        let b = unsafe { std::slice::from_raw_parts(d.as_ptr() as *const u8, d.len() * 8) };
        let desc =
            GridDesc { scalar_type: ScalarType::F64, dims: [3; 3], spacing: [1.0; 3], origin: [0.0; 3], ..desc() };
        let h = build_volume_octree(b, &desc, 2).unwrap();
        let s = h.select_bricks(&options(20_000)).unwrap();
        let grid = Grid::scalar(Samples::F64(&d), [3; 3]).unwrap();
        let all: Vec<f32> = (0..s.selection.bricks.len()).flat_map(|i| s.brick_texels(b, &desc, i).unwrap()).collect();
        let b0 = &s.selection.bricks[0];
        let first: Vec<f32> = b0.texel_positions(0).map(|x| grid.value(x, b0.lo[1], b0.lo[2]) as f32).collect();
        assert_eq!(&all[..first.len()], &first[..]);
        assert!(first.iter().zip(b0.texel_positions(0)).any(|(&t, x)| t as f64 != grid.value(x, b0.lo[1], b0.lo[2])));
    }

    #[test]
    fn draw_list_with_a_surface_is_plan_draw_list() {
        use crate::ffi::SurfaceMode;
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h
            .select_bricks(&SelectDesc {
                has_roi: true,
                roi_center: [0.0, 5.0, 6.0],
                roi_radius: 1.0,
                ..options(30_000)
            })
            .unwrap();
        let surface = h.surface_for_drawing(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized).unwrap();
        let mesh = surface.mesh(&h).unwrap();
        let polygons = surface.surface.polygon_count();
        assert!(polygons > 0 && mesh.polygons as usize == polygons);
        assert_eq!(
            mesh.points,
            h.extract_surface(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized, false).unwrap().points
        );
        for c in cameras() {
            let camera = camera(&c).unwrap();
            for (opacity, passes) in [(0.4, "surface-in-slabs,volume"), (1.0, "surface-opaque,volume"), (0.0, "volume")]
            {
                let scene = Scene { surface: Some(&surface.surface), surface_opacity: opacity, shading: false };
                let direct = plan::draw_list(&h.octree, &h.shape, &s.selection, &camera, &scene, None).unwrap();
                assert_eq!(s.list(&h, &c, Some((&surface, opacity))).unwrap(), direct);
                let out = s.draw_list_with_surface(&h, &c, &surface, opacity).unwrap();
                assert_eq!(out.passes, passes);
                assert_eq!(out.opaque_triangles, direct.opaque_triangles.len());
                assert_eq!(out.batch_offsets.len(), direct.bricks.len() + 1);
                let mut seen = vec![false; polygons];
                for (i, b) in direct.bricks.iter().enumerate() {
                    let range = out.batch_offsets[i]..out.batch_offsets[i + 1];
                    assert_eq!(range.len(), b.batches.len());
                    for (k, batch) in range.zip(&b.batches) {
                        assert_eq!(out.batch_slab[k], batch.slab);
                        assert_eq!(out.batch_first[k]..out.batch_end[k], batch.triangles);
                        let clip = batch.clip.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
                        assert_eq!(out.batch_clip[2 * k..2 * k + 2], [clip.0, clip.1]);
                        batch.triangles.clone().for_each(|t| seen[t as usize] = true);
                    }
                }
                assert_eq!(seen.iter().all(|&v| v), opacity > 0.0 && opacity < 1.0, "opacity {opacity}");
                if opacity == 1.0 {
                    assert_eq!(out.opaque_triangles, polygons);
                }
            }
        }
        // Kept SlabPolygons are made again for another surface.
        let other = h.surface_for_drawing(bytes(&d), &desc(), 0.3, SurfaceMode::Discretized).unwrap();
        let c = &cameras()[1];
        let scene = Scene { surface: Some(&other.surface), surface_opacity: 0.4, shading: false };
        let direct = plan::draw_list(&h.octree, &h.shape, &s.selection, &camera(c).unwrap(), &scene, None).unwrap();
        assert_eq!(s.list(&h, c, Some((&other, 0.4))).unwrap(), direct);
    }

    #[test]
    fn draw_list_with_a_surface_errors() {
        use crate::ffi::SurfaceMode;
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let other = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h.select_bricks(&options(12_000)).unwrap();
        let surface = h.surface_for_drawing(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized).unwrap();
        let foreign = other.surface_for_drawing(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized).unwrap();
        let c = &cameras()[0];
        assert!(s.draw_list_with_surface(&h, c, &foreign, 0.5).unwrap_err().contains("another octree"));
        assert!(foreign.mesh(&h).unwrap_err().contains("another octree"));
        for bad in [f64::NAN, 1.5, -0.1] {
            assert!(s.draw_list_with_surface(&h, c, &surface, bad).unwrap_err().contains("surface opacity"));
        }
        let e = h.surface_for_drawing(bytes(&d), &desc(), f64::NAN, SurfaceMode::Discretized).map(|_| ()).unwrap_err();
        assert!(e.contains("isovalue"), "{e}");
    }

    #[test]
    fn composite_through_the_bridge_is_the_cpu_compositor() {
        use crate::ffi::SurfaceMode;
        use crate::render::compositor::composite;
        let d = data();
        let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
        let s = h.select_bricks(&options(30_000)).unwrap();
        let surface = h.surface_for_drawing(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized).unwrap();
        let colors = [0.0, 0.2, 0.3, 0.4, 1.0, 1.0, 0.9, 0.8];
        let opacities = [0.0, 0.0, 0.3, 0.05, 1.0, 0.2];
        let tf = TransferFunction::new(
            vec![(0.0, [0.2, 0.3, 0.4]), (1.0, [1.0, 0.9, 0.8])],
            vec![(0.0, 0.0), (0.3, 0.05), (1.0, 0.2)],
        )
        .unwrap();
        let grid = grid_of(bytes(&d), &desc()).unwrap();
        for c in cameras() {
            let volume = s.composite(&h, &c, bytes(&d), &desc(), &colors, &opacities, false, 40, 30).unwrap();
            let direct = composite(&grid, &s.list(&h, &c, None).unwrap(), &tf, 40, 30, None).unwrap();
            assert_eq!(volume, direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
            assert!(volume.iter().any(|&v| v > 0.0), "the ball shows");
            for opacity in [0.4, 1.0] {
                let rgba = [0.9, 0.5, 0.1, opacity];
                let with = s
                    .composite_with_surface(
                        &h,
                        &c,
                        bytes(&d),
                        &desc(),
                        &colors,
                        &opacities,
                        false,
                        &surface,
                        &rgba,
                        40,
                        30,
                    )
                    .unwrap();
                let list = s.list(&h, &c, Some((&surface, opacity))).unwrap();
                let drawn = Some((&surface.surface, rgba.map(|v| v as f32)));
                let direct = composite(&grid, &list, &tf, 40, 30, drawn).unwrap();
                assert_eq!(with, direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
                assert_ne!(with, volume, "the surface shows at opacity {opacity}");
            }
        }
        let c = &cameras()[0];
        let e = s
            .composite_with_surface(&h, c, bytes(&d), &desc(), &colors, &opacities, false, &surface, &[1.0; 3], 8, 8)
            .unwrap_err();
        assert!(e.contains("surface colour"), "{e}");
        assert!(s
            .composite(&h, c, bytes(&d), &desc(), &colors[..3], &opacities, false, 8, 8)
            .unwrap_err()
            .contains("tuples"));
    }
}
