//! Screen-space importance: how a node's texels project for the camera.
//!
//! A cell of the grid (the largest spacing `s_max`, world units) seen at
//! view depth `z` covers, on an image `H` pixels high,
//!
//! ```text
//! perspective:  ppc(z) = s_max H / (2 z tan(theta / 2))    (theta: the vertical view angle)
//! parallel:     ppc    = s_max H / (2 scale)               (scale: half the view height)
//! ```
//!
//! pixels along a side. A node is measured at the nearest point of its box
//! (`z_near`, the smallest depth of its corners), where its texels look
//! largest. Its texels at stride `S` then cover `S ppc(z_near)` pixels, and
//!
//! ```text
//! S_min(n)  = smallest power of two S >= 1 with S ppc(z_near) >= m     (m: the smallest texel, pixels)
//! W_s(n)    = min(W_max, (ppc(z_near) / ppc(z_f))^2)                   (z_f: the focal point's depth)
//! ```
//!
//! `S_min` stops refinement where a texel would be smaller than `m` pixels.
//! Coarse texels are samples of the data, not averages, so a finer texel
//! can still change a pixel (a one-voxel vessel a stride of 2 skips): the
//! CLI and the mapper default to `m = 0`, no stop. `W_s` weighs the error
//! mass of a node (a sum of squared errors over its samples) by the pixel
//! area a sample covers, relative to a sample at the focal point: 1
//! everywhere under a parallel projection. A node entirely outside the view
//! frustum (or behind the camera) covers no pixel: `W_s = 0`.

use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::geometry::camera::{Camera, Projection};
use crate::geometry::vec3::{dot, sub};

/// Largest screen weight: nodes much nearer than the focal point count as
/// this many focal-plane samples (it keeps one node next to the camera from
/// taking the whole budget).
const MAX_WEIGHT: f64 = 16.0;

/// The screen-space importance of nodes for one camera and image size (see
/// the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenSpace {
    shape: GridShape,
    position: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    /// Perspective: `tan(theta / 2)`; parallel: `None`.
    tan_half: Option<f64>,
    /// Parallel: half the view height, world units.
    scale: f64,
    /// Width over height.
    aspect: f64,
    /// `s_max H / 2`: a cell's pixels are this over `z tan(theta/2)` or over `scale`.
    half_height_cells: f64,
    /// `ppc(z_f)`.
    focal_ppc: f64,
    /// `m`: the smallest texel worth refining to, pixels.
    min_texel_pixels: f64,
}

impl ScreenSpace {
    /// The screen space of `camera` on a `width x height` image over a grid
    /// of `shape`; refinement stops below texels of `min_texel_pixels`
    /// pixels (0 never stops, the default of the CLI and the mapper).
    pub fn new(
        camera: &Camera,
        width: usize,
        height: usize,
        shape: &GridShape,
        min_texel_pixels: f64,
    ) -> Result<ScreenSpace> {
        if width == 0 || height == 0 {
            return Err(Error::InvalidArgument(format!(
                "screen-space selection: image size {width}x{height} has no pixel; give a size of at least 1x1"
            )));
        }
        if !(min_texel_pixels >= 0.0 && min_texel_pixels.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "smallest texel {min_texel_pixels} pixels: give a finite number >= 0 (1: stop below a pixel)"
            )));
        }
        let (right, up, forward) = camera.basis();
        let s_max = shape.spacing.iter().copied().fold(0.0, f64::max);
        let mut space = ScreenSpace {
            shape: *shape,
            position: camera.position,
            right,
            up,
            forward,
            tan_half: None,
            scale: 1.0,
            aspect: width as f64 / height as f64,
            half_height_cells: s_max * height as f64 / 2.0,
            focal_ppc: 1.0,
            min_texel_pixels,
        };
        match camera.projection {
            Projection::Perspective { view_angle_deg } => {
                space.tan_half = Some((view_angle_deg.to_radians() / 2.0).tan())
            }
            Projection::Parallel { scale } => space.scale = scale,
        }
        let focal_depth = dot(sub(camera.focal_point, camera.position), forward);
        space.focal_ppc = space.ppc(focal_depth);
        if !(space.focal_ppc > 0.0 && space.focal_ppc.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "screen-space selection: a cell of {s_max} world units covers {} pixels at the focal point; \
                 give a camera and spacing of finite, positive size",
                space.focal_ppc
            )));
        }
        Ok(space)
    }

    /// Pixels a cell covers along a side at view depth `z` (`ppc(z)`).
    fn ppc(&self, z: f64) -> f64 {
        match self.tan_half {
            Some(t) => self.half_height_cells / (z * t),
            None => self.half_height_cells / self.scale,
        }
    }

    /// The nearest view depth of the index box `[lo, hi]` and whether the
    /// box may be in view (some part inside the frustum).
    fn nearest(&self, lo: [usize; 3], hi: [usize; 3]) -> (f64, bool) {
        let mut z_near = f64::INFINITY;
        // Per frustum side (right, left, top, bottom, in front): every corner outside it.
        let mut outside = [true; 5];
        for corner in 0..8 {
            let p = [0, 1, 2].map(|a| if corner >> a & 1 == 1 { hi[a] as f64 } else { lo[a] as f64 });
            let d = sub(self.shape.world(p), self.position);
            let (x, y, z) = (dot(d, self.right), dot(d, self.up), dot(d, self.forward));
            z_near = z_near.min(z);
            // Half the view's height and width at this depth.
            let half = match self.tan_half {
                Some(t) => z * t,
                None => self.scale,
            };
            let half_w = half * self.aspect;
            outside[0] &= x > half_w;
            outside[1] &= x < -half_w;
            outside[2] &= y > half;
            outside[3] &= y < -half;
            outside[4] &= self.tan_half.is_some() && z <= 0.0;
        }
        (z_near, !outside.iter().any(|&o| o))
    }

    /// `ppc(z_near)` of the box, infinite when the box reaches the camera
    /// (perspective: `z_near <= 0`).
    fn box_ppc(&self, z_near: f64) -> f64 {
        match self.tan_half {
            Some(_) if z_near <= 0.0 => f64::INFINITY,
            _ => self.ppc(z_near),
        }
    }

    /// `W_s(n)` of the index box `[lo, hi]` (module documentation).
    pub fn weight(&self, lo: [usize; 3], hi: [usize; 3]) -> f64 {
        let (z_near, in_view) = self.nearest(lo, hi);
        if !in_view {
            return 0.0;
        }
        let r = self.box_ppc(z_near) / self.focal_ppc;
        (r * r).min(MAX_WEIGHT)
    }

    /// Whether refinement stops anywhere ([`ScreenSpace::finest_stride`]
    /// above 1 for some box): only with a smallest texel above 0 pixels.
    pub fn caps(&self) -> bool {
        self.min_texel_pixels > 0.0
    }

    /// `S_min(n)` of the index box `[lo, hi]`: the finest stride whose
    /// texels still cover `m` pixels (module documentation).
    pub fn finest_stride(&self, lo: [usize; 3], hi: [usize; 3]) -> usize {
        let (z_near, _) = self.nearest(lo, hi);
        let ppc = self.box_ppc(z_near);
        // Also a NaN or infinite ppc (a box reaching the camera): full resolution.
        if ppc.partial_cmp(&self.min_texel_pixels) != Some(std::cmp::Ordering::Less) {
            return 1;
        }
        let ratio = self.min_texel_pixels / ppc;
        // Strides beyond 2^62 mean "the coarsest": a node is never coarser than its box.
        let log2 = ratio.log2().ceil().clamp(0.0, 62.0) as u32;
        1usize << log2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(n: usize, spacing: f64) -> GridShape {
        GridShape { dims: [n; 3], spacing: [spacing; 3], origin: [0.0; 3] }
    }

    /// Under a parallel projection every node in view weighs 1, and the
    /// finest stride follows the pixels a cell covers: 512 pixels over a
    /// view 2 * 300 units high with cells of 2 units is 1.7 pixels a cell.
    #[test]
    fn parallel_projection_weighs_alike_and_caps_by_pixels() {
        let s = shape(257, 2.0);
        let camera = Camera::around([0.0; 3], [512.0; 3], 30.0, 20.0, true).unwrap();
        let Projection::Parallel { scale } = camera.projection else { unreachable!() };
        let space = ScreenSpace::new(&camera, 512, 512, &s, 1.0).unwrap();
        let ppc = 2.0 * 512.0 / (2.0 * scale);
        assert!((space.focal_ppc - ppc).abs() < 1e-9);
        assert_eq!(space.weight([0; 3], [8; 3]), 1.0);
        assert_eq!(space.weight([128; 3], [256; 3]), 1.0);
        assert_eq!(space.finest_stride([0; 3], [8; 3]), if ppc >= 1.0 { 1 } else { 2 });
        // Four times fewer pixels: texels of stride 4 are the first to cover a pixel.
        let small = ScreenSpace::new(&camera, 128, 128, &s, 1.0).unwrap();
        let ppc_small = ppc / 4.0;
        let expect = (1.0 / ppc_small).log2().ceil().exp2() as usize;
        assert_eq!(small.finest_stride([0; 3], [8; 3]), expect);
        assert!(expect >= 2);
        // m = 0 never stops.
        assert_eq!(ScreenSpace::new(&camera, 16, 16, &s, 0.0).unwrap().finest_stride([0; 3], [8; 3]), 1);
    }

    /// In perspective the near corner weighs more than the far one, and a
    /// node behind the camera or beside the frustum weighs 0.
    #[test]
    fn perspective_weighs_near_nodes_more_and_culls_the_rest() {
        let s = shape(65, 1.0);
        let camera = Camera::new(
            [32.0, -100.0, 32.0],
            [32.0, 32.0, 32.0],
            [0.0, 0.0, 1.0],
            Projection::Perspective { view_angle_deg: 30.0 },
        )
        .unwrap();
        let space = ScreenSpace::new(&camera, 256, 256, &s, 1.0).unwrap();
        let near = space.weight([24, 0, 24], [40, 8, 40]);
        let focal = space.weight([24, 32, 24], [40, 40, 40]);
        let far = space.weight([24, 56, 24], [40, 64, 40]);
        assert!(near > focal && focal > far && far > 0.0, "{near} {focal} {far}");
        // The focal node's nearest face is at depth 132 against the focal point's 132.
        assert!((focal - 1.0).abs() < 1e-9, "{focal}");
        let expect = (132.0f64 / 100.0).powi(2);
        assert!((near - expect).abs() < 1e-9, "{near} vs {expect}");
        // Beside the frustum: the view is 2 * 132 * tan(15 deg) = 70.7 units wide at the focal point.
        let wide = shape(1025, 1.0);
        let space = ScreenSpace::new(&camera, 256, 256, &wide, 1.0).unwrap();
        assert_eq!(space.weight([512, 0, 0], [520, 8, 8]), 0.0);
        // Behind the camera.
        let behind = Camera::new([32.0, 200.0, 32.0], [32.0, 300.0, 32.0], [0.0, 0.0, 1.0], camera.projection).unwrap();
        let space = ScreenSpace::new(&behind, 256, 256, &s, 1.0).unwrap();
        assert_eq!(space.weight([0; 3], [64; 3]), 0.0);
    }

    /// A box around the camera is in view, refined to full resolution, and
    /// weighs the most.
    #[test]
    fn a_box_around_the_camera_is_full_resolution() {
        let s = shape(65, 1.0);
        let inside = Camera::new(
            [32.0; 3],
            [32.0, 40.0, 32.0],
            [0.0, 0.0, 1.0],
            Projection::Perspective { view_angle_deg: 30.0 },
        )
        .unwrap();
        let space = ScreenSpace::new(&inside, 64, 64, &s, 1.0).unwrap();
        assert_eq!(space.weight([0; 3], [64; 3]), MAX_WEIGHT);
        assert_eq!(space.finest_stride([0; 3], [64; 3]), 1);
    }

    #[test]
    fn bad_arguments_are_errors() {
        let s = shape(9, 1.0);
        let camera = Camera::around([0.0; 3], [8.0; 3], 0.0, 0.0, false).unwrap();
        for (w, h, m) in [(0, 4, 1.0), (4, 0, 1.0), (4, 4, -1.0), (4, 4, f64::NAN), (4, 4, f64::INFINITY)] {
            assert!(ScreenSpace::new(&camera, w, h, &s, m).is_err(), "{w} {h} {m}");
        }
    }
}
