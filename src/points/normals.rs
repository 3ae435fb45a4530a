//! Quantised normals (paper 3, section 3.3): "one-byte indices into a lookup
//! table containing normal vectors uniformly distributed in 3-space".
//!
//! The table is the 256-point spherical Fibonacci lattice,
//!
//! ```text
//! z_i = 1 - (2 i + 1) / 256,   phi_i = i * pi (3 - sqrt 5),   n_i = (sqrt(1 - z_i^2) cos phi_i, sqrt(1 - z_i^2) sin phi_i, z_i)
//! ```
//!
//! whose points cover the sphere with near-equal areas; a direction is
//! stored as the index of the table entry with the largest dot product.

use std::sync::OnceLock;

/// Entries of the table.
pub const COUNT: usize = 256;

/// The table of unit directions.
pub fn table() -> &'static [[f64; 3]; COUNT] {
    static TABLE: OnceLock<[[f64; 3]; COUNT]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        std::array::from_fn(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / COUNT as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = i as f64 * golden;
            [r * phi.cos(), r * phi.sin(), z]
        })
    })
}

/// The index of the table entry nearest to direction `v` (any length; the
/// zero vector, a flat neighbourhood, gives entry 0, pointing along +z).
pub fn quantise(v: [f64; 3]) -> u8 {
    let t = table();
    let mut best = (f64::NEG_INFINITY, 0);
    for (i, n) in t.iter().enumerate() {
        let d = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
        if d > best.0 {
            best = (d, i);
        }
    }
    best.1 as u8
}

/// The unit direction of index `i`.
pub fn direction(i: u8) -> [f64; 3] {
    table()[i as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_unit_and_quantisation_is_within_its_spacing() {
        for n in table() {
            assert!(((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() - 1.0).abs() < 1e-12);
        }
        // 256 near-equal cells of 4 pi / 256 sr: every direction is within ~9 degrees of its entry.
        let mut worst: f64 = 1.0;
        for k in 0..2000 {
            let a = k as f64 * 0.7548776662;
            let z = 1.0 - 2.0 * ((k as f64 * 0.5698402910) % 1.0);
            let r = (1.0 - z * z).sqrt();
            let v = [r * a.cos(), r * a.sin(), z];
            let n = direction(quantise(v));
            worst = worst.min(v[0] * n[0] + v[1] * n[1] + v[2] * n[2]);
        }
        assert!(worst > 10f64.to_radians().cos(), "worst angle {:.1} degrees", worst.acos().to_degrees());
        assert_eq!(quantise([0.0; 3]), 0);
        assert!(direction(quantise([0.0, 0.0, 1.0]))[2] > 0.99);
    }
}
