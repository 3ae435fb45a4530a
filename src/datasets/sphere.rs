//! A signed distance field to a sphere, offset so that the sphere is the 0.5
//! isosurface.
//!
//! ```text
//! f(t) = 0.5 + (|t - c| - R) / sqrt(3),   c = (0.5, 0.5, 0.5),  R = 0.35
//! ```
//!
//! in box-normalised coordinates `t in [0, 1]^3`. Since `|t - c| <= sqrt(3)/2`
//! and `R <= sqrt(3)/2`, `f` stays in `[0, 1]`; `f < 0.5` inside the sphere.
//! One unit of `f` is `sqrt(3)` box widths, i.e. `sqrt(3) (n - 1)` voxels on a
//! cube of `n` samples.

/// Sphere radius as a fraction of the box width.
pub const RADIUS: f64 = 0.35;

/// `f(t) = 0.5 + (|t - c| - R) / sqrt(3)`.
pub fn value(t: [f64; 3]) -> f64 {
    let d = ((t[0] - 0.5).powi(2) + (t[1] - 0.5).powi(2) + (t[2] - 0.5).powi(2)).sqrt();
    0.5 + (d - RADIUS) / 3f64.sqrt()
}

#[cfg(test)]
mod tests {
    #[test]
    fn surface_is_the_half_isosurface() {
        assert!((super::value([0.5 + super::RADIUS, 0.5, 0.5]) - 0.5).abs() < 1e-15);
        assert!(super::value([0.5; 3]) < 0.5);
        assert!(super::value([0.0; 3]) > 0.5 && super::value([1.0; 3]) <= 1.0);
    }
}
