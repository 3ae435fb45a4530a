//! The Marschner-Lobb test signal (Marschner & Lobb, *An evaluation of
//! reconstruction filters for volume rendering*, 1994), sampled over
//! `[-1, 1]^3`:
//!
//! ```text
//! p   = 2 t - 1                         (t in [0, 1]^3)
//! r   = sqrt(p_x^2 + p_y^2)
//! rho = cos(2 pi f_M cos(pi r / 2))
//! f   = (1 - sin(pi p_z / 2) + alpha (1 + rho)) / (2 (1 + alpha))     f in [0, 1]
//! ```
//!
//! with `f_M = 6` and `alpha = 0.25`. Its high-frequency rings make it the
//! classic worst case for trilinear reconstruction: nodal errors stay large
//! until fine levels.

use std::f64::consts::PI;

/// Modulation frequency f_M.
pub const F_M: f64 = 6.0;
/// Amplitude of the modulation alpha.
pub const ALPHA: f64 = 0.25;

/// The Marschner-Lobb value at box-normalised `t`.
pub fn value(t: [f64; 3]) -> f64 {
    let p = [2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0, 2.0 * t[2] - 1.0];
    let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
    let rho = (2.0 * PI * F_M * (PI * r / 2.0).cos()).cos();
    (1.0 - (PI * p[2] / 2.0).sin() + ALPHA * (1.0 + rho)) / (2.0 * (1.0 + ALPHA))
}

#[cfg(test)]
mod tests {
    #[test]
    fn known_values() {
        // centre: r = 0, rho = cos(2 pi 6) = 1, sin(0) = 0 -> (1 + 0.5) / 2.5
        assert!((super::value([0.5; 3]) - 0.6).abs() < 1e-12);
        // bottom z: sin(-pi/2) = -1 -> (2 + 0.25 (1 + rho)) / 2.5 at r = 0 is 1.0
        assert!((super::value([0.5, 0.5, 0.0]) - 1.0).abs() < 1e-12);
    }
}
