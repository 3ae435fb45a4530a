//! Volumetric scattering in the renderers (the plan's effect
//! `volume-scattering`, [`crate::transfer::scattering`] for VTK's model):
//! each sample's colour blended with its scattered light, the
//! transmittance towards each light taken along a shadow ray.
//!
//! What the shadow rays read: the CPU compositor and the brick shader read
//! the [`ShadowVolume`], the whole volume resampled to at most
//! [`SHADOW_VOLUME_MAX_DIM`] points per axis (a brick sees only itself, and
//! a shadow ray crosses the volume; the GL mapper uploads the same `f32`
//! values as one 3D texture, read with linear filtering). Its point `j` on an
//! axis of `N` grid points and `n` shadow points is the grid's trilinear
//! value at index `x = j (N - 1) / (n - 1)`; a grid of at most
//! `SHADOW_VOLUME_MAX_DIM` points per axis is copied whole. The reference ray
//! caster reads the full grid.
//!
//! Cost bound: a shadow ray takes at most [`MAX_SHADOW_STEPS`] samples. When
//! VTK's steps `s0` up to `min(exit, R)` would be more, it takes that many
//! equal steps `s` instead, each sample's opacity corrected for its length
//! `1 - (1 - a)^(s / s0)` (the same transmittance for a constant field).
//! A 64-point volume needs at most `sqrt 3 * 64 < 111` steps: VTK's own.
//!
//! ```text
//! T = prod_k (1 - a_k),  a_k = 1 - (1 - a(v(q + k s n)))^(s / s0),  q = p + s0 n
//! ```
//!
//! The last step is not shortened (VTK's loop runs while `k s < min(exit, R)`).

use super::blend::correct_opacity;
use super::sample::trilinear;
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridShape, GridVisitor, Sample, TypedGrid};
use crate::geometry::vec3::{dot, normalize, sub};
use crate::plan::DrawList;
use crate::transfer::lighting::{Lighting, Lights};
use crate::transfer::Scattering;
use rayon::prelude::*;

/// The most points per axis of the [`ShadowVolume`] (64^3 `f32`: 1 MiB).
pub const SHADOW_VOLUME_MAX_DIM: usize = 64;

/// The most samples a shadow ray takes (module documentation).
pub const MAX_SHADOW_STEPS: usize = 128;

/// VTK's `EPSILON`: a shadow ray shorter than this is no ray, and a
/// direction component below it is taken as this for the box test.
const EPSILON: f64 = 0.001;

/// The whole volume at a resolution the shadow rays read (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowVolume {
    /// Points per axis.
    pub dims: [usize; 3],
    /// Values, x fastest.
    pub values: Vec<f32>,
    /// The grid's points per axis.
    grid_dims: [usize; 3],
}

impl ShadowVolume {
    /// Resamples `grid` (module documentation).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a grid without points.
    pub fn new(grid: &Grid<'_>) -> Result<ShadowVolume> {
        let grid_dims = grid.shape().dims;
        if grid_dims.contains(&0) {
            return Err(Error::InvalidArgument("shadow volume: the grid has no points".into()));
        }
        let dims = shadow_dims(grid_dims);
        let values = grid.visit(Resample(dims));
        Ok(ShadowVolume { dims, values, grid_dims })
    }

    /// Bytes of its values (what the GL mapper's texture holds).
    pub fn bytes(&self) -> usize {
        self.values.len() * 4
    }

    /// The trilinear value at grid index point `x` (clamped to the volume).
    #[inline]
    pub fn value_at_index(&self, x: [f64; 3]) -> f64 {
        let u = [0, 1, 2].map(|a| x[a] * lattice_ratio(self.dims[a], self.grid_dims[a]));
        let (n, v) = (self.dims, &self.values);
        trilinear(n, u, |i, j, k| f64::from(v[i + n[0] * (j + n[1] * k)]))
    }
}

/// Shadow-volume lattice units per grid index unit: `(n - 1) / (N - 1)` (0 for one point).
fn lattice_ratio(n: usize, grid_n: usize) -> f64 {
    if grid_n > 1 {
        (n - 1) as f64 / (grid_n - 1) as f64
    } else {
        0.0
    }
}

/// The shadow volume's points of a typed grid.
struct Resample([usize; 3]);

impl GridVisitor for Resample {
    type Output = Vec<f32>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f32> {
        let n = self.0;
        let back = [0, 1, 2].map(|a| if n[a] > 1 { (g.dims[a] - 1) as f64 / (n[a] - 1) as f64 } else { 0.0 });
        (0..n[2])
            .into_par_iter()
            .flat_map_iter(|k| {
                let g = &g;
                (0..n[1]).flat_map(move |j| {
                    (0..n[0]).map(move |i| {
                        let x = [i as f64 * back[0], j as f64 * back[1], k as f64 * back[2]];
                        super::sample::grid_value(g, x) as f32
                    })
                })
            })
            .collect()
    }
}

/// VTK's texture space of a grid: the unit cube over its texels,
/// `t = (x + 1/2) / N` for index `x`, sizes `N_a spacing_a` (module documentation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TextureSpace {
    /// World position of `t = 0`.
    corner: [f64; 3],
    /// World size of the cube per axis.
    size: [f64; 3],
    dims: [usize; 3],
}

impl TextureSpace {
    pub(crate) fn new(shape: &GridShape) -> TextureSpace {
        let size = [0, 1, 2].map(|a| shape.dims[a] as f64 * shape.spacing[a]);
        let corner = [0, 1, 2].map(|a| shape.origin[a] - 0.5 * shape.spacing[a]);
        TextureSpace { corner, size, dims: shape.dims }
    }

    #[inline]
    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| (p[a] - self.corner[a]) / self.size[a])
    }

    #[inline]
    fn vector(&self, v: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| v[a] / self.size[a])
    }

    /// Grid index coordinates of texture point `t`: `t N - 1/2`.
    #[inline]
    pub(crate) fn index(&self, t: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| t[a] * self.dims[a] as f64 - 0.5)
    }
}

/// One frame's scattering: the parameters, the lights in world space, the
/// eye, the texture space and VTK's sample distance `d`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScatterFrame<'a> {
    scattering: &'a Scattering,
    lighting: &'a Lighting,
    eye: [f64; 3],
    space: TextureSpace,
    /// VTK's sample distance `d` (world units).
    distance: f64,
    /// `d / d0`: a transfer-function opacity (per `d0`) becomes VTK's (per `d`).
    to_vtk: f64,
    /// The reach extent `R`, texture units.
    extent: f64,
}

impl<'a> ScatterFrame<'a> {
    /// `lighting`'s lights must be in world space ([`Lighting::in_world`]);
    /// `d0` the reference spacing the transfer function's opacities are per.
    pub(crate) fn new(
        scattering: &'a Scattering,
        lighting: &'a Lighting,
        eye: [f64; 3],
        shape: &GridShape,
        d0: f64,
    ) -> ScatterFrame<'a> {
        let space = TextureSpace::new(shape);
        let distance = sample_distance(scattering, d0);
        let extent = reach_extent(scattering, shape, distance);
        ScatterFrame { scattering, lighting, eye, space, distance, to_vtk: distance / d0, extent }
    }

    /// The colour of the sample at world point `p` (module documentation of
    /// [`crate::transfer::scattering`]): straight colour `c`, opacity `a`
    /// (before gradient opacity), world gradient `grad`, seen along the unit
    /// ray direction `view`; `opacity(t)` is the opacity of the field at
    /// texture point `t` (what the shadow rays read). Clamped to `[0, 1]`.
    #[inline]
    pub(crate) fn colour(
        &self,
        p: [f64; 3],
        c: [f64; 3],
        a: f64,
        grad: [f64; 3],
        view: [f64; 3],
        opacity: impl Fn([f64; 3]) -> f64,
    ) -> [f64; 3] {
        let s = self.scattering;
        let shaded = self.lighting.shade_unclamped(c, super::shade::normal(grad), view);
        let k = s.volume_coefficient(s.vtk_gradient_magnitude(grad), correct_opacity(a, self.to_vtk));
        let m = &self.lighting.material;
        let q = self.space.point(p);
        // The view ray's step in texture units (VTK's g_lengthStep).
        let step = len(self.space.vector(view)) * self.distance;
        let mut secondary = [0.0; 3];
        match &self.lighting.lights {
            Lights::Headlight { diffuse, .. } => {
                let t = self.transmittance(q, self.space.point(self.eye), true, step, &opacity);
                let phase = s.phase(-1.0);
                for i in 0..3 {
                    secondary[i] += t * phase * c[i] * m.diffuse * diffuse[i] + m.ambient * s.headlight_ambient[i];
                }
            }
            Lights::Directional(lights) => {
                let to_eye = normalize(self.space.vector(sub(self.eye, p)));
                for l in lights {
                    let towards = self.space.vector(l.direction.map(|v| -v));
                    let phase = s.phase(-dot(normalize(towards), to_eye));
                    let t = self.transmittance(q, towards, false, step, &opacity);
                    for i in 0..3 {
                        secondary[i] += t * phase * c[i] * m.diffuse * l.diffuse[i] + m.ambient * l.ambient[i];
                    }
                }
            }
        }
        [0, 1, 2].map(|i| ((1.0 - k) * shaded[i] + k * secondary[i]).clamp(0.0, 1.0))
    }

    /// VTK's `volumeShadow` from texture point `q` towards `light` (a point
    /// when `positional`, else a direction), view step `step` (module
    /// documentation, [`MAX_SHADOW_STEPS`]).
    fn transmittance(
        &self,
        q: [f64; 3],
        light: [f64; 3],
        positional: bool,
        step: f64,
        opacity: &impl Fn([f64; 3]) -> f64,
    ) -> f64 {
        let towards = |q: [f64; 3]| if positional { sub(light, q) } else { light };
        let n = normalize(towards(q));
        let start = [0, 1, 2].map(|a| q[a] + step * n[a]);
        let Some(exit) = unit_cube_exit(start, n) else { return 1.0 };
        if exit < step {
            return 1.0;
        }
        let length = if positional { len(towards(start)) } else { exit };
        let reach = exit.min(length).min(self.extent);
        if reach.is_nan() || reach < EPSILON {
            return 1.0;
        }
        let needed = (reach / step).ceil();
        let (s, ratio) = if needed > MAX_SHADOW_STEPS as f64 {
            (reach / MAX_SHADOW_STEPS as f64, reach / MAX_SHADOW_STEPS as f64 / step)
        } else {
            (step, 1.0)
        };
        let mut shadow = 1.0;
        let mut k = 0usize;
        while (k as f64) * s < reach && k < MAX_SHADOW_STEPS {
            let d = k as f64 * s;
            let a = opacity([0, 1, 2].map(|i| start[i] + d * n[i]));
            shadow *= 1.0 - correct_opacity(a, ratio * self.to_vtk);
            if shadow <= 0.0 {
                return 0.0;
            }
            k += 1;
        }
        shadow
    }

    /// The grid index of texture point `t`.
    #[inline]
    pub(crate) fn index(&self, t: [f64; 3]) -> [f64; 3] {
        self.space.index(t)
    }
}

fn len(v: [f64; 3]) -> f64 {
    dot(v, v).sqrt()
}

/// VTK's `BBoxIntersect` of the ray from `o` along `d` with the unit cube
/// (each direction component below [`EPSILON`] taken as `sign * EPSILON`):
/// the exit distance when `t1 > max(t0, 0)`.
fn unit_cube_exit(o: [f64; 3], d: [f64; 3]) -> Option<f64> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for a in 0..3 {
        let da = if d[a].abs() < EPSILON { d[a].signum() * EPSILON } else { d[a] };
        let da = if d[a] == 0.0 { 0.0 } else { da };
        let inv = 1.0 / da;
        let (lo, hi) = ((0.0 - o[a]) * inv, (1.0 - o[a]) * inv);
        t0 = t0.max(lo.min(hi));
        t1 = t1.min(lo.max(hi));
    }
    (t1 > t0.max(0.0)).then_some(t1)
}

/// The opacity of value `v` through `lut` for a shadow ray (no data, NaN: 0).
#[inline]
pub(crate) fn opacity(lut: &crate::transfer::lut::Lut<'_>, v: f64) -> f64 {
    if v.is_nan() {
        0.0
    } else {
        lut.eval(v)[3]
    }
}

/// The shadow volume of `grid` when `list` scatters (`None` otherwise: no work).
///
/// # Errors
///
/// As [`ShadowVolume::new`].
pub fn shadow_for(grid: &Grid<'_>, list: &DrawList) -> Result<Option<ShadowVolume>> {
    if list.plan.scattering {
        ShadowVolume::new(grid).map(Some)
    } else {
        Ok(None)
    }
}

/// A scattering list needs its shadow volume, made for its grid.
pub(crate) fn check_shadow(list: &DrawList, shadow: Option<&ShadowVolume>) -> Result<()> {
    match (list.plan.scattering, shadow) {
        (true, None) => Err(Error::InvalidArgument(
            "the DrawList scatters light: composite it with its shadow volume (render::compositor::composite_shadowed)"
                .into(),
        )),
        (_, Some(s)) if s.dims != shadow_dims(s.grid_dims) => {
            Err(Error::InvalidArgument("the shadow volume is not one ShadowVolume::new made".into()))
        }
        _ => Ok(()),
    }
}

/// The frame's scattering, when the list scatters.
pub(crate) fn frame<'a>(
    list: &'a DrawList,
    shape: &GridShape,
    shadow: Option<&'a ShadowVolume>,
) -> Result<Option<(ScatterFrame<'a>, &'a ShadowVolume)>> {
    let Some(planned) = list.scattering.as_ref().filter(|_| list.plan.scattering) else { return Ok(None) };
    check_shadow(list, shadow)?;
    let Some(shadow) = shadow else { return Ok(None) };
    if shadow.grid_dims != shape.dims {
        return Err(Error::InvalidArgument(format!(
            "the shadow volume was made for a grid of {:?} points, the textures are of {:?}: make it from this grid",
            shadow.grid_dims, shape.dims
        )));
    }
    let d0 = list.reference_spacing;
    let frame = ScatterFrame::new(&planned.scattering, &planned.lighting, list.camera.position, shape, d0);
    Ok(Some((frame, shadow)))
}

/// VTK's texture space of `shape` as `(corner, size)`: world position of
/// `t = 0` and the cube's world size per axis (module documentation).
pub fn texture_space(shape: &GridShape) -> ([f64; 3], [f64; 3]) {
    let s = TextureSpace::new(shape);
    (s.corner, s.size)
}

/// The shadow volume's 3D texture coordinate of texture point `t` as
/// `t * scale + shift` per axis, for a grid of `grid_dims` points and a
/// shadow volume of `dims` (a texel centre per point, GL's linear filter):
/// `((t N - 1/2) (n - 1) / (N - 1) + 1/2) / n`.
pub fn shadow_texture_transform(grid_dims: [usize; 3], dims: [usize; 3]) -> ([f64; 3], [f64; 3]) {
    let r = [0, 1, 2].map(|a| lattice_ratio(dims[a], grid_dims[a]));
    let scale = [0, 1, 2].map(|a| grid_dims[a] as f64 * r[a] / dims[a] as f64);
    let shift = [0, 1, 2].map(|a| (0.5 - 0.5 * r[a]) / dims[a] as f64);
    (scale, shift)
}

/// The shadow volume's points per axis for a grid of `grid_dims` points.
pub fn shadow_dims(grid_dims: [usize; 3]) -> [usize; 3] {
    grid_dims.map(|n| n.min(SHADOW_VOLUME_MAX_DIM))
}

/// VTK's sample distance of `scattering` (its own, or `d0` when 0).
pub fn sample_distance(scattering: &Scattering, d0: f64) -> f64 {
    if scattering.sample_distance > 0.0 {
        scattering.sample_distance
    } else {
        d0
    }
}

/// The reach extent `R` (texture units) of `scattering` on a grid of
/// `shape` at VTK's sample distance `distance`.
pub fn reach_extent(scattering: &Scattering, shape: &GridShape, distance: f64) -> f64 {
    let largest = TextureSpace::new(shape).size.iter().copied().fold(0.0, f64::max);
    scattering.shadow_extent(distance / largest)
}
