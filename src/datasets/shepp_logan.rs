//! The 3D Shepp-Logan head phantom: the ten ellipsoids of the 3D extension by
//! Kak & Slaney (*Principles of Computerized Tomographic Imaging*, 1988),
//! with high-contrast ("modified", after Toft) intensities so the tissues are
//! visible without windowing.
//!
//! Coordinates are `p = 2 t - 1` in `[-1, 1]^3`. Ellipsoid `e` with centre
//! `c`, semi-axes `(a, b, c)` and rotation `phi` about the z axis contains `p` when
//!
//! ```text
//! x' =  (p_x - c_x) cos(phi) + (p_y - c_y) sin(phi)
//! y' = -(p_x - c_x) sin(phi) + (p_y - c_y) cos(phi)
//! (x' / a)^2 + (y' / b)^2 + ((p_z - c_z) / c)^2 <= 1
//! ```
//!
//! and the phantom is the sum of the intensities of the ellipsoids containing
//! `p`, clamped to `[0, 1]`:
//!
//! | # | centre (x, y, z)        | semi-axes (a, b, c)  | phi  | intensity | tissue        |
//! |---|-------------------------|----------------------|------|-----------|---------------|
//! | 1 | 0, 0, 0                 | 0.69, 0.92, 0.9      | 0    |  1.0      | skull         |
//! | 2 | 0, 0, 0                 | 0.6624, 0.874, 0.88  | 0    | -0.8      | brain         |
//! | 3 | -0.22, 0, -0.25         | 0.41, 0.16, 0.21     | 108  | -0.2      | left ventricle|
//! | 4 | 0.22, 0, -0.25          | 0.31, 0.11, 0.22     | 72   | -0.2      | right ventricle|
//! | 5 | 0, 0.35, -0.25          | 0.21, 0.25, 0.5      | 0    |  0.2      |               |
//! | 6 | 0, 0.1, -0.25           | 0.046, 0.046, 0.046  | 0    |  0.2      | tumour        |
//! | 7 | -0.08, -0.65, -0.25     | 0.046, 0.023, 0.02   | 0    |  0.1      | tumour        |
//! | 8 | 0.06, -0.65, -0.25      | 0.046, 0.023, 0.02   | 90   |  0.1      | tumour        |
//! | 9 | 0.06, -0.105, 0.625     | 0.056, 0.04, 0.1     | 90   |  0.2      |               |
//! |10 | 0, 0.1, 0.625           | 0.056, 0.056, 0.1    | 0    | -0.2      |               |
//!
//! So the skull shell is 1.0, brain 0.2, ventricles 0.0 and outside 0.0.

/// One ellipsoid: centre, semi-axes, rotation about z in degrees, intensity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// Centre in `[-1, 1]^3`.
    pub centre: [f64; 3],
    /// Semi-axes along the rotated x, y and z.
    pub axes: [f64; 3],
    /// Rotation about the z axis in degrees.
    pub phi_degrees: f64,
    /// Added to the value of every point inside.
    pub intensity: f64,
}

const fn e(centre: [f64; 3], axes: [f64; 3], phi_degrees: f64, intensity: f64) -> Ellipsoid {
    Ellipsoid { centre, axes, phi_degrees, intensity }
}

/// The table of the module docs.
pub const ELLIPSOIDS: [Ellipsoid; 10] = [
    e([0.0, 0.0, 0.0], [0.69, 0.92, 0.9], 0.0, 1.0),
    e([0.0, 0.0, 0.0], [0.6624, 0.874, 0.88], 0.0, -0.8),
    e([-0.22, 0.0, -0.25], [0.41, 0.16, 0.21], 108.0, -0.2),
    e([0.22, 0.0, -0.25], [0.31, 0.11, 0.22], 72.0, -0.2),
    e([0.0, 0.35, -0.25], [0.21, 0.25, 0.5], 0.0, 0.2),
    e([0.0, 0.1, -0.25], [0.046, 0.046, 0.046], 0.0, 0.2),
    e([-0.08, -0.65, -0.25], [0.046, 0.023, 0.02], 0.0, 0.1),
    e([0.06, -0.65, -0.25], [0.046, 0.023, 0.02], 90.0, 0.1),
    e([0.06, -0.105, 0.625], [0.056, 0.04, 0.1], 90.0, 0.2),
    e([0.0, 0.1, 0.625], [0.056, 0.056, 0.1], 0.0, -0.2),
];

impl Ellipsoid {
    /// True when `p` (in `[-1, 1]^3`) is inside or on the ellipsoid.
    pub fn contains(&self, p: [f64; 3]) -> bool {
        let (s, c) = self.phi_degrees.to_radians().sin_cos();
        let dx = p[0] - self.centre[0];
        let dy = p[1] - self.centre[1];
        let dz = p[2] - self.centre[2];
        let x = dx * c + dy * s;
        let y = -dx * s + dy * c;
        (x / self.axes[0]).powi(2) + (y / self.axes[1]).powi(2) + (dz / self.axes[2]).powi(2) <= 1.0
    }
}

/// The phantom at box-normalised `t`: sum of the intensities, clamped to `[0, 1]`.
pub fn value(t: [f64; 3]) -> f64 {
    let p = [2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0, 2.0 * t[2] - 1.0];
    let sum: f64 = ELLIPSOIDS.iter().filter(|e| e.contains(p)).map(|e| e.intensity).sum();
    // `<= 0` also maps the -0.0 that cancelling intensities can leave to +0.0.
    if sum <= 0.0 {
        0.0
    } else {
        sum.min(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::value;

    fn at(p: [f64; 3]) -> f64 {
        value([(p[0] + 1.0) / 2.0, (p[1] + 1.0) / 2.0, (p[2] + 1.0) / 2.0])
    }

    #[test]
    fn tissues_have_their_values() {
        assert_eq!(at([0.0, 0.9, 0.0]), 1.0, "skull");
        assert!((at([0.0, 0.0, 0.0]) - 0.2).abs() < 1e-12, "brain");
        assert_eq!(at([0.0, 0.0, 0.95]), 0.0, "outside");
        assert!(at([-0.22, 0.0, -0.25]).abs() < 1e-12, "left ventricle");
        assert!((at([0.0, 0.1, -0.25]) - 0.6).abs() < 1e-12, "tumour inside ellipsoid 5");
    }
}
