//! Transfer functions, below the renderers and the points: [`function`]
//! classifies values ([`TransferFunction`]: piecewise-linear colour and
//! opacity, exact transparency test), `lut` tabulates it for the inner loops
//! of the compositor and the point shader.

pub mod function;
pub(crate) mod lut;

pub use function::TransferFunction;
