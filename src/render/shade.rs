//! The gradient rule of shaded volumes, the same in the CPU compositor, the
//! reference ray caster and the brick shader: central differences of the
//! reconstruction `F` one lattice step away along each axis (a brick of
//! stride `s`: one texel, `s` samples; the full grid: one sample), scaled
//! by the world length of that step,
//!
//! ```text
//! g_a = (F(u + e_a) - F(u - e_a)) / (2 h_a),   h_a = stride * spacing_a
//! N   = g / |g|   (0 when g = 0: only the ambient term remains)
//! ```
//!
//! `u` in lattice coordinates (a brick's texels, its gradient border
//! included, [`super::texture::bordered_position`]; the grid's index space
//! for the reference). VTK's `computeGradient` takes the same differences
//! (`(g1 - g2) / in_cellSpacing`, one voxel away) and leaves out the 2,
//! which the normalisation removes. The shading itself is
//! [`crate::transfer::lighting`].

use crate::geometry::vec3::dot;

/// The gradient `g` of `f` at lattice point `u`, `h` the world length of
/// one lattice step per axis (module documentation).
#[inline]
pub(crate) fn gradient(f: impl Fn([f64; 3]) -> f64, u: [f64; 3], h: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|a| {
        let (mut up, mut down) = (u, u);
        up[a] += 1.0;
        down[a] -= 1.0;
        (f(up) - f(down)) / (2.0 * h[a])
    })
}

/// `g / |g|`, or 0 when `g` is 0 or not finite.
#[inline]
pub(crate) fn normal(g: [f64; 3]) -> [f64; 3] {
    let l = dot(g, g).sqrt();
    if l > 0.0 && l.is_finite() {
        [g[0] / l, g[1] / l, g[2] / l]
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear field's gradient is exact, whatever the step; zero gives a zero normal.
    #[test]
    fn linear_field() {
        let f = |u: [f64; 3]| 2.0 * u[0] - 3.0 * u[1] + 0.5 * u[2];
        let g = gradient(f, [1.5, 2.0, 7.25], [2.0, 1.0, 0.5]);
        assert_eq!(g, [1.0, -3.0, 1.0]);
        assert_eq!(normal([0.0; 3]), [0.0; 3]);
        let n = normal(g);
        assert!((dot(n, n) - 1.0).abs() < 1e-15);
    }
}
