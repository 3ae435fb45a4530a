//! The CPU compositor (executes a DrawList), the full-resolution reference
//! ray caster and image metrics.
//!
//! One responsibility per file: [`blend`] is the compositing step (opacity
//! correction, over and under), [`image`] holds and writes pictures,
//! [`metrics`] compares them, [`reference`](mod@reference) ray-casts the
//! full-resolution volume, [`compositor`] executes a
//! [`DrawList`](crate::plan::DrawList) slice by slice, brick by brick,
//! [`dependent`] draws two fields with dependent components, [`rgba`] an
//! RGBA volume (four dependent components). The
//! transfer function and its table live in [`crate::transfer`], re-exported
//! here as [`transfer`].
//! Inside the crate: `check` (inputs), `sample` (trilinear reconstruction of the grid and of a
//! brick's texture), `geometry` (rays against boxes and slice planes, screen
//! footprints), `triangles` (ray-triangle hits through a uniform grid, surface
//! shading), `shade` (the volume's gradient rule, shared by both renderers).

pub mod blend;
mod check;
pub mod compositor;
pub mod dependent;
mod fields;
mod geometry;
pub mod image;
mod intensity;
pub mod metrics;
pub mod reference;
pub mod rgba;
mod sample;
pub mod scattering;
mod shade;
pub mod texture;
mod transfer2d;
mod triangles;

pub use crate::transfer;

#[cfg(test)]
mod blend_tests;
#[cfg(test)]
mod crop_tests;
#[cfg(test)]
mod dependent_tests;
#[cfg(test)]
mod jitter_tests;
#[cfg(test)]
mod rgba_tests;
#[cfg(test)]
mod sampling_tests;
#[cfg(test)]
mod slice_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod view_selection_tests;
