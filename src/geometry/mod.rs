//! World-space geometry: three-vectors of `f64` ([`vec3`]) and the camera
//! with its rays ([`camera`]).

pub mod camera;
pub mod vec3;
