//! What one display returns.

use super::raster::{Counters, DepthImage};

/// The result of one display: the depth image, its counters and its time.
#[derive(Debug, Clone)]
pub struct Display {
    /// Depth (distance from the view plane, smaller is nearer) and painted face per pixel.
    pub image: DepthImage,
    /// Octants visited by colour, faces scan-converted, scanlines and pixels.
    pub counters: Counters,
    /// Wall time of the traversal and scan conversion, in milliseconds.
    pub ms: f64,
}
