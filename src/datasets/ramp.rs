//! A linear ramp: exactly trilinear, so every nodal error is 0.
//!
//! ```text
//! f(t) = (t_x + 2 t_y + 5 t_z) / 8,    t in [0, 1]^3,  f in [0, 1]
//! ```
//!
//! The weights sum to a power of two so that, for sizes `2^m + 1`, every
//! sample `t = i / 2^m` and every value is a short dyadic fraction: `f32` and
//! `f64` store them exactly and the octree's trilinear reconstruction
//! reproduces them bit for bit (E_0 = 0 at the root). Integer types round the
//! values and so are only approximately linear.

/// `f(t) = (t_x + 2 t_y + 5 t_z) / 8`.
pub fn value(t: [f64; 3]) -> f64 {
    (t[0] + 2.0 * t[1] + 5.0 * t[2]) / 8.0
}
