//! A shaded picture of a depth image (the paper's "depth shaded images"):
//! each painted pixel is lit by a headlight on its face, `|n . w|` for the
//! face's axis normal `n`, and dimmed with depth,
//!
//! ```text
//! grey = (0.25 + 0.75 |n_a . w|) (1 - 0.6 (z - z_min) / (z_max - z_min))
//! ```
//!
//! unpainted pixels stay transparent (shown over the background).

use super::raster::DepthImage;
use super::view::View;
use crate::render::image::Image;

/// The shaded picture of `image` seen along `view`.
pub fn shade(image: &DepthImage, view: &View) -> Image {
    let (lo, range) = image.depth_span();
    let mut out = Image::new(image.size, image.size);
    for (i, px) in out.rgba.iter_mut().enumerate() {
        let face = image.face[i];
        if face == 0 {
            continue;
        }
        let light = 0.25 + 0.75 * view.w[face as usize - 1].abs();
        let grey = (light * (1.0 - 0.6 * (image.depth[i] - lo) / range)) as f32;
        *px = [grey, grey * 0.97, grey * 0.9, 1.0];
    }
    out
}
