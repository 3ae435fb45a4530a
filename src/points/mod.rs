//! The hybrid point/volume representation (paper 3: Wilson, Ma, McCormick,
//! "A hybrid method for interactive volume rendering"): a low-resolution
//! volume plus points where its trilinear reconstruction is wrong.
//!
//! - [`generate`]: the low-resolution volume is T_f, the grid sampled every
//!   `f` samples and reconstructed trilinearly ([`crate::octree::trilinear`],
//!   the texture of a uniform stride-`f` selection); the error grid is
//!   `e(x) = f(x) - T_f(x)` at every sample; points go where `|e|` exceeds a
//!   threshold, or at the K largest `|e|` for a point budget (section 3.1).
//! - [`lowres`]: the optimized low-resolution volume, which overestimates
//!   the data by at most a bound (section 3.2).
//! - [`normals`]: the table of 256 directions a point's normal is quantised
//!   to (section 3.3).
//! - [`shade`]: the colour and opacity each point adds under a transfer
//!   function, averaged over its voxel (section 4.1).
//! - [`storage`]: the binary point file, 6 bytes a point on grids up to
//!   256^3 (9 beyond), with a versioned header (section 3.3).

pub mod draw;
pub mod generate;
pub mod lowres;
pub mod mass;
pub mod normals;
pub mod shade;
pub mod storage;

pub use draw::{add_points, Footprint};
pub use generate::{generate, generate_hybrid, PointOptions, PointSelect};
pub use lowres::low_resolution;
pub use mass::PointMass;
pub use shade::{shade, PointShade};
pub use storage::{read_points, write_points};

/// One stored point (quantised as in the file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Point {
    /// Grid sample of the point.
    pub ijk: [u16; 3],
    /// Index into [`normals::TABLE`] of the original data's gradient direction.
    pub normal: u8,
    /// Error `f - T_f` at the point, `error / 127 * error_scale` in data units.
    pub error: i8,
    /// Original value, `value_min + value / 255 * (value_max - value_min)`.
    pub value: u8,
}

/// The points of one grid and low-resolution factor, with what dequantises them.
#[derive(Debug, Clone, PartialEq)]
pub struct PointSet {
    /// Samples per axis of the grid the points were taken from.
    pub dims: [usize; 3],
    /// Low-resolution factor `f` (2, 4 or 8): the volume they complete is T_f.
    pub factor: usize,
    /// Data range the values are quantised over.
    pub value_range: [f64; 2],
    /// Largest `|error|` among the points: the error of `error = +-127`.
    pub error_scale: f64,
    /// The optimized representation's bound on how much the low-resolution
    /// volume overestimates (data units, [`lowres`]); infinite: plain subsampling.
    pub max_overestimate: f64,
    /// The points, in grid order (x fastest).
    pub points: Vec<Point>,
}

impl PointSet {
    /// Bytes per stored point: 6 with 8-bit coordinates (every axis at most
    /// 256 samples), 9 with 16-bit ones.
    pub fn point_bytes(&self) -> usize {
        if self.dims.iter().all(|&n| n <= 256) {
            6
        } else {
            9
        }
    }

    /// Bytes of all points as stored (without the file header).
    pub fn bytes(&self) -> usize {
        self.points.len() * self.point_bytes()
    }

    /// The original value of `p`, dequantised.
    pub fn value(&self, p: &Point) -> f64 {
        let [lo, hi] = self.value_range;
        lo + f64::from(p.value) / 255.0 * (hi - lo)
    }

    /// The error of `p` in data units, dequantised.
    pub fn error(&self, p: &Point) -> f64 {
        f64::from(p.error) / 127.0 * self.error_scale
    }
}
