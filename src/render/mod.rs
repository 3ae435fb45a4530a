//! The CPU compositor (executes a DrawList), the full-resolution reference
//! ray caster, transfer functions and image metrics.
//!
//! One responsibility per file: [`transfer`] classifies values, [`blend`] is
//! the compositing step (opacity correction, over and under), [`image`]
//! holds and writes pictures, [`metrics`] compares them,
//! [`reference`](mod@reference) ray-casts the full-resolution volume,
//! [`compositor`] executes a [`DrawList`](crate::plan::DrawList) slice by
//! slice, brick by brick.
//! Inside the crate: `check` (inputs), `sample` (trilinear reconstruction of the grid and of a
//! brick's texture), `lut` (the transfer function tabulated), `geometry` (rays against boxes and slice planes, screen
//! footprints), `triangles` (ray-triangle hits through a uniform grid, surface
//! shading).

pub mod blend;
mod check;
pub mod compositor;
mod geometry;
pub mod image;
pub(crate) mod lut;
pub mod metrics;
pub mod reference;
mod sample;
pub mod texture;
pub mod transfer;
mod triangles;

#[cfg(test)]
mod tests;
