//! The scene `render` and `bench render` share: the volume and its octree,
//! an optional isosurface, a transfer function, a camera, and one frame made
//! from a selection (select, SlabPolygons, DrawList, texture upload,
//! composite), timed step
//! by step.

use crate::build::build_octree;
use crate::field::Field;
use clap::Args;
use hybrid_octree::camera::Camera;
use hybrid_octree::grid::{Grid, GridShape};
use hybrid_octree::octree::{BuildOptions, VolumeOctree, DEFAULT_LEAF_SIZE};
use hybrid_octree::plan::crop::KeptRegion;
use hybrid_octree::plan::point_slabs::add_points;
use hybrid_octree::plan::scattering::plan_scattering;
use hybrid_octree::plan::texel_format::{TexelEncoding, TexelFormat};
use hybrid_octree::plan::{draw_list, plan, Blend, BlendMode, DrawList, Scene, SurfacePass};
use hybrid_octree::points::{shade, Footprint, PointSet};
use hybrid_octree::render::compositor::composite_shadowed;
use hybrid_octree::render::image::Image;
use hybrid_octree::render::reference::{reference_blend, ReferenceOptions};
use hybrid_octree::render::transfer::TransferFunction;
use hybrid_octree::select::{Roi, SelectOptions, Selection};
use hybrid_octree::slab::SlabPolygons;
use hybrid_octree::surface::{Surface, SurfaceOptions};
use hybrid_octree::transfer::{GradientOpacity, TransferFunction2D};
use hybrid_octree::{Error, Result};
use std::time::Instant;

/// View and scene options shared by `render` and `bench render`.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Leaf brick size of the Volume Octree (power of two, 2..=256).
    #[arg(long, default_value_t = DEFAULT_LEAF_SIZE)]
    pub leaf_size: usize,
    /// Also draw the isosurface at this value (the Hybrid Octree's DiscMC surface).
    #[arg(long, allow_negative_numbers = true)]
    pub isovalue: Option<f64>,
    /// Opacity of the isosurface: 1 opaque (drawn first), below 1 translucent (drawn in the slabs).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub surface_opacity: f64,
    /// Camera azimuth in degrees about +z (0: looking from -y).
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Camera elevation in degrees above the xy plane.
    #[arg(long, default_value_t = 20.0, allow_hyphen_values = true)]
    pub elevation: f64,
    /// Parallel projection instead of perspective.
    #[arg(long)]
    pub parallel: bool,
    /// Image width in pixels.
    #[arg(long, default_value_t = 512)]
    pub width: usize,
    /// Image height in pixels.
    #[arg(long, default_value_t = 512)]
    pub height: usize,
    /// Region of interest X,Y,Z,R (index space): refined first.
    #[arg(long, value_parser = roi, allow_hyphen_values = true)]
    pub roi: Option<Roi>,
    /// Volume shading.
    #[command(flatten)]
    pub shade: crate::shade::ShadeArgs,
    /// Volumetric scattering (with --shade).
    #[command(flatten)]
    pub scattering: crate::scattering::ScatteringArgs,
    /// Blend mode (VTK's SetBlendMode): composite, mip (maximum intensity),
    /// minip (minimum intensity), average (average intensity), additive,
    /// isosurface (the surfaces of --isosurface-values, ray cast), or slice
    /// (the volume on the plane of --slice-origin, --slice-normal).
    #[arg(long, default_value = "composite", value_parser = blend_mode)]
    pub blend: BlendMode,
    /// The values the isosurface blend mode draws, comma-separated (data units).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub isosurface_values: Vec<f64>,
    /// Gradient opacity G0,A0,G1,A1,...: opacity A (in [0, 1]) at gradient
    /// magnitude G (data units per world unit, increasing), piecewise linear,
    /// multiplying each sample's opacity (vtkVolumeProperty's GradientOpacity; Composite only).
    #[arg(long, value_parser = gradient_opacity, allow_hyphen_values = true)]
    pub gradient_opacity: Option<GradientOpacity>,
    /// Cropping and clipping planes of the volume.
    #[command(flatten)]
    pub crop: crate::crop::CropArgs,
    /// A 2D transfer function (JSON, docs/CLI.md): colour and opacity from
    /// the value and the gradient magnitude together, instead of the ramp
    /// and the gradient opacity (vtkVolumeProperty's TF_2D; Composite only).
    #[arg(long)]
    pub transfer_2d: Option<std::path::PathBuf>,
    /// The Slice blend mode's plane.
    #[command(flatten)]
    pub slice: crate::slice::SliceArgs,
    /// Jittering (VTK's UseJittering): each pixel's samples moved along its
    /// ray by a fixed fraction of the slice spacing, so coarse bricks show
    /// noise, not wood-grain rings (not in Slice, nor with a translucent
    /// surface or points; the plan's effects then end with `jittering`).
    #[arg(long)]
    pub jitter: bool,
    /// Brick texel format: auto (the data's own width: 8-bit data as unorm8,
    /// 16-bit as unorm16, the rest float32), float32, float16, unorm16 or
    /// unorm8. A narrower format holds more bricks in the budget at the price
    /// of its quantization error, which the selection counts.
    #[arg(long, default_value = "auto", value_parser = texel_format)]
    pub texel_format: TexelFormat,
    /// The view-dependent selection.
    #[command(flatten)]
    pub view: crate::view::ViewArgs,
}

fn texel_format(s: &str) -> std::result::Result<TexelFormat, String> {
    TexelFormat::parse(s).map_err(|e| e.to_string())
}

/// The `--gradient-opacity` points, checked ([`GradientOpacity::new`]).
fn gradient_opacity(s: &str) -> std::result::Result<GradientOpacity, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|p| p.trim().parse::<f64>().map_err(|_| format!("'{}' is not a number", p.trim())))
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| format!("'{s}' is not G0,A0,G1,A1,...: {e}"))?;
    if !v.len().is_multiple_of(2) {
        return Err(format!(
            "'{s}' has {} numbers: give pairs G,A (gradient magnitude, opacity), an even count",
            v.len()
        ));
    }
    GradientOpacity::new(v.chunks_exact(2).map(|p| (p[0], p[1] as f32)).collect()).map_err(|e| e.to_string())
}

fn blend_mode(s: &str) -> std::result::Result<BlendMode, String> {
    s.parse::<BlendMode>().map_err(|e| e.to_string())
}

fn roi(s: &str) -> std::result::Result<Roi, String> {
    let v: Vec<f64> =
        s.split(',').map(|p| p.trim().parse::<f64>()).collect::<std::result::Result<_, _>>().map_err(|_| {
            format!("'{s}' is not X,Y,Z,R (four numbers: the centre in index space and the radius in index units)")
        })?;
    match v[..] {
        [x, y, z, r] => Ok(Roi { center: [x, y, z], radius: r }),
        _ => Err(format!("'{s}' is not X,Y,Z,R: give four numbers")),
    }
}

/// A loaded scene.
pub struct Loaded {
    /// The octree.
    pub octree: VolumeOctree,
    /// The isosurface, if asked for.
    pub surface: Option<Surface>,
    /// The transfer function (a ramp over the data range).
    pub tf: TransferFunction,
    /// The camera.
    pub camera: Camera,
    /// The blend mode over the data range.
    pub blend: Blend,
    /// A gradient opacity that is 0 at every magnitude (Composite): every
    /// sample is transparent.
    pub hidden_by_gradient_opacity: bool,
    /// The cropping and clipping planes, world coordinates.
    pub region: Option<KeptRegion>,
    /// The same in index space, what the selection leaves out by.
    pub select_region: Option<KeptRegion>,
    /// The 2D transfer function of `--transfer-2d`.
    pub transfer_2d: Option<TransferFunction2D>,
    /// The Slice mode's plane in index space: the selection keeps the nodes it cuts.
    pub select_slice: Option<hybrid_octree::plan::SlicePlane>,
    /// The brick textures' texel format, resolved for the data.
    pub texel: TexelEncoding,
}

/// Builds the octree, the surface and the camera for `grid`.
pub fn load(grid: &Grid<'_>, args: &SceneArgs) -> Result<Loaded> {
    check_view(args)?;
    let octree = build_octree(grid, &BuildOptions { leaf_size: args.leaf_size })?;
    dress(grid, octree, args)
}

/// The scene of `args` around an octree already built for `grid` (with
/// `args.leaf_size`): the surface, the transfer function, the camera and
/// the blend mode.
pub fn dress(grid: &Grid<'_>, octree: VolumeOctree, args: &SceneArgs) -> Result<Loaded> {
    dress_field(Field::Grid(grid), octree, args)
}

/// [`dress`] for a volume in memory or on disk: an isosurface needs it in memory.
pub fn dress_field(field: Field<'_>, octree: VolumeOctree, args: &SceneArgs) -> Result<Loaded> {
    check_view(args)?;
    let region = args.crop.region()?;
    let surface = match args.isovalue {
        Some(iso) => Some(Surface::extract(
            field.grid("an isosurface (--isovalue)")?,
            &octree,
            &SurfaceOptions::discretized(iso),
        )?),
        None => None,
    };
    let (min, max) = octree.value_range();
    let tf = TransferFunction::ramp(min, max);
    let shape = field.shape();
    let lo = shape.world([0.0; 3]);
    let hi = shape.world(shape.dims.map(|d| (d - 1) as f64));
    let camera = Camera::around(lo, hi, args.azimuth, args.elevation, args.parallel)?;
    let plane = args.slice.plane(args.blend, lo, hi)?;
    let blend = match (args.blend, args.isosurface_values.is_empty(), plane) {
        (BlendMode::Isosurface, _, _) => Blend::isosurfaces(&args.isosurface_values, [min, max])?,
        (BlendMode::Slice, true, Some(plane)) => Blend::slice(plane, [min, max])?,
        (_, true, _) => Blend::new(args.blend, [min, max]),
        (_, false, _) => {
            return Err(hybrid_octree::Error::InvalidArgument(
                "--isosurface-values is for --blend isosurface: add it, or leave the values out".into(),
            ))
        }
    };
    let hidden_by_gradient_opacity =
        args.blend == BlendMode::Composite && args.gradient_opacity.as_ref().is_some_and(|g| g.constant() == Some(0.0));
    let select_region = region.map(|r| r.to_index(shape));
    let transfer_2d = match &args.transfer_2d {
        Some(path) => Some(crate::transfer2d::load(path, (min, max), shape)?),
        None => None,
    };
    let select_slice = plane.map(|p| p.to_index(shape));
    let texel = TexelEncoding::resolve(args.texel_format, field.scalar_type(), (min, max), field.nan_count())?;
    Ok(Loaded {
        octree,
        surface,
        tf,
        camera,
        blend,
        hidden_by_gradient_opacity,
        region,
        select_region,
        transfer_2d,
        select_slice,
        texel,
    })
}

/// The image size and the surface opacity: in range, or a clear error.
fn check_view(args: &SceneArgs) -> Result<()> {
    if args.width == 0 || args.height == 0 || args.width > 8192 || args.height > 8192 {
        return Err(Error::InvalidArgument(format!(
            "image size {}x{} is out of range: use 1..=8192 pixels per side",
            args.width, args.height
        )));
    }
    if !(0.0..=1.0).contains(&args.surface_opacity) {
        return Err(Error::InvalidArgument(format!(
            "surface opacity {} must be between 0 and 1",
            args.surface_opacity
        )));
    }
    Ok(())
}

/// The selection's options for `scene` under `budget_bytes` and `tolerance`:
/// the region of interest, the gradient border when the frame is shaded
/// (Composite only), peak-keeping texels for MIP and MinIP, the nodes the
/// cropping and clipping planes remove left out, the bytes and error of the
/// scene's texel format.
pub fn select_options(scene: &Loaded, args: &SceneArgs, budget_bytes: usize, tolerance: f64) -> SelectOptions {
    SelectOptions {
        roi: args.roi,
        gradient_border: hybrid_octree::plan::needs_gradients(
            args.shade.lighting().as_ref(),
            args.gradient_opacity.as_ref(),
            scene.transfer_2d.is_some(),
            scene.blend.mode,
        ) || scene.blend.mode == BlendMode::Isosurface,
        pooled: scene.blend.mode.is_extremum(),
        region: scene.select_region,
        slice: scene.select_slice,
        bytes_per_texel: scene.texel.bytes(),
        texel_error: scene.texel.normalized_error(scene.octree.value_range()),
        ..SelectOptions::new(budget_bytes, tolerance)
    }
}

/// One frame: its DrawList, image and step times.
pub struct Frame {
    /// What was drawn.
    pub list: DrawList,
    /// The picture.
    pub image: Image,
    /// SlabPolygons time (the selection's surface batches, translucent
    /// surfaces only; once per selection), ms.
    pub slab_polygons_ms: f64,
    /// DrawList time (the per-view part: order, slices, batches and points into slabs, plan), ms.
    pub drawlist_ms: f64,
    /// Texture upload time (the bricks' textures copied once per DrawList) and the points'
    /// shading (once per transfer function), ms.
    pub upload_ms: f64,
    /// Compositing time (the frame drawn from the uploaded textures), ms.
    pub composite_ms: f64,
}

/// Makes the SlabPolygons (translucent surface) and the DrawList for
/// `selection` (with `points` in its slabs), and composites it.
pub fn frame(
    grid: &Grid<'_>,
    scene: &Loaded,
    selection: &Selection,
    args: &SceneArgs,
    points: Option<(&PointSet, Footprint)>,
) -> Result<Frame> {
    frame_of(Field::Grid(grid), scene, selection, args, points)
}

/// [`frame`] of a volume in memory or on disk (points need it in memory).
pub fn frame_of(
    field: Field<'_>,
    scene: &Loaded,
    selection: &Selection,
    args: &SceneArgs,
    points: Option<(&PointSet, Footprint)>,
) -> Result<Frame> {
    let planned = plan_frame(field.shape(), scene, selection, args, points.map(|p| p.0))?;
    draw_frame(field, scene, planned, args, points)
}

/// A frame's DrawList and what making it took (SlabPolygons, DrawList ms).
pub struct Planned {
    /// The DrawList.
    pub list: DrawList,
    /// SlabPolygons time, ms.
    pub slab_polygons_ms: f64,
    /// DrawList time, ms.
    pub drawlist_ms: f64,
}

/// The SlabPolygons (translucent surface) and the DrawList of `selection`
/// (with `points` in its slabs) over the grid of `shape`: the plan of [`frame_of`].
pub fn plan_frame(
    shape: &GridShape,
    scene: &Loaded,
    selection: &Selection,
    args: &SceneArgs,
    points: Option<&PointSet>,
) -> Result<Planned> {
    let lighting = args.shade.lighting();
    let view = scene_view(scene, args, lighting.as_ref());
    let started = Instant::now();
    let polygons = match (plan(selection, &view).surface, &scene.surface) {
        (SurfacePass::Translucent, Some(s)) => Some(SlabPolygons::new(&scene.octree, s, shape, selection)),
        _ => None,
    };
    let slab_polygons_ms = started.elapsed().as_secs_f64() * 1e3;
    let started = Instant::now();
    let mut list = draw_list(&scene.octree, shape, selection, &scene.camera, &view, polygons.as_ref())?;
    list.texel = scene.texel;
    if let Some(set) = points {
        add_points(&mut list, shape, set)?;
    }
    let scattering = args.scattering.scattering(scene.octree.value_range())?;
    let list = plan_scattering(list, lighting.as_ref(), scattering.as_ref())?;
    let list = hybrid_octree::plan::jitter::plan_jitter(list, args.jitter);
    let drawlist_ms = started.elapsed().as_secs_f64() * 1e3;
    Ok(Planned { list, slab_polygons_ms, drawlist_ms })
}

/// What the planner sees of the scene.
fn scene_view<'a>(
    scene: &'a Loaded,
    args: &'a SceneArgs,
    lighting: Option<&'a hybrid_octree::transfer::lighting::Lighting>,
) -> Scene<'a> {
    Scene {
        surface: scene.surface.as_ref(),
        surface_opacity: args.surface_opacity,
        shading: lighting,
        gradient_opacity: args.gradient_opacity.as_ref(),
        transfer_2d: scene.transfer_2d.as_ref(),
        blend: scene.blend,
        region: scene.region.as_ref(),
    }
}

/// Uploads the textures of a planned frame and composites it.
pub fn draw_frame(
    field: Field<'_>,
    scene: &Loaded,
    planned: Planned,
    args: &SceneArgs,
    points: Option<(&PointSet, Footprint)>,
) -> Result<Frame> {
    let Planned { list, slab_polygons_ms, drawlist_ms } = planned;
    let started = Instant::now();
    let textures = field.upload(&list)?;
    let shadow = field.shadow(&list)?;
    let shades = match points {
        Some((set, _)) => shade(field.grid("points")?, set, &scene.tf)?,
        None => Vec::new(),
    };
    let upload_ms = started.elapsed().as_secs_f64() * 1e3;
    let started = Instant::now();
    let colour = surface_colour(args);
    let surface = scene.surface.as_ref().map(|s| (s, colour));
    let drawn = points.map(|(set, kind)| (set, shades.as_slice(), kind));
    let image =
        composite_shadowed(&textures, shadow.as_ref(), &list, &scene.tf, args.width, args.height, surface, drawn)?;
    let composite_ms = started.elapsed().as_secs_f64() * 1e3;
    Ok(Frame { list, image, slab_polygons_ms, drawlist_ms, upload_ms, composite_ms })
}

/// The isosurface colour `[r, g, b, opacity]`.
pub fn surface_colour(args: &SceneArgs) -> [f32; 4] {
    [0.9, 0.75, 0.55, args.surface_opacity as f32]
}

/// The full-resolution reference picture of the scene.
pub fn reference_image(grid: &Grid<'_>, scene: &Loaded, args: &SceneArgs) -> Result<Image> {
    reference_image_at(grid, scene, args, None)
}

/// [`reference_image`] of `grid` with the opacity unit distance `opacity_unit`
/// (world units; `None`: `grid`'s reference spacing): another sampling of
/// the scene's volume drawn with the scene's opacity per length.
pub fn reference_image_at(
    grid: &Grid<'_>,
    scene: &Loaded,
    args: &SceneArgs,
    opacity_unit: Option<f64>,
) -> Result<Image> {
    let surface = scene.surface.as_ref().map(|s| (s, surface_colour(args)));
    let lighting = args.shade.lighting();
    let scattering = args.scattering.scattering(scene.octree.value_range())?;
    reference_blend(
        grid,
        &scene.tf,
        &scene.camera,
        args.width,
        args.height,
        &ReferenceOptions {
            surface,
            lighting: lighting.as_ref(),
            gradient_opacity: args.gradient_opacity.as_ref(),
            transfer_2d: scene.transfer_2d.as_ref(),
            region: scene.region.as_ref(),
            opacity_unit,
            scattering: scattering.as_ref(),
            ..ReferenceOptions::default()
        },
        &scene.blend,
    )
}

/// The transfer function's visibility test for the selection: a node shows
/// unless the transfer function is transparent over its whole range, or a
/// gradient opacity is 0 everywhere (and, with a surface, it holds none of
/// it); under the blend mode's rule ([`Blend::visible`]). Under Composite
/// a 2D transfer function decides alone: a node shows unless the table is 0
/// over its range at every gradient magnitude.
pub fn visible<'a>(scene: &'a Loaded, isovalue: Option<f64>) -> impl Fn(f64, f64) -> bool + 'a {
    let classifies = scene.transfer_2d.as_ref().filter(|_| scene.blend.mode == BlendMode::Composite);
    move |min, max| {
        let shows = match classifies {
            Some(t) => !t.is_transparent_over(min, max),
            None => {
                !scene.hidden_by_gradient_opacity
                    && scene.blend.visible(min, max, &|a, b| !scene.tf.is_transparent_over(a, b))
            }
        };
        shows || isovalue.is_some_and(|iso| min < iso && iso <= max)
    }
}
