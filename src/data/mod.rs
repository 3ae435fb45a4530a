//! The sampled data every algorithm reads: the borrowed, typed view of a
//! regular scalar grid ([`grid`]), the owned volume behind it ([`volume`]),
//! the grid resampled as VTK's vtkImageResample does ([`resample`]),
//! and the sample spacings every renderer shares ([`spacing`]).

pub mod grid;
pub mod planes;
pub mod resample;
pub mod spacing;
pub mod volume;
