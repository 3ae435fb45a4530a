//! Transfer functions, below the renderers and the points: [`function`]
//! classifies values ([`TransferFunction`]: piecewise-linear colour and
//! opacity, exact transparency test), `lut` tabulates it for the inner loops
//! of the compositor and the point shader, [`lighting`] shades a sample
//! (material, lights, VTK's volume shading model).

pub mod function;
pub mod lighting;
pub(crate) mod lut;

pub use function::TransferFunction;
