//! Which passes a scene needs (ARCHITECTURE section 6) and the DrawList the
//! renderers execute.
//!
//! The planner looks at the scene and emits only what it calls for, and says
//! which passes it chose ([`Plan::passes`]):
//!
//! - no surface: volume bricks only;
//! - opaque surface: the surface pass first (depth test and write), then the
//!   bricks with depth test only, no interleaving;
//! - translucent surface: each brick's triangle batches drawn inside its
//!   slabs, back to front, clip planes only for batches spanning slabs;
//! - bricks fully transparent under the transfer function: never selected
//!   (no texture spent), counted in [`Plan::skipped_bricks`];
//! - shading only when asked for and when it changes a colour (not with
//!   `ambient = 1, diffuse = specular = 0` under the headlight): then the
//!   plan says `volume-shaded` and the DrawList carries the lighting, its
//!   lights in world space.
//! - the blend mode ([`Blend`]): `volume` for Composite, `volume-mip`,
//!   `volume-minip`, `volume-average` or `volume-additive` for the others
//!   or `volume-isosurface`, or `volume-slice` (the Slice mode's plane,
//!   [`crate::plan::slice`]: only the nodes it cuts are selected); shading,
//!   `-shaded`, is for the compositing modes, Composite and Isosurface, and
//!   Slice, as VTK shades; a translucent surface is for the first two: it is
//!   sorted into the slabs of a composite, and a reduced ray has no order,
//!   so under the other modes it is not drawn, while an opaque surface still is).
//! - gradient opacity ([`GradientOpacity`], Composite only) only when it
//!   changes an opacity: not when it is 1 at every magnitude; a constant
//!   `c != 1` scales every opacity without a gradient ([`Plan::opacity_scale`],
//!   effect `opacity-scale`); otherwise each sample's gradient is taken
//!   ([`Plan::gradient_opacity`], effect `gradient-opacity`, the DrawList
//!   carries the function).
//! - a 2D transfer function ([`TransferFunction2D`], Composite only, as
//!   VTK 9.2 draws it) classifies each sample by its value and gradient
//!   magnitude instead of the 1D function: effect `transfer-2d`, gradients
//!   taken, the DrawList carries the table; the 1D gradient opacity is then
//!   not applied (VTK's TF_2D mode ignores it). Under the other blend modes
//!   it is not planned (the 1D function classifies).
//! - [`Plan::effects`] names what each volume sample does besides its
//!   classification, in the order applied: `transfer-2d` (the
//!   classification itself), `gradient-opacity` or `opacity-scale`, then
//!   `shading`. Gradients are taken exactly when
//!   [`Plan::gradients`]; brick textures carry their border when
//!   [`Plan::bordered`] (gradients, or Isosurface's step back).
//! - cropping and clipping planes ([`crate::plan::crop`]) only where they
//!   remove part of the volume's box: a cropping that keeps the whole box
//!   and a plane with the whole box on its kept side are dropped; what is
//!   left is [`DrawList::region`], and [`Plan::effects`] ends with
//!   `cropping`, `clipping`. Bricks whose box it removes are not selected
//!   ([`crate::plan::select::SelectOptions::region`]). They act on the
//!   volume's samples only, in every blend mode (a removed sample is no
//!   sample; Isosurface shows nothing there): the isosurface and the points
//!   are drawn whole.

use super::blend::Blend;
use super::crop::KeptRegion;
use super::select::Brick;
use super::slab::Batch;
use crate::geometry::camera::Camera;
use crate::transfer::lighting::Lighting;
use crate::transfer::{GradientOpacity, TransferFunction2D};
use rayon::prelude::*;

/// How the surface is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfacePass {
    /// No surface in the scene.
    None,
    /// Opaque: a depth-tested surface pass before the volume.
    Opaque,
    /// Translucent: batches inside the slabs of the bricks.
    Translucent,
}

/// What the renderer will do, and why it skipped the rest.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Plan {
    /// Any brick to draw.
    pub volume: bool,
    /// How the surface is drawn.
    pub surface: SurfacePass,
    /// Gradient shading of the volume (the DrawList's [`DrawList::lighting`]).
    pub shading: bool,
    /// Gradient opacity taken per sample from its gradient (the DrawList's
    /// [`DrawList::gradient_opacity`]).
    pub gradient_opacity: bool,
    /// A constant factor of every sample's opacity before the slice-spacing
    /// correction: a gradient opacity that is this at every magnitude (1: none).
    pub opacity_scale: f64,
    /// Each sample classified by the 2D transfer function (the DrawList's
    /// [`DrawList::transfer_2d`]) from its value and gradient magnitude.
    pub transfer_2d: bool,
    /// Nodes not selected because the transfer function makes them fully transparent.
    pub skipped_bricks: usize,
    /// How the samples along a ray become a pixel.
    pub blend: Blend,
    /// The passes, in the order they run (e.g. `["surface-opaque", "volume"]`).
    pub passes: Vec<String>,
    /// Two fields with dependent components: each sample's colour from field
    /// 0, its opacity from field 1 ([`crate::plan::dependent`]; Composite only).
    pub dependent: bool,
    /// Four fields with dependent components (an RGBA volume): each sample's
    /// colour is fields 0, 1, 2 as VTK 9.2 reads them, its opacity the opacity
    /// function at field 3's `v'`, its gradient field 0's ([`crate::plan::dependent`]; Composite only).
    pub rgba: bool,
    /// What each volume sample does besides its classification, in the
    /// order applied (e.g. `["gradient-opacity", "shading"]`), then what
    /// removes samples in every pass, `cropping`, `clipping` (the DrawList's
    /// [`DrawList::region`]); see the module documentation.
    pub effects: Vec<String>,
    /// Each pixel's samples moved along its ray by a fixed fraction of the
    /// slice spacing ([`crate::plan::jitter`], effect `jittering`, last of [`Plan::effects`]).
    pub jitter: bool,
    /// Volumetric scattering (the DrawList's [`DrawList::scattering`],
    /// [`crate::plan::scattering`]): shadow rays towards the lights.
    pub scattering: bool,
    /// The ray sample distance `s` the slices were refined to
    /// ([`crate::plan::sampling`], effect `sample-distance`): every brick's
    /// slice spacing is `(s / d0)` of its stride's. `None`: the stride's.
    pub sample_distance: Option<f64>,
    /// The least slice spacing, world units, the slices were widened to so
    /// that a frame meets its time ([`crate::plan::cost::widen_slices`]):
    /// `m d0`, `m` a power of two. `None`: the strides' spacings.
    pub min_slice_spacing: Option<f64>,
}

impl Plan {
    /// Whether the volume's samples take gradients (shading, gradient
    /// opacity or the 2D transfer function): brick textures then carry one
    /// border texel per side.
    pub fn gradients(&self) -> bool {
        self.shading || self.gradient_opacity || self.transfer_2d || self.scattering
    }

    /// Whether brick textures carry one border texel per side: gradients
    /// read it, and Isosurface the sample before a brick's first.
    pub fn bordered(&self) -> bool {
        self.gradients() || (self.volume && self.blend.mode == super::BlendMode::Isosurface)
    }
}

/// One brick of the DrawList.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BrickDraw {
    /// The texture request: node, level p, texel box.
    pub brick: Brick,
    /// World box of the brick.
    pub world_lo: [f64; 3],
    /// World box of the brick.
    pub world_hi: [f64; 3],
    /// World distance d between consecutive slices (the brick's sample
    /// spacing along the view); opacity is corrected by `a' = 1 - (1 - a)^(d/d0)`.
    pub slice_spacing: f64,
    /// View depths of the slices through the brick, back to front: slice
    /// planes at depths `k * slice_spacing` (a lattice shared by all bricks of
    /// the same spacing), those inside the brick's depth range
    /// (`d_min <= z < d_max`, see [`crate::plan::slab::slice_depths`]). A sample on
    /// a face shared with another brick belongs to the brick whose NEAR face
    /// it is (each box is closed on the faces towards the eye and on the
    /// volume's own faces), so every point is sampled by exactly one brick;
    /// a GPU executor must use the same rule.
    pub slices: Vec<f64>,
    /// Surface batches (translucent surfaces only), back to front.
    pub batches: Vec<Batch>,
    /// Points of the hybrid representation in the brick, by slab, back to
    /// front (empty without points; see [`crate::plan::point_slabs`]).
    pub points: Vec<PointBucket>,
}

/// Points drawn between two slices of a brick (paper 3, section 4: "slices
/// of points are drawn interleaved with each pair of volumetric planes").
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PointBucket {
    /// Slab index within the brick, as [`Batch::slab`].
    pub slab: usize,
    /// Indices into the [`PointSet`](crate::points::PointSet)'s points, in grid order.
    pub points: Vec<u32>,
}

/// What every renderer executes: bricks in compositing order (back to
/// front), their slices, and the surface passes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DrawList {
    /// The plan.
    pub plan: Plan,
    /// The camera the list was made for.
    pub camera: Camera,
    /// Bricks back to front.
    pub bricks: Vec<BrickDraw>,
    /// Opaque surface pass: all triangle ids (empty unless the plan says opaque).
    pub opaque_triangles: Vec<u32>,
    /// Reference slice spacing d0 (world units): the full-resolution sample
    /// spacing, against which opacity is corrected.
    pub reference_spacing: f64,
    /// The volume's shading, lights in world space (`Some` exactly when
    /// [`Plan::shading`]); brick textures then carry one border texel per
    /// side for the gradient ([`crate::plan::select::SelectOptions::gradient_border`]).
    pub lighting: Option<Lighting>,
    /// The samples kept, world coordinates (`Some` exactly when
    /// [`Plan::effects`] is not empty): the cropping and planes that remove
    /// part of the volume's box.
    pub region: Option<KeptRegion>,
    /// The gradient opacity (`Some` exactly when [`Plan::gradient_opacity`]);
    /// brick textures then carry the gradient border too.
    pub gradient_opacity: Option<GradientOpacity>,
    /// The 2D transfer function (`Some` exactly when [`Plan::transfer_2d`]);
    /// brick textures then carry the gradient border.
    pub transfer_2d: Option<TransferFunction2D>,
    /// Volumetric scattering (`Some` exactly when [`Plan::scattering`]).
    pub scattering: Option<crate::transfer::scattering::LitScattering>,
    /// The brick textures' texel format (its bytes are the selection's
    /// `bytes_per_texel`): Float32 unless the caller resolved another one.
    pub texel: crate::plan::texel_format::TexelEncoding,
}

/// What the scene holds besides the volume.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The isosurface, if drawn.
    pub surface: Option<&'a crate::surface::Surface>,
    /// Its opacity: 1 opaque, in (0, 1) translucent, 0 hidden.
    pub surface_opacity: f64,
    /// Gradient shading of the volume: `Some` when the volume property asks
    /// (vtkVolumeProperty's Shade), with its material and the lights.
    pub shading: Option<&'a Lighting>,
    /// Gradient opacity of the volume (vtkVolumeProperty's GradientOpacity).
    pub gradient_opacity: Option<&'a GradientOpacity>,
    /// The 2D transfer function (vtkVolumeProperty's TF_2D mode): `Some`
    /// classifies the volume by value and gradient magnitude (Composite).
    pub transfer_2d: Option<&'a TransferFunction2D>,
    /// The blend mode (VTK's `vtkVolumeMapper::SetBlendMode`) and its ranges.
    pub blend: Blend,
    /// VTK's cropping and clipping planes, world coordinates (`None`: every
    /// sample is kept).
    pub region: Option<&'a KeptRegion>,
}

impl Scene<'_> {
    /// The volume alone under `blend`: no surface, no shading, gradient
    /// opacity, 2D transfer function, cropping or clipping.
    pub fn volume(blend: Blend) -> Scene<'static> {
        Scene {
            surface: None,
            surface_opacity: 1.0,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend,
            region: None,
        }
    }
}

/// The plan for a scene (see the module documentation). Its [`Plan::effects`]
/// name the region's only in [`draw_list`], which knows the volume's box.
pub fn plan(selection: &crate::plan::select::Selection, scene: &Scene<'_>) -> Plan {
    let has_surface = scene.surface.is_some_and(|s| s.polygon_count() > 0) && scene.surface_opacity > 0.0;
    let composite = scene.blend.mode.composites();
    let surface = match (has_surface, scene.surface_opacity >= 1.0) {
        (false, _) => SurfacePass::None,
        (true, true) => SurfacePass::Opaque,
        (true, false) if composite => SurfacePass::Translucent,
        // Sorted into the slabs of a composite only: a reduced ray has no order.
        (true, false) => SurfacePass::None,
    };
    let volume = !selection.bricks.is_empty();
    let mut passes = Vec::new();
    match surface {
        SurfacePass::Opaque => passes.push("surface-opaque".to_string()),
        SurfacePass::Translucent => passes.push("surface-in-slabs".to_string()),
        SurfacePass::None => {}
    }
    let mut plan = Plan {
        volume,
        surface,
        shading: false,
        gradient_opacity: false,
        opacity_scale: 1.0,
        transfer_2d: volume && scene.transfer_2d.is_some() && scene.blend.mode == super::BlendMode::Composite,
        skipped_bricks: selection.skipped,
        blend: scene.blend,
        passes,
        dependent: false,
        rgba: false,
        effects: Vec::new(),
        jitter: false,
        scattering: false,
        sample_distance: None,
        min_slice_spacing: None,
    };
    if volume {
        plan.passes.push(scene.blend.mode.pass());
    }
    plan_effects(&mut plan, scene.shading, scene.gradient_opacity);
    plan.effects = effects(&plan, None);
    plan
}

/// Whether a scene of this shading, gradient opacity, 2D transfer function
/// (`transfer_2d`: the scene has one) and blend mode takes gradients (the
/// planner's rules): what a selection's
/// [`crate::plan::select::SelectOptions::gradient_border`] should be.
pub fn needs_gradients(
    lighting: Option<&Lighting>,
    gradient_opacity: Option<&GradientOpacity>,
    transfer_2d: bool,
    mode: super::BlendMode,
) -> bool {
    let composite = mode == super::BlendMode::Composite;
    (mode.shades() && shades(true, lighting))
        || (composite && transfer_2d)
        || (composite && gradient_opacity.is_some_and(|g| g.constant().is_none()))
}

/// Sets `plan`'s per-sample effects (shading, gradient opacity and the volume
/// pass's name) for this lighting and gradient opacity; [`effects`] names them.
fn plan_effects(plan: &mut Plan, lighting: Option<&Lighting>, gradient_opacity: Option<&GradientOpacity>) {
    // The 1D gradient opacity is not applied under a 2D transfer function (VTK's TF_2D).
    let composite = plan.volume && plan.blend.mode == super::BlendMode::Composite && !plan.transfer_2d;
    // Shading in both compositing modes and Slice, gradient opacity in Composite only.
    plan.shading = plan.volume && plan.blend.mode.shades() && shades(true, lighting);
    let constant = gradient_opacity.map(|g| g.constant());
    plan.gradient_opacity = composite && matches!(constant, Some(None));
    plan.opacity_scale = match constant {
        Some(Some(c)) if composite => f64::from(c),
        _ => 1.0,
    };
    let mode = plan.blend.mode;
    let (plain, shaded) = (volume_pass(mode, false), volume_pass(mode, true));
    for pass in &mut plan.passes {
        if *pass == plain || *pass == shaded {
            *pass = volume_pass(mode, plan.shading);
        }
    }
}

/// The effect of volumetric scattering ([`crate::plan::scattering::EFFECT`]).
pub(crate) const SCATTERING_EFFECT: &str = "volume-scattering";

/// The effect of two dependent fields ([`crate::plan::dependent::EFFECT`]).
pub(crate) const DEPENDENT_EFFECT: &str = "dependent-components";

/// The effect of an RGBA volume's four dependent fields ([`crate::plan::dependent::RGBA_EFFECT`]).
pub(crate) const RGBA_COMPONENTS_EFFECT: &str = "rgba-components";

/// The effect of refined slices ([`crate::plan::sampling::EFFECT`]).
pub(crate) const SAMPLE_DISTANCE_EFFECT: &str = "sample-distance";

/// The effect of jittering ([`crate::plan::jitter::EFFECT`]).
pub(crate) const JITTER_EFFECT: &str = "jittering";

/// The plan's [`Plan::effects`]: what each sample does besides its
/// classification, in the order applied (`dependent-components`,
/// `rgba-components` or `transfer-2d`, then `gradient-opacity` or `opacity-scale`, then `shading`, then `volume-scattering`), then what `region` (the cropping and
/// planes acting on the volume, see [`crops`]) removes (`cropping`, `clipping`), then `sample-distance`, then `jittering`.
pub(crate) fn effects(plan: &Plan, region: Option<&KeptRegion>) -> Vec<String> {
    let mut effects = Vec::new();
    if plan.dependent {
        effects.push(DEPENDENT_EFFECT.to_string());
    }
    if plan.rgba {
        effects.push(RGBA_COMPONENTS_EFFECT.to_string());
    }
    if plan.transfer_2d {
        effects.push("transfer-2d".to_string());
    }
    if plan.gradient_opacity {
        effects.push("gradient-opacity".to_string());
    } else if plan.opacity_scale != 1.0 {
        effects.push("opacity-scale".to_string());
    }
    if plan.shading {
        effects.push("shading".to_string());
    }
    if plan.scattering {
        effects.push(SCATTERING_EFFECT.to_string());
    }
    effects.extend(region.map(|r| r.effects()).unwrap_or_default());
    if plan.sample_distance.is_some() {
        effects.push(SAMPLE_DISTANCE_EFFECT.to_string());
    }
    if plan.jitter {
        effects.push(JITTER_EFFECT.to_string());
    }
    effects
}

/// The volume pass: the blend mode's ([`super::BlendMode::pass`]), `-shaded`
/// appended when shaded (`volume-shaded`, `volume-isosurface-shaded`).
fn volume_pass(mode: super::BlendMode, shading: bool) -> String {
    match (mode, shading) {
        (super::BlendMode::Composite, true) => "volume-shaded".to_string(),
        (mode, true) => format!("{}-shaded", mode.pass()),
        (mode, false) => mode.pass(),
    }
}

/// The planner's cropping rule: of `region`, what removes part of the
/// volume's box `[lo, hi]` ([`KeptRegion::acting_on`]), when there is a volume.
fn crops(volume: bool, region: Option<&KeptRegion>, lo: [f64; 3], hi: [f64; 3]) -> Option<KeptRegion> {
    region.filter(|_| volume).and_then(|r| r.acting_on(lo, hi))
}

/// `list` planned again for `region` (world coordinates) over the grid of
/// `shape`, as [`draw_list`] plans [`Scene::region`]: [`Plan::effects`] and
/// [`DrawList::region`] say what removes part of the volume, or are cleared.
/// The bricks are not selected again: those `region` removes entirely still
/// draw (nothing); select with [`crate::plan::select::SelectOptions::region`]
/// to leave them out.
pub fn recrop(mut list: DrawList, region: Option<&KeptRegion>, shape: &crate::data::grid::GridShape) -> DrawList {
    let (lo, hi) = volume_box(shape);
    list.region = crops(list.plan.volume, region, lo, hi);
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}

/// The world box of the grid's samples.
fn volume_box(shape: &crate::data::grid::GridShape) -> ([f64; 3], [f64; 3]) {
    (shape.world([0.0; 3]), shape.world(shape.dims.map(|d| (d - 1) as f64)))
}

/// The planner's shading rule: shade a volume, when the scene asks, unless
/// the lighting gives every colour back ([`Lighting::is_identity`]).
fn shades(volume: bool, lighting: Option<&Lighting>) -> bool {
    volume && lighting.is_some_and(|l| !l.is_identity())
}

/// `list` planned again for `lighting` (lights in world or view space, for
/// the list's camera) and `gradient_opacity`, as [`draw_list`] plans
/// [`Scene::shading`] and [`Scene::gradient_opacity`]: the plan's `volume`
/// pass becomes `volume-shaded` (or back), its effects are made again, and
/// [`DrawList::lighting`] and [`DrawList::gradient_opacity`] are set, or
/// cleared when not applied.
///
/// # Errors
///
/// [`crate::Error::InvalidArgument`] for a bad number in the lighting ([`Lighting::check`]).
pub fn replan_effects(
    mut list: DrawList,
    lighting: Option<&Lighting>,
    gradient_opacity: Option<&GradientOpacity>,
) -> crate::Result<DrawList> {
    if let Some(l) = lighting {
        l.check()?;
    }
    plan_effects(&mut list.plan, lighting, gradient_opacity);
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list.lighting = lighting.filter(|_| list.plan.shading).map(|l| l.in_world(&list.camera));
    list.gradient_opacity = gradient_opacity.filter(|_| list.plan.gradient_opacity).cloned();
    Ok(list)
}

/// `list` planned again for the 2D transfer function `transfer_2d`, as
/// [`draw_list`] plans [`Scene::transfer_2d`] (Composite only): the plan's
/// `transfer_2d`, its effects and [`DrawList::transfer_2d`] set or cleared.
/// Call it before [`replan_effects`], which then leaves the 1D gradient
/// opacity out under a 2D function.
pub fn replan_transfer_2d(mut list: DrawList, transfer_2d: Option<&TransferFunction2D>) -> DrawList {
    list.plan.transfer_2d =
        list.plan.volume && transfer_2d.is_some() && list.plan.blend.mode == super::BlendMode::Composite;
    list.transfer_2d = transfer_2d.filter(|_| list.plan.transfer_2d).cloned();
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}

/// The DrawList for `selection` seen from `camera`: the plan, the bricks back
/// to front with their slices (every `stride` samples along the view: `d =
/// min(stride, c) d0`, against `d0`, see [`crate::data::spacing`]), and the surface
/// passes the plan asks for.
///
/// Only view-dependent work is done here (order, slices, UpdatePosition of
/// the surface batches, see [`crate::plan::slab`]). A translucent surface is drawn
/// from `polygons`, the selection's [`SlabPolygons`](crate::plan::slab::SlabPolygons)
/// made once per selection and surface; without it they are made here, every
/// call.
///
/// # Errors
///
/// [`crate::Error::InvalidArgument`] if `polygons` was made for other bricks
/// than `selection`'s or for a surface of another polygon count than
/// `scene.surface` (make them again after a new selection), or for a bad
/// number in the lighting ([`Lighting::check`]).
pub fn draw_list(
    octree: &crate::octree::VolumeOctree,
    shape: &crate::data::grid::GridShape,
    selection: &crate::plan::select::Selection,
    camera: &Camera,
    scene: &Scene<'_>,
    polygons: Option<&crate::plan::slab::SlabPolygons>,
) -> crate::Result<DrawList> {
    if let Some(l) = scene.shading {
        l.check()?;
    }
    let mut plan = plan(selection, scene);
    let lighting = scene.shading.filter(|_| plan.shading).map(|l| l.in_world(camera));
    let gradient_opacity = scene.gradient_opacity.filter(|_| plan.gradient_opacity).cloned();
    let transfer_2d = scene.transfer_2d.filter(|_| plan.transfer_2d).cloned();
    let (lo, hi) = volume_box(shape);
    let region = crops(plan.volume, scene.region, lo, hi);
    plan.effects = effects(&plan, region.as_ref());
    let d0 = crate::data::spacing::reference_spacing(shape);
    let ids: Vec<crate::octree::NodeId> = selection.bricks.iter().map(|b| b.node).collect();
    let order = crate::plan::order::brick_order(camera, octree, shape, &ids, true);
    let made;
    let polygons = match (plan.surface, scene.surface) {
        (SurfacePass::Translucent, Some(s)) => Some(match polygons {
            Some(p) if p.fits(selection, s.polygon_count()) => p,
            Some(_) => {
                return Err(crate::Error::InvalidArgument(
                    "the SlabPolygons were made for another selection or surface: make them again for this one".into(),
                ))
            }
            None => {
                made = crate::plan::slab::SlabPolygons::new(octree, s, shape, selection);
                &made
            }
        }),
        _ => None,
    };
    let bricks = order
        .par_iter()
        .map(|&i| {
            let brick = selection.bricks[i];
            let world_lo = shape.world(brick.lo.map(|v| v as f64));
            let world_hi = shape.world(brick.hi.map(|v| v as f64));
            let slice_spacing = crate::data::spacing::slice_spacing(shape, brick.stride);
            let slices = crate::plan::slab::slice_depths(camera, world_lo, world_hi, slice_spacing);
            let batches = match polygons.map(|p| p.brick(i)) {
                Some(b) if !b.is_empty() => crate::plan::slab::assign_batches(camera, &slices, b),
                _ => Vec::new(),
            };
            BrickDraw { brick, world_lo, world_hi, slice_spacing, slices, batches, points: Vec::new() }
        })
        .collect();
    let opaque_triangles = match (plan.surface, scene.surface) {
        (SurfacePass::Opaque, Some(s)) => (0..s.polygon_count() as u32).collect(),
        _ => Vec::new(),
    };
    Ok(DrawList {
        plan,
        camera: *camera,
        bricks,
        opaque_triangles,
        reference_spacing: d0,
        lighting,
        gradient_opacity,
        transfer_2d,
        region,
        scattering: None,
        texel: Default::default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::{BuildOptions, VolumeOctree};
    use crate::plan::select::{select, SelectOptions};
    use crate::surface::{Surface, SurfaceOptions};

    struct Fixture {
        volume: crate::data::volume::Volume,
        octree: VolumeOctree,
        surface: Surface,
    }

    fn fixture() -> Fixture {
        let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        let surface = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(0.5)).unwrap();
        Fixture { volume, octree, surface }
    }

    fn list(f: &Fixture, scene: &Scene<'_>, visible: impl Fn(f64, f64) -> bool) -> DrawList {
        let grid = f.volume.grid(None).unwrap();
        let options = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(200_000, 0.0) };
        let selection = select(&f.octree, &options, visible).unwrap();
        let shape = grid.shape();
        let camera = Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), 30.0, 20.0, false).unwrap();
        draw_list(&f.octree, shape, &selection, &camera, scene, None).unwrap()
    }

    #[test]
    fn volume_only_without_a_surface() {
        let f = fixture();
        let l = list(
            &f,
            &Scene {
                surface: None,
                surface_opacity: 1.0,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(l.plan.passes, vec!["volume"]);
        assert_eq!(l.plan.surface, SurfacePass::None);
        assert!(l.opaque_triangles.is_empty() && l.bricks.iter().all(|b| b.batches.is_empty()));
        assert!(l.bricks.iter().all(|b| !b.slices.is_empty()));
    }

    #[test]
    fn opaque_surface_first_then_volume_without_interleaving() {
        let f = fixture();
        let l = list(
            &f,
            &Scene {
                surface: Some(&f.surface),
                surface_opacity: 1.0,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(l.plan.passes, vec!["surface-opaque", "volume"]);
        assert_eq!(l.opaque_triangles.len(), f.surface.polygon_count());
        assert!(l.bricks.iter().all(|b| b.batches.is_empty()), "no batches in the slabs");
    }

    #[test]
    fn translucent_surface_goes_into_the_slabs_every_triangle_at_least_once() {
        let f = fixture();
        let shaded = Lighting::headlight(Default::default());
        let l = list(
            &f,
            &Scene {
                surface: Some(&f.surface),
                surface_opacity: 0.4,
                shading: Some(&shaded),
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(l.plan.passes, vec!["surface-in-slabs", "volume-shaded"]);
        assert!(l.opaque_triangles.is_empty());
        let mut seen = vec![false; f.surface.polygon_count()];
        for b in &l.bricks {
            for batch in &b.batches {
                for t in batch.triangles.clone() {
                    seen[t as usize] = true;
                }
            }
        }
        assert!(seen.iter().all(|&s| s), "a triangle is in no batch");
    }

    #[test]
    fn slab_polygons_made_once_give_the_same_list_for_each_view() {
        let f = fixture();
        let grid = f.volume.grid(None).unwrap();
        let shape = grid.shape();
        let options = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(200_000, 0.0) };
        let selection = select(&f.octree, &options, |_, _| true).unwrap();
        let polygons = crate::plan::slab::SlabPolygons::new(&f.octree, &f.surface, shape, &selection);
        let scene = Scene {
            surface: Some(&f.surface),
            surface_opacity: 0.4,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        for (azimuth, elevation, parallel) in [(0.0, 0.0, true), (45.0, 35.0, false), (200.0, -60.0, false)] {
            let camera =
                Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), azimuth, elevation, parallel).unwrap();
            let once = draw_list(&f.octree, shape, &selection, &camera, &scene, Some(&polygons)).unwrap();
            assert_eq!(once, draw_list(&f.octree, shape, &selection, &camera, &scene, None).unwrap());
            assert!(once.bricks.iter().any(|b| !b.batches.is_empty()));
        }
    }

    #[test]
    fn slab_polygons_of_another_selection_are_refused() {
        let f = fixture();
        let grid = f.volume.grid(None).unwrap();
        let shape = grid.shape();
        // Other nodes (a SlabPolygons depends on the bricks' nodes only, not their strides).
        let small = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(200_000, 0.0) };
        let all = select(&f.octree, &small, |_, _| true).unwrap();
        let fewer = select(&f.octree, &SelectOptions::new(20_000, 0.0), |_, _| true).unwrap();
        let nodes = |s: &crate::plan::select::Selection| s.bricks.iter().map(|b| b.node).collect::<Vec<_>>();
        assert_ne!(nodes(&all), nodes(&fewer));
        let polygons = crate::plan::slab::SlabPolygons::new(&f.octree, &f.surface, shape, &fewer);
        let camera = Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), 30.0, 20.0, false).unwrap();
        let scene = Scene {
            surface: Some(&f.surface),
            surface_opacity: 0.4,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        let e = draw_list(&f.octree, shape, &all, &camera, &scene, Some(&polygons)).unwrap_err().to_string();
        assert!(e.contains("made for another selection or surface"), "{e}");
    }

    #[test]
    fn transparent_nodes_cost_no_texture_and_a_hidden_surface_no_pass() {
        let f = fixture();
        let l = list(
            &f,
            &Scene {
                surface: Some(&f.surface),
                surface_opacity: 0.0,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, max| max > 0.9,
        );
        assert!(l.plan.skipped_bricks > 0);
        assert_eq!(l.plan.surface, SurfacePass::None);
        assert!(!l.plan.shading);
        let shaded = Lighting::headlight(Default::default());
        let none = list(
            &f,
            &Scene {
                surface: None,
                surface_opacity: 1.0,
                shading: Some(&shaded),
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| false,
        );
        assert!(!none.plan.volume && none.bricks.is_empty() && none.plan.passes.is_empty() && !none.plan.shading);
    }

    /// A reduced ray has no depth order: under the blend modes besides
    /// Composite a translucent surface gets no pass (an opaque one keeps its).
    #[test]
    fn a_translucent_surface_is_composited_only() {
        let f = fixture();
        for mode in [super::super::BlendMode::Mip, super::super::BlendMode::Additive] {
            let blend = Blend::new(mode, [0.0, 1.0]);
            let scene = |opacity| Scene {
                surface: Some(&f.surface),
                surface_opacity: opacity,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend,
                region: None,
            };
            let l = list(&f, &scene(0.4), |_, _| true);
            assert_eq!(l.plan.surface, SurfacePass::None);
            assert_eq!(l.plan.passes, vec![mode.pass()]);
            assert!(l.bricks.iter().all(|b| b.batches.is_empty()));
            let l = list(&f, &scene(1.0), |_, _| true);
            assert_eq!(l.plan.passes, vec!["surface-opaque".to_string(), mode.pass()]);
        }
    }

    /// Shading that changes no colour (ambient 1, diffuse and specular 0,
    /// the headlight) is planned unshaded: "volume", no lighting in the list.
    #[test]
    fn identity_shading_is_not_planned() {
        let f = fixture();
        let identity = Lighting::headlight(crate::transfer::lighting::Material {
            ambient: 1.0,
            diffuse: 0.0,
            specular: 0.0,
            specular_power: 10.0,
        });
        let l = list(
            &f,
            &Scene {
                surface: None,
                surface_opacity: 1.0,
                shading: Some(&identity),
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(l.plan.passes, vec!["volume"]);
        assert!(!l.plan.shading && l.lighting.is_none());
        let shaded = Lighting::headlight(Default::default());
        let l = list(
            &f,
            &Scene {
                surface: None,
                surface_opacity: 1.0,
                shading: Some(&shaded),
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(l.plan.passes, vec!["volume-shaded"]);
        assert!(l.plan.shading && l.lighting.is_some());
        // Planned again: the same as planned with the scene's shading.
        let plain = list(
            &f,
            &Scene {
                surface: None,
                surface_opacity: 1.0,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend: Default::default(),
                region: None,
            },
            |_, _| true,
        );
        assert_eq!(replan_effects(plain.clone(), Some(&shaded), None).unwrap(), l);
        assert_eq!(replan_effects(l, Some(&identity), None).unwrap(), plain);
    }

    /// Gradient opacity: none or 1 everywhere is no effect; a constant `c !=
    /// 1` is the effect `opacity-scale` without gradients; one that varies is
    /// `gradient-opacity` with gradients and the function in the list, before
    /// `shading`; only for Composite; planned again the same.
    #[test]
    fn gradient_opacity_is_planned_only_when_it_changes_an_opacity() {
        let f = fixture();
        fn scene<'a>(
            g: Option<&'a GradientOpacity>,
            shading: Option<&'a Lighting>,
            mode: super::super::BlendMode,
        ) -> Scene<'a> {
            Scene {
                surface: None,
                surface_opacity: 1.0,
                shading,
                gradient_opacity: g,
                transfer_2d: None,
                blend: super::super::Blend::new(mode, [0.0, 1.0]),
                region: None,
            }
        }
        let composite = super::super::BlendMode::Composite;
        let plain = list(&f, &scene(None, None, composite), |_, _| true);
        let one = GradientOpacity::new(vec![(0.0, 1.0), (2.0, 1.0)]).unwrap();
        assert_eq!(list(&f, &scene(Some(&one), None, composite), |_, _| true), plain);
        assert!(!needs_gradients(None, Some(&one), false, composite));

        let half = GradientOpacity::new(vec![(0.0, 0.5)]).unwrap();
        let l = list(&f, &scene(Some(&half), None, composite), |_, _| true);
        assert_eq!((l.plan.effects.clone(), l.plan.opacity_scale), (vec!["opacity-scale".to_string()], 0.5));
        assert!(
            !l.plan.gradients()
                && l.gradient_opacity.is_none()
                && !needs_gradients(None, Some(&half), false, composite)
        );

        let ramp = GradientOpacity::new(vec![(0.0, 0.0), (0.1, 1.0)]).unwrap();
        let l = list(&f, &scene(Some(&ramp), None, composite), |_, _| true);
        assert_eq!(l.plan.effects, vec!["gradient-opacity"]);
        assert_eq!(l.plan.passes, vec!["volume"]);
        assert!(l.plan.gradients() && l.plan.gradient_opacity && l.plan.opacity_scale == 1.0);
        assert_eq!(l.gradient_opacity.as_ref(), Some(&ramp));
        assert!(needs_gradients(None, Some(&ramp), false, composite));
        let shaded = Lighting::headlight(Default::default());
        let both = list(&f, &scene(Some(&ramp), Some(&shaded), composite), |_, _| true);
        assert_eq!(both.plan.effects, vec!["gradient-opacity", "shading"]);
        assert_eq!(both.plan.passes, vec!["volume-shaded"]);
        assert_eq!(replan_effects(plain.clone(), Some(&shaded), Some(&ramp)).unwrap(), both);
        assert_eq!(replan_effects(both, None, None).unwrap(), plain);

        let mip = super::super::BlendMode::Mip;
        let l = list(&f, &scene(Some(&ramp), None, mip), |_, _| true);
        assert!(l.plan.effects.is_empty() && !l.plan.gradients() && l.gradient_opacity.is_none());
        assert!(!needs_gradients(Some(&shaded), Some(&ramp), false, mip));
        let none = list(&f, &scene(Some(&ramp), None, composite), |_, _| false);
        assert!(none.plan.effects.is_empty() && !none.plan.gradients());
    }
}
