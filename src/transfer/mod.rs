//! Transfer functions, below the renderers and the points: [`function`]
//! classifies values ([`TransferFunction`]: piecewise-linear colour and
//! opacity, exact transparency test), `lut` tabulates it for the inner loops
//! of the compositor and the point shader, [`lighting`] shades a sample
//! (material, lights, VTK's volume shading model), [`gradient_opacity`]
//! scales a sample's opacity by its gradient magnitude, [`transfer2d`] gives
//! colour and opacity from the value and the gradient magnitude together,
//! [`direct_colour`] scales the colour components of an RGBA volume as VTK does.

pub mod direct_colour;
pub mod function;
pub mod gradient_opacity;
pub mod lighting;
pub(crate) mod lut;
pub mod scattering;
pub mod transfer2d;

pub use function::TransferFunction;
pub use gradient_opacity::GradientOpacity;
pub use scattering::Scattering;
pub use transfer2d::TransferFunction2D;
