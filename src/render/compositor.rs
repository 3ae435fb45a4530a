//! The CPU compositor: executes a [`DrawList`] as a GPU slicer would, one
//! pixel ray at a time.
//!
//! The DrawList orders bricks back to front. A brick's texture is the
//! grid at its texel positions, reconstructed trilinearly in texel space
//! (T_p). It is sampled only on its slice planes: for each view depth `z` in
//! [`BrickDraw::slices`] the pixel ray's point at that depth,
//!
//! ```text
//! p = o + d (z - depth(o)) / (d . forward)
//! ```
//!
//! counted when it lies in the brick's world box. Along each axis the box
//! is closed on its near face (the one of smaller view depth; the min face
//! when the view runs along the axis' faces) and open on its far face, and
//! closed on the volume's own faces: a point on a face two bricks share
//! belongs to exactly one of them, and a slice through a face seen head-on
//! belongs to the brick whose near face it is, the one that lists it
//! ([`crate::plan::slab::slice_depths`] keeps depths `d_min <= z < d_max`). Each
//! coordinate of `p(z)` is monotone in `z` (as computed, rounding included),
//! so the slices inside the box are one run: the exact test is made only at
//! its ends, scanning in from the first and last candidate slices. The
//! texture is read at the texel coordinates of `p(z)` along the ray's texel
//! line, from its entry depth `z_a` (per ray and brick; no accumulation):
//!
//! ```text
//! u(z) = u_a + (z - z_a) u_b,   u_a = ((p(z_a) - origin) / spacing - lo) / stride,
//!                               u_b = d / (spacing stride (d . forward))
//! ```
//!
//! (the same line as `((p(z) - origin) / spacing - lo) / stride`, up to
//! rounding: a few ulps of the brick's texel coordinates). Each
//! sample is classified (through `crate::transfer::lut`, within 1e-6 of the transfer
//! function), corrected for the brick's slice spacing `d` against
//! `d0 = DrawList::reference_spacing` and blended. The DrawList's order is
//! back to front (`over`); the compositor walks the same sequence reversed,
//! front to back (`under`), which gives the same picture:
//!
//! ```text
//! a' = 1 - (1 - a)^(d / d0),   C = C + (1 - A) a' c,   A = A + (1 - A) a'
//! ```
//!
//! and stops a pixel once `A >= `[`OPAQUE`] (early ray termination): everything
//! behind would add at most `1 - A <= 1 - OPAQUE` to each channel.
//!
//! Shading ([`DrawList::lighting`], the plan's `volume-shaded`): each sample
//! of opacity `a > 0` has its colour `c` shaded
//! ([`crate::transfer::lighting`]) at the normal of the brick's gradient,
//! central differences one texel away on its bordered texture
//! (`super::shade`), the ray direction as `V`. The headlight takes the
//! gradient as it is (`Headlit`: `N . V` and `R . V = 2 (N . V)^2 - 1` from
//! one dot product, no normal made), each brick its step `1 / (2 h)` once.
//!
//! Gradient opacity ([`DrawList::gradient_opacity`], the plan's effect
//! `gradient-opacity`): the opacity `a` of each sample with `a > 0` is
//! multiplied by `a_grad(|g|)` of the same gradient
//! ([`crate::transfer::gradient_opacity`]), before the slice-spacing
//! correction; a constant one ([`crate::plan::Plan::opacity_scale`]) multiplies
//! it without a gradient. The gradient is taken once per sample for both
//! effects, and without either none is taken (the executor counts them).
//!
//! 2D transfer function ([`DrawList::transfer_2d`], the plan's effect
//! `transfer-2d`): each sample's colour and opacity come from its value and
//! gradient magnitude (`super::transfer2d`) instead of the 1D function; the
//! gradient is taken for every sample and shared with the shading.
//!
//! Isosurface ([`crate::plan::blend`], the plan's `volume-isosurface`): a
//! sample at `u(z)` shows the isovalue `c` crossed since the sample before
//! it, `u(z - d)` (on the bordered texture, so the step back may leave the
//! brick by a texel), as `(c(c), a(c))`, not corrected for `d`; else nothing.
//!
//! Opaque surface ([`DrawList::opaque_triangles`]): the first hit gives the
//! pixel's depth and its shaded colour goes under the volume in front of it,
//! last; samples at or behind that depth are dropped (a depth test).
//! Translucent batches ([`crate::plan::slab`]): the hits of slab `s`'s triangles,
//! within the batch's clip range `near <= depth < far`, are blended after
//! slices `0 .. s` and before slice `s` (slab `n` after the last), back to
//! front; walked in reverse like the slices.
//! Points of the hybrid representation (bucketed by
//! [`crate::plan::point_slabs`], drawn by [`crate::points::footprint`]): each
//! point of slab `s` of a brick is splatted onto the pixels of its footprint
//! before the frame, and blended in that slab like a batch hit (after slices
//! `0 .. s`, before slice `s`), nearest last within the slab; a pixel whose
//! ray misses the brick's box blends the brick's points it still sees.
//! Two dependent fields ([`crate::plan::Plan::dependent`], see
//! [`crate::render::dependent`]): each sample's colour is the transfer
//! function's at the colour texture, its opacity the function's at the
//! opacity texture, both at the same texel coordinates; the gradient
//! (shading, gradient opacity) is the colour texture's. An RGBA volume
//! ([`crate::plan::Plan::rgba`], [`crate::render::rgba`]): the colour is
//! the red texture (the gradient's) and the green and blue textures read
//! as VTK reads them, the opacity the function's at the alpha texture's
//! `v'`; the shaded colour is clamped to `[0, 1]`.
//! Cropping and clipping planes ([`DrawList::region`], the plan's
//! `effects`): a sample whose point `p(z)` the region does not keep
//! ([`crate::plan::crop::KeptRegion::keeps`]) is empty, skipped like a
//! transparent one, in every blend mode; surfaces and points are drawn whole.
//! Blend modes besides Composite (the list's [`crate::plan::Plan::blend`])
//! reduce the same samples instead of blending them: `projection`; Slice
//! samples the plane's point only: `slice`.
//! Jittering ([`crate::plan::Plan::jitter`], effect `jittering`): each
//! brick of spacing `d` samples the pixel's ray at the depths
//! `z = k d + (o mod d)` inside its box instead of its slices, `o` the
//! pixel's offset ([`crate::plan::jitter`]); the same box rule, the same
//! per-sample work: `jitter`.
//! Bands of rows run in parallel; every pixel is computed on its own, so the picture
//! does not depend on the number of threads.

use super::blend::{correct_opacity, under, Rgba};
use super::check::{check_colour, check_list, check_size};
use super::fields::{clamp_rgb, classify_other, OtherFields};
use super::geometry::{at_depth, ray_box, screen_rect};
use super::image::Image;
use super::scattering::{ScatterFrame, ShadowVolume};
use super::shade::normal;
use super::texture::gradient::{Steps, TexelPoint};
use super::texture::{upload, Texel, Texels, Texture, Textures};
use super::triangles::{Hit, TriangleGrid};
use crate::base::error::Result;
use crate::data::grid::{Grid, GridShape};
use crate::geometry::camera::Ray;
use crate::geometry::vec3::{add, dot, scale, sub};
use crate::plan::crop::KeptRegion;
use crate::plan::{BrickDraw, DrawList};
use crate::points::footprint::{footprint, project, Footprint};
use crate::points::{PointSet, PointShade};
use crate::surface::Surface;
use crate::transfer::lighting::{Headlit, Lighting};
use crate::transfer::lut::Lut;
use crate::transfer::{GradientOpacity, TransferFunction, TransferFunction2D};
use rayon::prelude::*;

mod jitter;
mod projection;
mod slice;

/// Early ray termination: a pixel whose accumulated opacity reaches this
/// stops. Whatever lies behind would add at most `(1 - A) <= 1 - OPAQUE`
/// (= 1/1024, a quarter of an 8-bit level) to each of its channels.
pub const OPAQUE: f64 = 1.0 - 1.0 / 1024.0;

/// A brick ready to draw.
struct Prepared<'a, S> {
    /// Position in the DrawList.
    index: usize,
    draw: &'a BrickDraw,
    texture: &'a Texture<S>,
    /// The other fields' textures of dependent components (`None`: one field).
    other: Option<OtherFields<&'a Texture<S>>>,
    /// Per axis, whether the min and max faces are in the box.
    closed: [(bool, bool); 3],
    /// `d / d0`.
    ratio: f64,
    /// The world length of one texel step (the gradient's differences).
    steps: Steps,
    /// Pixels `[x0, x1) x [y0, y1)` that may see the brick.
    rect: [usize; 4],
}

impl<S> Prepared<'_, S> {
    /// In the box: inside, or on a closed face.
    #[inline]
    fn contains(&self, p: [f64; 3]) -> bool {
        let (lo, hi) = (self.draw.world_lo, self.draw.world_hi);
        (0..3).all(|a| {
            (p[a] > lo[a] || (self.closed[a].0 && p[a] == lo[a]))
                && (p[a] < hi[a] || (self.closed[a].1 && p[a] == hi[a]))
        })
    }

    /// The run `s0..s1` of the brick's slices (back to front, decreasing)
    /// that pixel ray `pr` samples between the depths `za`, `zb` where it
    /// enters and leaves the box: the candidates `z < limit`,
    /// `za - tol <= z <= zb + tol`, whose point `p(z)` is in the box (a
    /// contiguous run: `p(z)` is monotone per axis).
    fn sampled_run(&self, pr: &PixelRay, za: f64, zb: f64) -> (usize, usize) {
        let tol = 1e-9 * (1.0 + za.abs().max(zb.abs()));
        let slices = &self.draw.slices;
        let c0 = slices.partition_point(|&z| z > zb + tol).max(slices.partition_point(|&z| z >= pr.limit));
        let c1 = slices.partition_point(|&z| z >= za - tol).max(c0);
        let inside = |j: usize| self.contains(at_depth(&pr.ray, pr.z_origin, pr.cos, slices[j]));
        let mut s0 = c0;
        while s0 < c1 && !inside(s0) {
            s0 += 1;
        }
        let mut s1 = c1;
        while s1 > s0 && !inside(s1 - 1) {
            s1 -= 1;
        }
        (s0, s1)
    }
}

/// Which (brick position, batch index) pairs draw each surface polygon.
struct Batches {
    start: Vec<u32>,
    entries: Vec<(u32, u32)>,
}

/// Composites `list` over `grid` with `tf` into a `width x height` picture
/// (see the module documentation): [`upload`]s the bricks' textures, then
/// [`composite_textures`]. `surface` (with its `[r, g, b, opacity]`) is
/// required when the list draws surface triangles.
pub fn composite(
    grid: &Grid<'_>,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
) -> Result<Image> {
    check_size(width, height)?;
    check_list(list, grid.shape(), surface.map(|s| s.0))?;
    let shadow = super::scattering::shadow_for(grid, list)?;
    composite_shadowed(&upload(grid, list)?, shadow.as_ref(), list, tf, width, height, surface, None)
}

/// Composites `list` from its uploaded `textures` (see [`composite`]).
pub fn composite_textures(
    textures: &Textures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
) -> Result<Image> {
    composite_with_points(textures, list, tf, width, height, surface, None)
}

/// [`composite_textures`] with the points of the hybrid representation that
/// `list` buckets ([`crate::plan::point_slabs::add_points`]), each adding its shade
/// ([`crate::points::shade()`], one per point of the set), drawn with `footprint`.
///
/// # Errors
///
/// As [`composite_textures`], and [`crate::Error::InvalidArgument`] when the
/// list draws points but none are given, or names a point the set does not have.
pub fn composite_with_points(
    textures: &Textures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
    points: Option<DrawnPoints<'_>>,
) -> Result<Image> {
    composite_shadowed(textures, None, list, tf, width, height, surface, points)
}

/// [`composite_with_points`] of a list that may scatter light, its shadow
/// rays reading `shadow` ([`super::scattering::shadow_for`] of the grid).
///
/// # Errors
///
/// As [`composite_with_points`], and [`crate::Error::InvalidArgument`] when
/// the list scatters without a shadow volume or with one of another grid.
#[allow(clippy::too_many_arguments)]
pub fn composite_shadowed(
    textures: &Textures,
    shadow: Option<&ShadowVolume>,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
    points: Option<DrawnPoints<'_>>,
) -> Result<Image> {
    check_size(width, height)?;
    check_list(list, &textures.shape, surface.map(|s| s.0))?;
    check_points(list, points.map(|p| (p.0, p.1)))?;
    textures.check(list)?;
    super::scattering::check_shadow(list, shadow)?;
    Ok(execute_counted(textures, None, shadow, list, tf, width, height, surface, points)?.0)
}

/// The per-sample work a picture did: what the tests count to show that
/// an effect the plan leaves out does none of its work.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    /// Gradients taken (shading, gradient opacity, 2D transfer function).
    pub gradients: usize,
    /// Bricks a pixel's ray crossed with jittered samples (jittering).
    pub jittered: usize,
    /// Samples whose colour was read from an RGBA volume's colour fields.
    pub direct_colours: usize,
}

/// [`composite_with_points`] on checked inputs (`shadow`: what the
/// scattering's shadow rays read, [`super::scattering`]), and the work it did.
#[allow(clippy::too_many_arguments)]
pub(crate) fn execute_counted(
    textures: &Textures,
    other: Option<OtherFields<&Textures>>,
    shadow: Option<&ShadowVolume>,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
    points: Option<DrawnPoints<'_>>,
) -> Result<(Image, Counts)> {
    // The other fields' textures stored as the main one's.
    macro_rules! run {
        ($t:expr, $variant:path) => {{
            let other = other
                .map(|o| {
                    o.try_map(|x| match &x.texels {
                        $variant(v) => Ok(v.as_slice()),
                        _ => Err(crate::Error::InvalidArgument(
                            "the fields' textures are stored in different types: upload them together with \
                             render::dependent or render::rgba"
                                .into(),
                        )),
                    })
                })
                .transpose()?;
            execute($t, other, shadow, &textures.shape, list, tf, width, height, surface, points)
        }};
    }
    match &textures.texels {
        Texels::F32(t) => run!(t, Texels::F32),
        Texels::F64(t) => run!(t, Texels::F64),
        Texels::U8(t) => run!(t, Texels::U8),
        Texels::U16(t) => run!(t, Texels::U16),
        Texels::F16(t) => run!(t, Texels::F16),
    }
}

/// [`composite_textures`], and how many gradients it took (0 unless the list shades).
#[cfg(test)]
pub(crate) fn composite_counting_gradients(
    textures: &Textures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
) -> Result<(Image, usize)> {
    composite_counting(textures, list, tf, width, height).map(|(i, c)| (i, c.gradients))
}

/// [`composite_textures`], and the work it did ([`Counts`]).
#[cfg(test)]
pub(crate) fn composite_counting(
    textures: &Textures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
) -> Result<(Image, Counts)> {
    check_size(width, height)?;
    check_list(list, &textures.shape, None)?;
    textures.check(list)?;
    execute_counted(textures, None, None, list, tf, width, height, None, None)
}

/// The points a DrawList draws: the set, each point's shade (one per point
/// of the set) and the footprint.
pub type DrawnPoints<'a> = (&'a PointSet, &'a [PointShade], Footprint);

/// Every point the list draws exists in `points`, and each has a shade.
fn check_points(list: &DrawList, points: Option<(&PointSet, &[PointShade])>) -> Result<()> {
    if let Some((set, shades)) = points {
        if shades.len() != set.points.len() {
            return Err(crate::Error::InvalidArgument(format!(
                "{} point shades for {} points: shade the point set the list was made with",
                shades.len(),
                set.points.len()
            )));
        }
    }
    let points = points.map(|p| p.0);
    let count = points.map_or(0, |p| p.points.len());
    let named = list.bricks.iter().flat_map(|b| b.points.iter()).flat_map(|k| k.points.iter()).copied().max();
    match named {
        Some(i) if i as usize >= count => Err(crate::Error::InvalidArgument(format!(
            "the DrawList draws point {i} but {} given: pass the point set the list was made with",
            if points.is_some() { format!("only {count} points are") } else { "no points are".to_string() }
        ))),
        _ => Ok(()),
    }
}

/// [`composite_with_points`] on checked inputs, textures stored as `S`.
#[allow(clippy::too_many_arguments)]
fn execute<S: Texel>(
    textures: &[Texture<S>],
    other: Option<OtherFields<&[Texture<S>]>>,
    shadow: Option<&ShadowVolume>,
    shape: &GridShape,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    surface: Option<(&Surface, [f32; 4])>,
    points: Option<DrawnPoints<'_>>,
) -> Result<(Image, Counts)> {
    let shape = *shape;
    let d0 = list.reference_spacing;
    let volume_lo = shape.world([0.0; 3]);
    let volume_hi = shape.world(shape.dims.map(|d| (d - 1) as f64));
    let forward = list.camera.forward();
    let bricks: Vec<Prepared<S>> = list
        .bricks
        .iter()
        .enumerate()
        .filter_map(|(index, draw)| {
            let rect = screen_rect(&list.camera, width, height, draw.world_lo, draw.world_hi)?;
            // Near face closed, far face open, the volume's faces closed; along a face: min closed.
            let closed = [0, 1, 2].map(|a| {
                let (lo_near, hi_near) = (forward[a] >= 0.0, forward[a] < 0.0);
                (lo_near || draw.world_lo[a] <= volume_lo[a], hi_near || draw.world_hi[a] >= volume_hi[a])
            });
            let ratio = draw.slice_spacing / d0;
            let other = other.map(|o| o.map(|t| &t[index]));
            let texture = &textures[index];
            let steps = Steps::new(scale(shape.spacing, texture.stride()));
            Some(Prepared { index, draw, texture, other, closed, ratio, steps, rect })
        })
        .collect();
    let (mut opaque, mut translucent) = (None, None);
    if let Some((s, colour)) = surface {
        check_colour(colour)?;
        opaque = TriangleGrid::new(s, &shape, list.opaque_triangles.iter().copied()).map(|g| (s, g, colour));
        let table = batches(list, s);
        let ids = (0..s.polygon_count() as u32).filter(|&t| table.start[t as usize] < table.start[t as usize + 1]);
        translucent = TriangleGrid::new(s, &shape, ids).map(|g| (s, g, colour, table));
    }
    let lut = Lut::new(tf);
    let splats = points.map(|(set, shades, kind)| splat(list, &shape, set, shades, kind, width, height));
    let lighting = list.lighting.as_ref().filter(|_| list.plan.shading);
    let region = list.region.as_ref().filter(|_| !list.plan.effects.is_empty());
    let isosurfaces = Some(&list.plan.blend).filter(|b| b.mode == crate::plan::BlendMode::Isosurface);
    let gradient_opacity = list.gradient_opacity.as_ref().filter(|_| list.plan.gradient_opacity);
    let transfer_2d = list.transfer_2d.as_ref().filter(|_| list.plan.transfer_2d);
    let opacity_scale = list.plan.opacity_scale;
    let jitter = list.plan.jitter.then(|| crate::plan::jitter::period(list));
    let scattering = super::scattering::frame(list, &shape, shadow)?;
    let plain = !crate::plan::jitter::other_effects(&list.plan)
        && scattering.is_none()
        && other.is_none()
        && transfer_2d.is_none()
        && lighting.is_none()
        && region.is_none()
        && isosurfaces.is_none()
        && gradient_opacity.is_none()
        && opacity_scale == 1.0;
    let executor = Executor {
        list,
        splats: splats.as_ref(),
        lut,
        width,
        height,
        shape,
        bricks: &bricks,
        lighting,
        headlit: lighting.and_then(Lighting::headlit),
        region,
        isosurfaces,
        gradient_opacity,
        transfer_2d,
        scattering,
        plain,
        opacity_scale,
        jitter,
        opaque: opaque.as_ref().map(|(s, g, c)| (*s, g, *c)),
        translucent: translucent.as_ref().map(|(s, g, c, b)| (*s, g, *c, b)),
    };
    Ok(executor.run())
}

/// The batches drawing each polygon, as a table by polygon id: entries by
/// (brick position, batch index), in O(polygons + batch triangles).
fn batches(list: &DrawList, surface: &Surface) -> Batches {
    let mut start = vec![0u32; surface.polygon_count() + 1];
    let all = || list.bricks.iter().enumerate().flat_map(|(b, d)| d.batches.iter().enumerate().map(move |k| (b, k)));
    for (_, (_, batch)) in all() {
        for t in batch.triangles.clone() {
            start[t as usize + 1] += 1;
        }
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut at = start.clone();
    let mut entries = vec![(0u32, 0u32); start[start.len() - 1] as usize];
    for (b, (k, batch)) in all() {
        for t in batch.triangles.clone() {
            entries[at[t as usize] as usize] = (b as u32, k as u32);
            at[t as usize] += 1;
        }
    }
    Batches { start, entries }
}

/// One point's share of a pixel: `(brick position, slab, depth, straight colour, opacity)`.
type Splat = (u32, u32, f64, [f64; 3], f64);

/// The points' footprints, by pixel: pixel `p`'s entries are
/// `entries[start[p] .. start[p + 1]]`.
struct Splats {
    start: Vec<u32>,
    entries: Vec<Splat>,
}

/// Splats every point `list` draws (see the module documentation and
/// [`crate::plan::point_slabs`]), in list order, so the table does not depend on threads.
fn splat(
    list: &DrawList,
    shape: &GridShape,
    set: &PointSet,
    shades: &[PointShade],
    kind: Footprint,
    width: usize,
    height: usize,
) -> Splats {
    let d0 = list.reference_spacing;
    let mut hits: Vec<(u32, Splat)> = Vec::new();
    for (b, draw) in list.bricks.iter().enumerate() {
        for bucket in &draw.points {
            for &i in &bucket.points {
                let p = &set.points[i as usize];
                let shade = shades[i as usize];
                let a_p = f64::from(shade.alpha);
                if a_p <= 0.0 {
                    continue;
                }
                let [r, g, bl] = shade.rgb.map(f64::from);
                let world = shape.world(p.ijk.map(f64::from));
                let Some((centre, s)) = project(&list.camera, width, height, world, d0) else { continue };
                let depth = list.camera.depth(world);
                footprint(kind, centre, s, width, height, |x, y, w| {
                    hits.push(((x + y * width) as u32, (b as u32, bucket.slab as u32, depth, [r, g, bl], a_p * w)));
                });
            }
        }
    }
    let mut start = vec![0u32; width * height + 1];
    for h in &hits {
        start[h.0 as usize + 1] += 1;
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut at = start.clone();
    let mut entries = vec![(0, 0, 0.0, [0.0; 3], 0.0); hits.len()];
    for (pixel, e) in hits {
        entries[at[pixel as usize] as usize] = e;
        at[pixel as usize] += 1;
    }
    Splats { start, entries }
}

struct Executor<'a, S> {
    list: &'a DrawList,
    splats: Option<&'a Splats>,
    /// The transfer function, tabulated.
    lut: Lut<'a>,
    width: usize,
    height: usize,
    shape: GridShape,
    bricks: &'a [Prepared<'a, S>],
    /// The shading, lights in world space (`None`: unshaded).
    lighting: Option<&'a Lighting>,
    /// The lighting's headlight prepared (`None`: unshaded, or directional lights).
    headlit: Option<Headlit>,
    /// The samples kept (`None`: all).
    region: Option<&'a KeptRegion>,
    /// The Isosurface blend mode's values (`None` for Composite).
    isosurfaces: Option<&'a crate::plan::Blend>,
    /// The gradient opacity (`None`: none, or a constant in `opacity_scale`).
    gradient_opacity: Option<&'a GradientOpacity>,
    /// The 2D transfer function (`None`: the 1D function classifies).
    transfer_2d: Option<&'a TransferFunction2D>,
    /// Volumetric scattering and the volume its shadow rays read (`None`: none).
    scattering: Option<(ScatterFrame<'a>, &'a ShadowVolume)>,
    /// True when the plan runs no effect and composites: a sample is the
    /// transfer function's colour and opacity alone.
    plain: bool,
    /// Every opacity's constant factor (1: none).
    opacity_scale: f64,
    /// The jitter period `P` when the plan jitters (`None`: samples on the
    /// slice lattice; see [`crate::plan::jitter`]).
    jitter: Option<f64>,
    opaque: Option<(&'a Surface, &'a TriangleGrid, [f32; 4])>,
    translucent: Option<(&'a Surface, &'a TriangleGrid, [f32; 4], &'a Batches)>,
}

/// Rows drawn together.
const BAND: usize = 8;

/// Per-thread scratch: the band's bricks, the pixel's hits, a brick's batch hits.
#[derive(Default)]
struct Scratch {
    row: Vec<usize>,
    hits: Vec<Hit>,
    /// `(slab, depth, straight colour, opacity)` of one brick's batch hits.
    events: Vec<(usize, f64, [f64; 3], f64)>,
    /// The work done ([`Counts`]).
    counts: Counts,
}

impl<S: Texel> Executor<'_, S> {
    /// The picture, bands of [`BAND`] rows in parallel, each column of a
    /// band in turn (neighbouring rays read the same texels), and the
    /// work done.
    fn run(self) -> (Image, Counts) {
        let (w, h) = (self.width, self.height);
        let bands: Vec<(Vec<[f32; 4]>, Counts)> = (0..h.div_ceil(BAND))
            .into_par_iter()
            .map_init(Scratch::default, |scratch, band| {
                let (y0, y1) = (band * BAND, ((band + 1) * BAND).min(h));
                scratch.row.clear();
                scratch.row.extend((0..self.bricks.len()).filter(|&b| {
                    let rect = self.bricks[b].rect;
                    rect[2] < y1 && y0 < rect[3]
                }));
                let mut out = vec![[0.0; 4]; (y1 - y0) * w];
                scratch.counts = Counts::default();
                for x in 0..w {
                    for y in y0..y1 {
                        out[(y - y0) * w + x] = self.pixel(x, y, scratch);
                    }
                }
                (out, scratch.counts)
            })
            .collect();
        let counts = Counts {
            gradients: bands.iter().map(|b| b.1.gradients).sum(),
            jittered: bands.iter().map(|b| b.1.jittered).sum(),
            direct_colours: bands.iter().map(|b| b.1.direct_colours).sum(),
        };
        let rgba = bands.into_iter().flat_map(|b| b.0).collect();
        (Image { width: w, height: h, rgba }, counts)
    }
}

/// A pixel's ray: `cos = direction . forward`, `z_origin = depth(origin)`,
/// and the depth of the opaque surface (infinite without one).
struct PixelRay {
    /// Pixel index `x + y width`.
    pixel: usize,
    ray: Ray,
    cos: f64,
    z_origin: f64,
    limit: f64,
}

impl PixelRay {
    /// View depth of the ray's point at parameter `t`.
    #[inline]
    fn depth(&self, t: f64) -> f64 {
        self.z_origin + t * self.cos
    }
}

impl<S: Texel> Executor<'_, S> {
    fn pixel(&self, x: usize, y: usize, scratch: &mut Scratch) -> [f32; 4] {
        let camera = &self.list.camera;
        let ray = camera.ray(x, y, self.width, self.height);
        let mut pr = PixelRay {
            pixel: x + y * self.width,
            ray,
            cos: dot(ray.direction, camera.forward()),
            z_origin: camera.depth(ray.origin),
            limit: f64::INFINITY,
        };
        let mut surface_hit = None;
        if let Some((surface, tris, colour)) = self.opaque {
            if let Some(h) = tris.first_hit(&ray, f64::INFINITY) {
                pr.limit = pr.depth(h.t);
                surface_hit = Some((tris.shade(surface, &h, ray.direction, colour), colour[3] as f64));
            }
        }
        if self.list.plan.blend.mode == crate::plan::BlendMode::Slice {
            return self.slice_pixel(x, y, &pr, scratch, surface_hit);
        }
        if !self.list.plan.blend.mode.composites() {
            return self.project(x, y, &pr, scratch, surface_hit);
        }
        scratch.hits.clear();
        if let Some((_, tris, _, _)) = self.translucent {
            tris.all_hits(&ray, f64::INFINITY, &mut scratch.hits);
        }
        // Front to back: the band's bricks in reverse list order, until opaque.
        let mut acc: Rgba = [0.0; 4];
        for i in (0..scratch.row.len()).rev() {
            let b = scratch.row[i];
            let rect = self.bricks[b].rect;
            if (rect[0]..rect[1]).contains(&x) && (rect[2]..rect[3]).contains(&y) {
                acc = match (self.jitter, self.plain) {
                    (None, true) => self.brick::<true>(b, &pr, acc, scratch),
                    (None, false) => self.brick::<false>(b, &pr, acc, scratch),
                    (Some(p), true) => self.brick_jittered::<true>(b, &pr, x, y, p, acc, scratch),
                    (Some(p), false) => self.brick_jittered::<false>(b, &pr, x, y, p, acc, scratch),
                };
                if acc[3] >= OPAQUE {
                    break;
                }
            }
        }
        if let Some((rgb, a)) = surface_hit {
            acc = under(acc, rgb, a);
        }
        acc.map(|v| v as f32)
    }

    /// Blends brick `b`'s slices (and its batches' hits) under `acc`, front
    /// to back, stopping once `acc` is [`OPAQUE`]. `PLAIN` ([`Executor::plain`]):
    /// each sample is the transfer function's colour and corrected opacity
    /// alone, a loop of its own without the effects' branches.
    fn brick<const PLAIN: bool>(&self, b: usize, pr: &PixelRay, mut acc: Rgba, scratch: &mut Scratch) -> Rgba {
        let brick = &self.bricks[b];
        self.batch_events(b, pr, scratch);
        let Some((ta, tb)) = ray_box(&pr.ray, brick.draw.world_lo, brick.draw.world_hi) else {
            // Footprints reach past the box's silhouette: its points still show.
            for &(_, _, c, a) in scratch.events.iter().rev() {
                acc = under(acc, c, a);
            }
            return acc;
        };
        let (za, zb) = (pr.depth(ta), pr.depth(tb));
        let slices = &brick.draw.slices;
        let (s0, s1) = brick.sampled_run(pr, za, zb);
        // All slices when batches interleave.
        let (j0, j1) = if scratch.events.is_empty() { (s0, s1) } else { (0, slices.len()) };
        // The texel line u(z) = ua + (z - za) ub (see the module documentation).
        let (ua, ub) = self.texel_line(brick, pr, za);
        // Events are by slab, back to front: taken from the end, front to back.
        let mut e = scratch.events.len();
        for j in (j0..j1).rev() {
            // Slab j goes before slice j (back to front): slabs above j are in front of it.
            while let Some(&(_, _, c, a)) = e.checked_sub(1).and_then(|k| scratch.events.get(k)).filter(|ev| ev.0 > j) {
                acc = under(acc, c, a);
                e -= 1;
            }
            if (s0..s1).contains(&j) {
                acc = self.sample_at_depth::<PLAIN>(brick, pr, slices[j], za, (ua, ub), acc, scratch);
                if acc[3] >= OPAQUE {
                    return acc;
                }
            }
        }
        for &(_, _, c, a) in scratch.events[..e].iter().rev() {
            acc = under(acc, c, a);
        }
        acc
    }

    /// `acc` with the sample of `pr` at depth `z` in brick `brick` under
    /// it, `(ua, ub)` the ray's texel line `u(z) = ua + (z - za) ub` (see
    /// the module documentation); `PLAIN` as in [`Self::brick`].
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample_at_depth<const PLAIN: bool>(
        &self,
        brick: &Prepared<'_, S>,
        pr: &PixelRay,
        z: f64,
        za: f64,
        (ua, ub): ([f64; 3], [f64; 3]),
        mut acc: Rgba,
        scratch: &mut Scratch,
    ) -> Rgba {
        let dz = z - za;
        if PLAIN {
            let [r, gr, bl, a] = self.lut.eval(brick.texture.at_texel(add(ua, scale(ub, dz))));
            if a > 0.0 {
                acc = under(acc, [r, gr, bl], correct_opacity(a, brick.ratio));
            }
            return acc;
        }
        if !self.keeps(pr, z) {
            return acc;
        }
        let p = brick.texture.point(add(ua, scale(ub, dz)));
        let v = brick.texture.value_at(&p);
        match self.isosurfaces {
            None => acc = self.sample(brick, &p, v, brick.ratio, (pr, z), acc, scratch),
            Some(blend) => {
                // The values crossed since the sample one step nearer the eye, uncorrected.
                let d = brick.draw.slice_spacing;
                let before = brick.texture.at_texel(sub(p.u, scale(ub, d)));
                for c in blend.crossings(before, v) {
                    acc = self.sample(brick, &p, c, 1.0, (pr, z), acc, scratch);
                }
            }
        }
        acc
    }

    /// True when the sample of `pr` at depth `z` is kept (always without a region).
    #[inline]
    fn keeps(&self, pr: &PixelRay, z: f64) -> bool {
        self.region.is_none_or(|r| r.keeps(at_depth(&pr.ray, pr.z_origin, pr.cos, z)))
    }

    /// `acc` with the sample at texel point `p` of value `value` (the
    /// texel's, or an isovalue crossed) under it: transfer function, the
    /// plan's effects ([`Self::effects`]), opacity corrected by
    /// `ratio = d / d0` (1 for an isovalue); the sample is the ray's point at depth `at.1`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample(
        &self,
        brick: &Prepared<'_, S>,
        p: &TexelPoint,
        value: f64,
        ratio: f64,
        at: (&PixelRay, f64),
        acc: Rgba,
        scratch: &mut Scratch,
    ) -> Rgba {
        let (grad, [r, gr, bl, mut a]) = match self.transfer_2d {
            None => (None, self.lut.eval(value)),
            Some(t) => {
                let g = self.gradient(brick, p, scratch);
                (Some(g), super::transfer2d::classify(t, value, g))
            }
        };
        let [mut r, mut gr, mut bl] = [r, gr, bl];
        if let Some(other) = brick.other {
            scratch.counts.direct_colours += usize::from(matches!(other, OtherFields::Rgba(..)));
            // Dependent components (`super::fields`): the opacity field's opacity, or the RGB colour.
            ([r, gr, bl], a) = classify_other(other, value, [r, gr, bl], |v| self.lut.eval(v)[3], |t| t.at_texel(p.u));
        }
        if a <= 0.0 {
            return acc;
        }
        let pr = at.0;
        let (rgb, a) = match &self.scattering {
            None => self.effects(brick, p, grad, [r, gr, bl], a, pr.ray.direction, scratch),
            Some((frame, shadow)) => {
                let g = grad.unwrap_or_else(|| self.gradient(brick, p, scratch));
                let x = at_depth(&pr.ray, pr.z_origin, pr.cos, at.1);
                let rgb = frame.colour(x, [r, gr, bl], a, g, pr.ray.direction, |t| {
                    super::scattering::opacity(&self.lut, shadow.value_at_index(frame.index(t)))
                });
                // The opacity after the colour: VTK blends with the transfer function's.
                let scale = self.gradient_opacity.map_or(1.0, |f| f64::from(f.eval(dot(g, g).sqrt())));
                (rgb, a * self.opacity_scale * scale)
            }
        };
        if a > 0.0 {
            under(acc, clamp_rgb(brick.other.as_ref(), rgb), correct_opacity(a, ratio))
        } else {
            acc
        }
    }

    /// Colour `c` and opacity `a` of the sample at texel point `p` of
    /// `brick`'s texture (its gradient border included) after the plan's effects:
    /// the opacity scaled, or times the gradient opacity, the colour shaded
    /// along `view` (module documentation); one gradient for both, `grad`
    /// when already taken.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn effects(
        &self,
        brick: &Prepared<'_, S>,
        p: &TexelPoint,
        grad: Option<[f64; 3]>,
        c: [f64; 3],
        a: f64,
        view: [f64; 3],
        scratch: &mut Scratch,
    ) -> ([f64; 3], f64) {
        let mut a = a * self.opacity_scale;
        if self.lighting.is_none() && self.gradient_opacity.is_none() {
            return (c, a);
        }
        let g = match grad {
            Some(g) => g,
            None => self.gradient(brick, p, scratch),
        };
        if let Some(f) = self.gradient_opacity {
            a *= f64::from(f.eval(dot(g, g).sqrt()));
        }
        match (self.lighting, &self.headlit) {
            (Some(_), Some(headlit)) if a > 0.0 => (headlit.shade(c, g, view), a),
            (Some(lighting), None) if a > 0.0 => (lighting.shade(c, normal(g), view), a),
            _ => (c, a),
        }
    }

    /// The gradient at texel point `p` of `brick`'s texture
    /// (`super::shade`'s rule, one texel away), counted.
    #[inline]
    fn gradient(&self, brick: &Prepared<'_, S>, p: &TexelPoint, scratch: &mut Scratch) -> [f64; 3] {
        scratch.counts.gradients += 1;
        brick.texture.gradient_at(p, &brick.steps)
    }

    /// The pixel's hits of brick `b`'s batch triangles in front of the
    /// opaque depth and inside their batch's clip range, and its points'
    /// footprints in front of that depth, by slab, back to front.
    fn batch_events(&self, b: usize, pr: &PixelRay, scratch: &mut Scratch) {
        scratch.events.clear();
        let index = self.bricks[b].index as u32;
        if let Some(splats) = self.splats {
            let at = &splats.entries[splats.start[pr.pixel] as usize..splats.start[pr.pixel + 1] as usize];
            for &(_, slab, z, c, a) in at.iter().filter(|e| e.0 == index) {
                if z < pr.limit {
                    scratch.events.push((slab as usize, z, c, a));
                }
            }
        }
        self.surface_events(b, pr, scratch);
        scratch.events.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.total_cmp(&a.1)));
    }

    /// Brick `b`'s batch hits (see [`Self::batch_events`]), unsorted.
    fn surface_events(&self, b: usize, pr: &PixelRay, scratch: &mut Scratch) {
        let Some((surface, tris, colour, table)) = self.translucent else { return };
        let draw = self.bricks[b].draw;
        if draw.batches.is_empty() {
            return;
        }
        let index = self.bricks[b].index as u32;
        for h in &scratch.hits {
            let z = pr.depth(h.t);
            if z >= pr.limit {
                continue;
            }
            let p = h.polygon as usize;
            // The polygon's entries of this brick (entries by brick, then batch).
            let entries = &table.entries[table.start[p] as usize..table.start[p + 1] as usize];
            let first = entries.partition_point(|e| e.0 < index);
            for &(_, k) in entries[first..].iter().take_while(|e| e.0 == index) {
                let batch = &draw.batches[k as usize];
                if batch.clip.is_some_and(|(near, far)| !(near <= z && z < far)) {
                    continue;
                }
                let rgb = tris.shade(surface, h, pr.ray.direction, colour);
                scratch.events.push((batch.slab, z, rgb, colour[3] as f64));
            }
        }
    }
}
