//! What a DrawList asks of the CPU compositor, term by term: the inputs of
//! the cost model ([`super::CostModel`]).
//!
//! For each brick `b` of the list, its box's 8 corners projected on a
//! `W x H` image give its screen rectangle `R_b` (pixels, clamped to the
//! image; the whole image when a corner lies at or behind the eye), and
//!
//! ```text
//! samples(b) = min(|slices(b)| |R_b|,  V_b rho(z_b) / d_b |R_b| / |R_b unclamped|)
//! rho(z)     = (H / (2 z tan(theta / 2)))^2     perspective (theta: the view angle)
//!            = (H / (2 scale))^2                parallel
//! ```
//!
//! `V_b` its world volume, `d_b` its slice spacing, `z_b` the view depth of
//! its centre: the slice planes cut the box into `V_b / d_b` of area per
//! unit depth, each holding `rho` pixel rays per unit area. The compositor
//! tests every ray of `R_b` against the box (`brick_pixels = sum |R_b|`),
//! samples it on the slices inside (`samples = sum samples(b)`), and takes
//! a gradient for each sample when the plan does (`gradient_samples`), a
//! shadow ray when it scatters (`scattering_samples`). Early ray
//! termination and transparent samples make the real work smaller; the fit
//! absorbs that into the coefficients.

use crate::geometry::camera::{Camera, Projection};
use crate::plan::{BlendMode, DrawList};

/// The number of terms, the constant included.
pub const TERMS: usize = 10;

/// The terms' names, in the order of [`CostTerms::as_array`].
pub const TERM_NAMES: [&str; TERMS] = [
    "frame",
    "pixels",
    "bricks",
    "brick_pixels",
    "samples",
    "gradient_samples",
    "scattering_samples",
    "triangles",
    "points",
    "upload_bytes",
];

/// The work of one frame (see the module documentation). Every count is
/// non-negative and finite.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct CostTerms {
    /// Pixels of the image, `W H` (a ray set up per pixel).
    pub pixels: f64,
    /// Bricks drawn.
    pub bricks: f64,
    /// Sum over bricks of the pixels of their screen rectangles.
    pub brick_pixels: f64,
    /// Samples on the bricks' slices, estimated.
    pub samples: f64,
    /// Samples that take a gradient (shading, gradient opacity, 2D transfer function).
    pub gradient_samples: f64,
    /// Samples that march a shadow ray (volumetric scattering).
    pub scattering_samples: f64,
    /// Surface triangles drawn (opaque, and translucent batches' triangles).
    pub triangles: f64,
    /// Points of the hybrid representation drawn.
    pub points: f64,
    /// Texture bytes uploaded for the frame.
    pub upload_bytes: f64,
}

impl CostTerms {
    /// The terms of `list` drawn on a `width x height` image, uploading
    /// `upload_bytes` of textures first.
    pub fn of(list: &DrawList, width: usize, height: usize, upload_bytes: usize) -> CostTerms {
        let slice_mode = list.plan.blend.mode == BlendMode::Slice;
        let mut t = CostTerms {
            pixels: (width * height) as f64,
            bricks: list.bricks.len() as f64,
            upload_bytes: upload_bytes as f64,
            ..CostTerms::default()
        };
        for b in &list.bricks {
            let Some((clamped, full)) = rect_areas(&list.camera, width, height, b.world_lo, b.world_hi) else {
                continue;
            };
            t.brick_pixels += clamped;
            if slice_mode {
                t.samples += clamped;
                continue;
            }
            let bound = b.slices.len() as f64 * clamped;
            let volume: f64 = (0..3).map(|a| (b.world_hi[a] - b.world_lo[a]).max(0.0)).product();
            let centre = [0, 1, 2].map(|a| 0.5 * (b.world_lo[a] + b.world_hi[a]));
            let estimate = match density(&list.camera, height, list.camera.depth(centre)) {
                Some(rho) if b.slice_spacing > 0.0 && full > 0.0 => volume * rho / b.slice_spacing * (clamped / full),
                _ => bound,
            };
            t.samples += if estimate.is_finite() { estimate.min(bound) } else { bound };
        }
        t.triangles = list.opaque_triangles.len() as f64
            + list
                .bricks
                .iter()
                .flat_map(|b| &b.batches)
                .map(|batch| f64::from(batch.triangles.end.saturating_sub(batch.triangles.start)))
                .sum::<f64>();
        t.points = list.bricks.iter().flat_map(|b| &b.points).map(|p| p.points.len() as f64).sum();
        if list.plan.gradients() {
            t.gradient_samples = t.samples;
        }
        if list.plan.scattering {
            t.scattering_samples = t.samples;
        }
        t
    }

    /// The terms as one row, the constant first (the order of [`TERM_NAMES`]).
    pub fn as_array(&self) -> [f64; TERMS] {
        [
            1.0,
            self.pixels,
            self.bricks,
            self.brick_pixels,
            self.samples,
            self.gradient_samples,
            self.scattering_samples,
            self.triangles,
            self.points,
            self.upload_bytes,
        ]
    }

    /// Whether every term is finite and non-negative.
    pub fn is_valid(&self) -> bool {
        self.as_array().iter().all(|v| v.is_finite() && *v >= 0.0)
    }
}

/// Pixel rays per unit area of a plane at view depth `z` (`None` at or behind the eye).
fn density(camera: &Camera, height: usize, z: f64) -> Option<f64> {
    let h = height as f64;
    match camera.projection {
        Projection::Parallel { scale } => Some((h / (2.0 * scale)).powi(2)),
        Projection::Perspective { view_angle_deg } => {
            let t = (view_angle_deg.to_radians() / 2.0).tan();
            (z > 0.0).then(|| (h / (2.0 * z * t)).powi(2))
        }
    }
}

/// `(clamped, unclamped)` pixel areas of the screen rectangle of the box
/// `[lo, hi]`; the whole image for both when a corner lies at or behind
/// the eye; `None` when the rectangle misses the image.
fn rect_areas(camera: &Camera, width: usize, height: usize, lo: [f64; 3], hi: [f64; 3]) -> Option<(f64, f64)> {
    let (w, h) = (width as f64, height as f64);
    let whole = Some((w * h, w * h));
    let Some([x0, x1, y0, y1]) = camera.box_on_screen(width, height, lo, hi) else {
        return whole;
    };
    if !(x0.is_finite() && x1.is_finite() && y0.is_finite() && y1.is_finite()) {
        return whole;
    }
    let full = (x1 - x0).max(1.0) * (y1 - y0).max(1.0);
    let clamped = (x1.min(w) - x0.max(0.0)).max(0.0) * (y1.min(h) - y0.max(0.0)).max(0.0);
    (clamped > 0.0).then_some((clamped, full))
}
