//! The full-resolution reference ray caster: what the multiresolution
//! frames are measured against.
//!
//! For each pixel the camera ray is clipped to the volume's world box
//! `[t0, t1]`, cut into `n = ceil((t1 - t0) / step)` equal segments of length
//! `l = (t1 - t0) / n <= step` and sampled at their midpoints (trilinear on
//! the full grid), front to back:
//!
//! ```text
//! (c, a) = transfer function(value),  a' = 1 - (1 - a)^(l / d0),  d0 = crate::data::spacing::reference_spacing
//! C += (1 - A) a' c,  A += (1 - A) a'              (premultiplied; stop once A > 0.999)
//! ```
//!
//! A surface (with colour `[r, g, b, opacity]`) is hit in world space; each
//! hit (each triangle once, one hit where triangles share an edge) is
//! composited the same way (`c` the headlight-shaded colour, `a` the
//! opacity, no correction) before the samples behind it. With a lighting
//! ([`ReferenceOptions::lighting`]) each sample of opacity `a > 0` has its
//! colour shaded ([`crate::transfer::lighting`]) at the normal of the full
//! grid's gradient, central differences one sample away (`super::shade`,
//! the compositor's rule at stride 1), the ray direction as `V`. With a
//! gradient opacity ([`ReferenceOptions::gradient_opacity`]) each sample's
//! opacity is multiplied by `a_grad(|g|)` of that gradient
//! ([`crate::transfer::gradient_opacity`]) before the correction:
//! `a' = 1 - (1 - a a_grad)^(l / d0)`. With a 2D transfer function
//! ([`ReferenceOptions::transfer_2d`], Composite only) `(c, a)` is
//! `T(value, |g|)` of that gradient (`super::transfer2d`) instead of the
//! 1D function's, corrected and shaded the same way. An opaque surface
//! (opacity 1) ends the ray at its first hit; opacity 0 hides it. Rows run in parallel; every
//! pixel is computed on its own, so the picture does not depend on the
//! number of threads.
//!
//! Under the Isosurface blend mode a sample shows the isovalues crossed
//! since the sample before it (the entry point for the first), each
//! `(c(c), a(c))` uncorrected, nearest first, and nothing without one ([`crate::plan::blend`]).
//!
//! Blend modes besides Composite and Isosurface ([`reference_blend`]) reduce the same
//! samples, each standing for `l / d0` reference spacings, instead of
//! blending them: `projection`; Slice draws the ray's point on its plane
//! only: `slice`. With a region ([`ReferenceOptions::region`],
//! VTK's cropping and clipping planes) a sample it removes is empty (not
//! blended, not reduced); surfaces are drawn whole.

use super::blend::{correct_opacity, under, Rgba};
use super::check::{check_colour, check_size};
use super::fields::{clamp_rgb, classify_other, OtherFields};
use super::geometry::ray_box;
use super::image::Image;
use super::sample::{grid_value, to_index, trilinear};
use super::shade::{gradient, normal};
use super::triangles::{Hit, TriangleGrid};
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridShape, GridVisitor, Sample, TypedGrid};
use crate::geometry::camera::Camera;
use crate::plan::crop::KeptRegion;
use crate::plan::{Blend, BlendMode};
use crate::surface::Surface;
use crate::transfer::lighting::Lighting;
use crate::transfer::{GradientOpacity, TransferFunction, TransferFunction2D};
use rayon::prelude::*;

mod projection;
mod slice;

/// Accumulated opacity past which a ray stops.
pub const EARLY_TERMINATION: f64 = 0.999;

/// What the reference draws besides the volume, and how finely.
#[derive(Debug, Clone, Copy, Default)]
pub struct ReferenceOptions<'a> {
    /// Sample spacing along the ray, world units (> 0); `None`: `d0 / 4` ([`crate::data::spacing::reference_spacing`]).
    pub step: Option<f64>,
    /// A surface and its `[r, g, b, opacity]`, all in `[0, 1]`.
    pub surface: Option<(&'a Surface, [f32; 4])>,
    /// Shade the volume with this material and these lights (view-space
    /// lights follow the camera).
    pub lighting: Option<&'a Lighting>,
    /// Keep only these samples (cropping, clipping planes; world
    /// coordinates): a removed sample is empty.
    pub region: Option<&'a KeptRegion>,
    /// Multiply each sample's opacity by this function of its gradient magnitude.
    pub gradient_opacity: Option<&'a GradientOpacity>,
    /// Classify each sample by its value and gradient magnitude with this
    /// table instead of the 1D function (Composite only).
    pub transfer_2d: Option<&'a TransferFunction2D>,
    /// The opacity unit distance `d0`, world units (> 0; VTK's
    /// ScalarOpacityUnitDistance); `None`: the grid's reference spacing.
    /// A resampled copy of a volume drawn with the original's `d0` keeps its opacity per length.
    pub opacity_unit: Option<f64>,
    /// Volumetric scattering (Composite, with [`Self::lighting`]; not run
    /// when [`crate::plan::scattering::scatters`] would not): shadow rays
    /// through the full grid ([`super::scattering`]).
    pub scattering: Option<&'a crate::transfer::Scattering>,
}

/// Ray-casts `grid` classified by `tf`, seen by `camera`, into a
/// `width x height` picture (see the module documentation).
pub fn reference(
    grid: &Grid<'_>,
    tf: &TransferFunction,
    camera: &Camera,
    width: usize,
    height: usize,
    options: &ReferenceOptions<'_>,
) -> Result<Image> {
    reference_blend(grid, tf, camera, width, height, options, &Blend::default())
}

/// [`reference()`] under `blend`'s mode: Composite as there; the other modes
/// reduce the same samples (see `projection`).
pub fn reference_blend(
    grid: &Grid<'_>,
    tf: &TransferFunction,
    camera: &Camera,
    width: usize,
    height: usize,
    options: &ReferenceOptions<'_>,
    blend: &Blend,
) -> Result<Image> {
    reference_fields(grid, None, tf, camera, width, height, options, blend)
}

/// [`reference_blend`] with, when `other` is given, each sample's opacity
/// from the opacity function at the opacity field instead of `grid`'s (two
/// dependent fields, see [`crate::render::dependent`]) or its colour and
/// opacity from the RGBA fields, clamped after shading (an RGBA volume,
/// `grid` its red field, [`crate::render::rgba`]); `other` must be fields of the same image.
#[allow(clippy::too_many_arguments)]
pub(crate) fn reference_fields(
    grid: &Grid<'_>,
    other: Option<OtherFields<&Grid<'_>>>,
    tf: &TransferFunction,
    camera: &Camera,
    width: usize,
    height: usize,
    options: &ReferenceOptions<'_>,
    blend: &Blend,
) -> Result<Image> {
    check_size(width, height)?;
    let shape = *grid.shape();
    let d0 = options.opacity_unit.unwrap_or_else(|| crate::data::spacing::reference_spacing(&shape));
    if !(d0 > 0.0 && d0.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "opacity unit distance {d0}: give a positive number of world units"
        )));
    }
    let step = options.step.unwrap_or(d0 / 4.0);
    if !(step > 0.0 && step.is_finite()) {
        return Err(Error::InvalidArgument(format!("reference step {step}: give a positive number of world units")));
    }
    if let Some(l) = options.lighting {
        l.check()?;
    }
    let lighting = options.lighting.map(|l| l.in_world(camera));
    let surface = match options.surface {
        Some((_, colour)) if colour[3] == 0.0 => None, // invisible
        Some((s, colour)) => {
            check_colour(colour)?;
            TriangleGrid::new(s, &shape, 0..s.polygon_count() as u32).map(|g| (s, g, colour))
        }
        None => None,
    };
    let lighting = lighting.as_ref();
    if let Some(s) = options.scattering {
        s.check()?;
    }
    let scatters = blend.mode == BlendMode::Composite
        && options.scattering.is_some_and(|s| s.runs())
        && lighting
            .is_some_and(|l| !matches!(&l.lights, crate::transfer::lighting::Lights::Directional(v) if v.is_empty()));
    let scattering = match (options.scattering, lighting) {
        (Some(s), Some(l)) if scatters => Some(super::scattering::ScatterFrame::new(s, l, camera.position, &shape, d0)),
        _ => None,
    };
    Ok(grid.visit(Caster {
        scattering,
        tf,
        camera,
        width,
        height,
        shape,
        step,
        d0,
        surface: surface.as_ref(),
        lighting,
        gradient_opacity: options.gradient_opacity,
        transfer_2d: options.transfer_2d.filter(|_| blend.mode == BlendMode::Composite),
        blend: *blend,
        region: options.region,
        other,
    }))
}

struct Caster<'a> {
    tf: &'a TransferFunction,
    camera: &'a Camera,
    width: usize,
    height: usize,
    shape: GridShape,
    step: f64,
    d0: f64,
    surface: Option<&'a (&'a Surface, TriangleGrid, [f32; 4])>,
    /// Lights in world space.
    lighting: Option<&'a Lighting>,
    gradient_opacity: Option<&'a GradientOpacity>,
    transfer_2d: Option<&'a TransferFunction2D>,
    blend: Blend,
    region: Option<&'a KeptRegion>,
    /// The other fields of dependent components (`None`: one field).
    other: Option<OtherFields<&'a Grid<'a>>>,
    /// Volumetric scattering (`None`: none).
    scattering: Option<super::scattering::ScatterFrame<'a>>,
}

impl GridVisitor for Caster<'_> {
    type Output = Image;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Image {
        let rows: Vec<Vec<[f32; 4]>> = (0..self.height)
            .into_par_iter()
            .map_init(Vec::new, |hits, y| (0..self.width).map(|x| self.pixel(&g, x, y, hits)).collect())
            .collect();
        Image { width: self.width, height: self.height, rgba: rows.concat() }
    }
}

impl Caster<'_> {
    fn pixel<T: Sample>(&self, g: &TypedGrid<'_, T>, x: usize, y: usize, hits: &mut Vec<Hit>) -> [f32; 4] {
        let ray = self.camera.ray(x, y, self.width, self.height);
        hits.clear();
        if let Some((_, tris, colour)) = self.surface {
            if colour[3] >= 1.0 {
                hits.extend(tris.first_hit(&ray, f64::INFINITY));
            } else {
                tris.all_hits(&ray, f64::INFINITY, hits);
            }
        }
        if self.blend.mode == BlendMode::Slice {
            return self.slice(g, &ray, hits.first());
        }
        if !self.blend.mode.composites() {
            return self.project(g, &ray, hits.first());
        }
        let isosurfaces = Some(&self.blend).filter(|b| b.mode == BlendMode::Isosurface);
        let mut acc: Rgba = [0.0; 4];
        let mut next_hit = 0;
        // Composites the surface hits up to `t`; true when an opaque one ends the ray.
        let mut surface_until = |acc: &mut Rgba, t: f64| -> bool {
            let Some((surface, tris, colour)) = self.surface else { return false };
            while let Some(h) = hits.get(next_hit).filter(|h| h.t <= t) {
                *acc = under(*acc, tris.shade(surface, h, ray.direction, *colour), colour[3] as f64);
                next_hit += 1;
                if colour[3] >= 1.0 {
                    return true;
                }
            }
            false
        };
        let (lo, hi) = (self.shape.world([0.0; 3]), self.shape.world(self.shape.dims.map(|d| (d - 1) as f64)));
        if let Some((t0, t1)) = ray_box(&ray, lo, hi) {
            let n = ((t1 - t0) / self.step).ceil().max(1.0) as usize;
            let l = (t1 - t0) / n as f64;
            let at = |t: f64| to_index(&self.shape, [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]));
            let mut before = grid_value(g, at(t0));
            for i in 0..n {
                let t = t0 + (i as f64 + 0.5) * l;
                if surface_until(&mut acc, t) {
                    return acc.map(|v| v as f32);
                }
                let p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.direction[a]);
                let u = to_index(&self.shape, p);
                let v = grid_value(g, u);
                if self.region.is_some_and(|r| !r.keeps(p)) {
                    // Empty; still the value one step nearer for Isosurface's next sample.
                    before = v;
                    continue;
                }
                let sample = |acc: Rgba, value: f64, ratio: f64| {
                    let (grad, [r, gr, b, mut a]) = match self.transfer_2d {
                        None => (None, self.tf.eval(value).map(f64::from)),
                        Some(t) => {
                            let grad = gradient(|v| grid_value(g, v), u, self.shape.spacing);
                            (Some(grad), super::transfer2d::classify(t, value, grad))
                        }
                    };
                    let [mut r, mut gr, mut b] = [r, gr, b];
                    if let Some(other) = self.other {
                        // Dependent components (`super::fields`): the opacity field's opacity, or the RGB colour.
                        ([r, gr, b], a) = classify_other(
                            other,
                            value,
                            [r, gr, b],
                            |v| f64::from(self.tf.opacity(v)),
                            |f| trilinear(self.shape.dims, u, |i, j, k| f.value(i, j, k)),
                        );
                    }
                    let (rgb, a) = match &self.scattering {
                        Some(frame) if a > 0.0 => self.scattered(g, frame, p, u, grad, [r, gr, b], a, ray.direction),
                        _ => self.effects(g, u, grad, [r, gr, b], a, ray.direction),
                    };
                    if a > 0.0 {
                        under(acc, clamp_rgb(self.other.as_ref(), rgb), correct_opacity(a, ratio))
                    } else {
                        acc
                    }
                };
                match isosurfaces {
                    None => acc = sample(acc, v, l / self.d0),
                    Some(blend) => {
                        for c in blend.crossings(before, v) {
                            acc = sample(acc, c, 1.0);
                        }
                    }
                }
                before = v;
                if acc[3] > EARLY_TERMINATION {
                    return acc.map(|v| v as f32);
                }
            }
        }
        surface_until(&mut acc, f64::INFINITY);
        acc.map(|v| v as f32)
    }
}

impl Caster<'_> {
    /// Colour and opacity of the sample at world point `p` (index point `u`)
    /// under volumetric scattering: the colour of [`super::scattering`] with
    /// shadow rays through the full grid, the opacity times the gradient opacity.
    #[allow(clippy::too_many_arguments)]
    fn scattered<T: Sample>(
        &self,
        g: &TypedGrid<'_, T>,
        frame: &super::scattering::ScatterFrame<'_>,
        p: [f64; 3],
        u: [f64; 3],
        grad: Option<[f64; 3]>,
        c: [f64; 3],
        a: f64,
        view: [f64; 3],
    ) -> ([f64; 3], f64) {
        let grad = grad.unwrap_or_else(|| gradient(|v| grid_value(g, v), u, self.shape.spacing));
        let rgb = frame.colour(p, c, a, grad, view, |t| {
            let v = grid_value(g, frame.index(t));
            if v.is_nan() {
                0.0
            } else {
                f64::from(self.tf.opacity(v))
            }
        });
        let scale =
            self.gradient_opacity.map_or(1.0, |f| f64::from(f.eval(crate::geometry::vec3::dot(grad, grad).sqrt())));
        (rgb, a * scale)
    }

    /// Colour `c` and opacity `a` of the sample at index point `u` after the
    /// gradient opacity and the shading (module documentation); `grad` the
    /// gradient when already taken.
    #[inline]
    fn effects<T: Sample>(
        &self,
        g: &TypedGrid<'_, T>,
        u: [f64; 3],
        grad: Option<[f64; 3]>,
        c: [f64; 3],
        a: f64,
        view: [f64; 3],
    ) -> ([f64; 3], f64) {
        if a <= 0.0 || (self.lighting.is_none() && self.gradient_opacity.is_none()) {
            return (c, a);
        }
        let grad = grad.unwrap_or_else(|| gradient(|v| grid_value(g, v), u, self.shape.spacing));
        let a = match self.gradient_opacity {
            Some(f) => a * f64::from(f.eval(crate::geometry::vec3::dot(grad, grad).sqrt())),
            None => a,
        };
        match self.lighting {
            Some(lighting) if a > 0.0 => (lighting.shade(c, normal(grad), view), a),
            _ => (c, a),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::Samples;
    use crate::geometry::camera::Projection;
    use crate::render::triangles::tests::surface_of;

    /// A constant field seen along z through a slab of known thickness:
    /// the closed form `1 - (1 - a)^(L / d0)`, whatever the step.
    #[test]
    fn constant_field_matches_the_closed_form() {
        let data = vec![0.5f32; 5 * 5 * 9];
        let shape = GridShape { dims: [5, 5, 9], spacing: [1.0, 1.0, 0.5], origin: [0.0; 3] };
        let grid = Grid::new(Samples::F32(&data), shape, 1, None).unwrap();
        let tf = TransferFunction::new(vec![(0.0, [1.0, 0.5, 0.25])], vec![(0.0, 0.1)]).unwrap();
        let camera =
            Camera::new([2.0, 2.0, 10.0], [2.0, 2.0, 0.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 1.0 })
                .unwrap();
        let exact = 1.0 - 0.9f64.powf(4.0 / 0.5); // L = 4, d0 = 0.5
        for step in [None, Some(0.3), Some(0.05)] {
            let img = reference(
                &grid,
                &tf,
                &camera,
                4,
                4,
                &ReferenceOptions {
                    step,
                    surface: None,
                    lighting: None,
                    gradient_opacity: None,
                    transfer_2d: None,
                    region: None,
                    opacity_unit: None,
                    scattering: None,
                },
            )
            .unwrap();
            for p in &img.rgba {
                assert!((p[3] as f64 - exact).abs() < 1e-6, "{step:?}: {} vs {exact}", p[3]);
                assert!((p[1] as f64 - 0.5 * exact).abs() < 1e-6);
            }
        }
        let bad = ReferenceOptions {
            step: Some(0.0),
            surface: None,
            lighting: None,
            gradient_opacity: None,
            transfer_2d: None,
            region: None,
            opacity_unit: None,
            scattering: None,
        };
        assert!(reference(&grid, &tf, &camera, 4, 4, &bad).unwrap_err().to_string().contains("positive"));
        assert!(reference(&grid, &tf, &camera, 0, 4, &ReferenceOptions::default()).is_err());
    }

    /// An opaque plane half way stops the rays there; a translucent one is
    /// composited between the two halves of the volume.
    #[test]
    fn surfaces_stop_or_tint_the_rays() {
        let data = vec![0.5f32; 5 * 5 * 5];
        let grid = Grid::scalar(Samples::F32(&data), [5, 5, 5]).unwrap();
        let tf = TransferFunction::new(vec![(0.0, [1.0, 1.0, 1.0])], vec![(0.0, 0.1)]).unwrap();
        let camera =
            Camera::new([2.0, 2.0, 10.0], [2.0, 2.0, 0.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 1.0 })
                .unwrap();
        let plane = surface_of(&[
            [[-1.0, -1.0, 2.0], [6.0, -1.0, 2.0], [6.0, 6.0, 2.0]],
            [[-1.0, -1.0, 2.0], [6.0, 6.0, 2.0], [-1.0, 6.0, 2.0]],
        ]);
        let front = 1.0 - 0.9f64.powi(2); // the volume in front of the plane: 2 units
        for opacity in [1.0f32, 0.5] {
            let options = ReferenceOptions {
                step: None,
                surface: Some((&plane, [0.0, 0.0, 1.0, opacity])),
                lighting: None,
                gradient_opacity: None,
                transfer_2d: None,
                region: None,
                opacity_unit: None,
                scattering: None,
            };
            let img = reference(&grid, &tf, &camera, 3, 3, &options).unwrap();
            let p = img.rgba[4].map(|v| v as f64);
            let a = opacity as f64;
            let expected_a = front + (1.0 - front) * a + (1.0 - front) * (1.0 - a) * front;
            assert!((p[3] - expected_a).abs() < 1e-6, "opacity {opacity}: {p:?}");
            assert!((p[2] - (front + (1.0 - front) * a + (1.0 - front) * (1.0 - a) * front)).abs() < 1e-6);
            assert!((p[0] - (front + (1.0 - front) * (1.0 - a) * front)).abs() < 1e-6);
        }
    }
}
