//! The hybrid point/volume representation (paper 3: Wilson, Ma, McCormick,
//! "A hybrid method for interactive volume rendering"): a low-resolution
//! volume plus points where its trilinear reconstruction is wrong.
//!
//! - [`generate`](mod@generate): the low-resolution volume is T_f, the grid sampled every
//!   `f` samples and reconstructed trilinearly ([`crate::octree::trilinear`],
//!   the texture of a uniform stride-`f` selection); the error grid is
//!   `e(x) = f(x) - T_f(x)` at every sample; points go where `|e|` exceeds a
//!   threshold, or at the K largest `|e|` for a point budget (section 3.1).
//! - [`lowres`]: the optimized low-resolution volume, which overestimates
//!   the data by at most a bound (section 3.2).
//! - [`normals`]: the table of 256 directions a point's normal is quantised
//!   to (section 3.3).
//! - [`opacity`]: the opacity and colour a point adds over the volume
//!   (section 3.3); [`footprint`]: the pixels it covers (section 4); the
//!   DrawList buckets points into slabs in [`crate::plan::point_slabs`].
//! - [`shade`](mod@shade): the colour and opacity each point adds under a transfer
//!   function, averaged over its voxel (section 4.1).
//! - [`storage`]: the binary point file, 6 bytes a point on grids up to
//!   256^3 (9 beyond), with a versioned header (section 3.3).

pub mod footprint;
pub mod generate;
pub mod lowres;
pub mod mass;
pub mod normals;
pub mod opacity;
pub mod set;
pub mod shade;
pub mod storage;

pub use footprint::Footprint;
pub use generate::{generate, generate_hybrid, PointOptions, PointSelect};
pub use lowres::low_resolution;
pub use mass::PointMass;
pub use set::{Point, PointSet};
pub use shade::{shade, PointShade};
pub use storage::{read_points, write_points};
