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
        self.contains_rotated(p, self.phi_degrees.to_radians().sin_cos())
    }

    /// [`Ellipsoid::contains`] with `(sin phi, cos phi)` given (the phantom
    /// computes them once, not once a sample).
    #[inline(always)]
    fn contains_rotated(&self, p: [f64; 3], (s, c): (f64, f64)) -> bool {
        let dx = p[0] - self.centre[0];
        let dy = p[1] - self.centre[1];
        let dz = p[2] - self.centre[2];
        let x = dx * c + dy * s;
        let y = -dx * s + dy * c;
        (x / self.axes[0]).powi(2) + (y / self.axes[1]).powi(2) + (dz / self.axes[2]).powi(2) <= 1.0
    }
}

/// `(sin phi, cos phi)` of every ellipsoid, computed once.
fn rotations() -> &'static [(f64, f64); 10] {
    static ROTATIONS: std::sync::OnceLock<[(f64, f64); 10]> = std::sync::OnceLock::new();
    ROTATIONS.get_or_init(|| ELLIPSOIDS.map(|e| e.phi_degrees.to_radians().sin_cos()))
}

/// The phantom at box-normalised `t`: sum of the intensities, clamped to `[0, 1]`.
pub fn value(t: [f64; 3]) -> f64 {
    let p = [2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0, 2.0 * t[2] - 1.0];
    let rotations = rotations();
    let sum: f64 =
        ELLIPSOIDS.iter().zip(rotations).filter(|(e, &r)| e.contains_rotated(p, r)).map(|(e, _)| e.intensity).sum();
    // `<= 0` also maps the -0.0 that cancelling intensities can leave to +0.0.
    if sum <= 0.0 {
        0.0
    } else {
        sum.min(1.0)
    }
}

/// One row of the phantom, `out[i] = value([i / (n - 1), ty, tz])` for
/// `n = out.len()` (`t_x = 0` when `n = 1`), equal bit for bit to [`value`]
/// but without testing every ellipsoid at every sample: along a row each
/// ellipsoid holds one run of samples, found from the quadratic
///
/// ```text
/// A dx^2 + B dx + C <= 0,   dx = p_x - c_x
/// A = cos^2/a^2 + sin^2/b^2,  B = 2 dy sin cos (1/a^2 - 1/b^2)
/// C = dy^2 (sin^2/a^2 + cos^2/b^2) + (dz/c)^2 - 1
/// ```
///
/// whose ends are then settled by [`Ellipsoid::contains`] itself on the
/// few samples around each root, so rounding cannot move a sample in or out.
/// Between the ends of the runs the set of ellipsoids is constant: its sum
/// (in table order, as [`value`] adds) is computed once per stretch.
pub fn row(ty: f64, tz: f64, out: &mut [f64]) {
    let n = out.len();
    if n == 0 {
        return;
    }
    let t = |i: usize| if n > 1 { i as f64 / (n - 1) as f64 } else { 0.0 };
    let py = 2.0 * ty - 1.0;
    let pz = 2.0 * tz - 1.0;
    let rotations = rotations();
    // runs[e] = (first, last) samples inside ellipsoid e, inclusive; None when none.
    let mut runs = [None; 10];
    for (e, (ellipsoid, &r)) in ELLIPSOIDS.iter().zip(rotations).enumerate() {
        runs[e] = run(ellipsoid, r, py, pz, n, &|i| [2.0 * t(i) - 1.0, py, pz]);
    }
    let mut cuts: Vec<usize> = vec![0, n];
    for &(first, last) in runs.iter().flatten() {
        cuts.push(first);
        cuts.push(last + 1);
    }
    cuts.sort_unstable();
    cuts.dedup();
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let sum: f64 = ELLIPSOIDS
            .iter()
            .zip(&runs)
            .filter(|(_, r)| r.is_some_and(|(first, last)| first <= a && a <= last))
            .map(|(e, _)| e.intensity)
            .sum();
        let v = if sum <= 0.0 { 0.0 } else { sum.min(1.0) };
        out[a..b].fill(v);
    }
}

/// The run of samples `0 .. n` of a row (at `p = at(i)`) inside `e`: its
/// first and last sample. The roots of the quadratic (see [`row`]) bound it;
/// [`Ellipsoid::contains`] decides every sample within [`MARGIN`] of a root,
/// and the whole row when the roots do not settle it.
fn run(
    e: &Ellipsoid,
    (s, c): (f64, f64),
    py: f64,
    pz: f64,
    n: usize,
    at: &dyn Fn(usize) -> [f64; 3],
) -> Option<(usize, usize)> {
    let dz = pz - e.centre[2];
    // A sum of non-negative terms is at least each term: outside everywhere.
    if (dz / e.axes[2]).powi(2) > 1.0 {
        return None;
    }
    let inside = |i: usize| e.contains_rotated(at(i), (s, c));
    let exact = || {
        let first = (0..n).find(|&i| inside(i))?;
        let last = (first..n).rev().find(|&i| inside(i))?;
        Some((first, last))
    };
    let dy = py - e.centre[1];
    let (ia, ib) = (1.0 / (e.axes[0] * e.axes[0]), 1.0 / (e.axes[1] * e.axes[1]));
    let qa = c * c * ia + s * s * ib;
    let qb = 2.0 * dy * s * c * (ia - ib);
    let qc = dy * dy * (s * s * ia + c * c * ib) + (dz / e.axes[2]).powi(2) - 1.0;
    let disc = qb * qb - 4.0 * qa * qc;
    let vertex = -qb / (2.0 * qa);
    let half = if disc > 0.0 { disc.sqrt() / (2.0 * qa) } else { 0.0 };
    // Sample index of p_x = c_x + dx: i = (p_x + 1) (n - 1) / 2.
    let index = |dx: f64| (e.centre[0] + dx + 1.0) * (n.max(2) - 1) as f64 / 2.0;
    let (lo, hi) = (index(vertex - half), index(vertex + half));
    if !(lo.is_finite() && hi.is_finite()) {
        return exact();
    }
    let clamp = |x: f64| x.clamp(0.0, (n - 1) as f64) as usize;
    let (lo_a, lo_b) = (clamp(lo.floor() - MARGIN), clamp(lo.ceil() + MARGIN));
    let (hi_a, hi_b) = (clamp(hi.floor() - MARGIN), clamp(hi.ceil() + MARGIN));
    if hi_b <= lo_b + 2 * MARGIN as usize {
        // A short run, or none (disc < 0 near tangency): every sample around it.
        let first = (lo_a..=hi_b).find(|&i| inside(i));
        return first.map(|f| (f, (f..=hi_b).rev().find(|&i| inside(i)).unwrap_or(f)));
    }
    // The run starts in [lo_a, lo_b] unless it starts at sample 0 (lo < 0:
    // then lo_a = lo_b = 0) and ends in [hi_a, hi_b].
    let first = (lo_a..=lo_b).find(|&i| inside(i));
    let last = (hi_a..=hi_b).rev().find(|&i| inside(i));
    match (first, last) {
        // Inside just after the start window and just before the end window,
        // and outside just before and after them: the run is settled.
        (Some(f), Some(l))
            if (f == 0 || !inside(f - 1)) && (l + 1 == n || !inside(l + 1)) && inside(lo_b) && inside(hi_a) =>
        {
            Some((f, l))
        }
        _ => exact(),
    }
}

/// Samples on either side of a root that [`run`] tests one by one.
const MARGIN: f64 = 3.0;

#[cfg(test)]
mod tests {
    use super::value;

    #[test]
    fn rows_equal_the_sample_by_sample_phantom() {
        for (n, ny, nz) in [(65, 65, 65), (100, 37, 41), (257, 29, 23), (2, 2, 2), (1023, 7, 9)] {
            let mut out = vec![0.0; n];
            for k in 0..nz {
                let tz = k as f64 / (nz - 1) as f64;
                for j in 0..ny {
                    let ty = j as f64 / (ny - 1) as f64;
                    super::row(ty, tz, &mut out);
                    for (i, &v) in out.iter().enumerate() {
                        let t = [i as f64 / (n - 1) as f64, ty, tz];
                        assert_eq!(v.to_bits(), value(t).to_bits(), "n {n} at {i} {j} {k}");
                    }
                }
            }
        }
    }

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
