//! Built-in datasets, generated in Rust at any size: the volumes the README,
//! the CLI (`--dataset`), the benchmarks and the ParaView tests share.
//!
//! Every generator is a pure function of the box-normalised position
//! `t = (i / (nx - 1), j / (ny - 1), k / (nz - 1))` in `[0, 1]^3`, evaluated in
//! parallel one z-slice per task, so the result is the same bit for bit on any
//! number of threads. Geometry is spacing 1 and origin 0 (index space = world
//! space), so a dataset of size `n` spans `[0, n - 1]^3`.
//!
//! One file per dataset; [`dataset`] names them, [`generate()`] samples and
//! converts them to the requested scalar type.

pub mod constant;
pub mod dataset;
pub mod generate;
pub mod marschner_lobb;
pub mod ramp;
pub mod shepp_logan;
pub mod sphere;
pub mod vessels;
pub mod wavelet;

pub use dataset::Dataset;
pub use generate::{generate, generate_dims, to_type_range};
