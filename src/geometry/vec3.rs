//! Three-vectors of `f64` (world or index space): the few operations the
//! geometry code shares.

/// `a + b`.
#[inline]
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `s a`.
#[inline]
pub fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a - b`.
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a . b`.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a / m` with `m = max |a_i| > 0` finite: components in `[-1, 1]`, one of
/// them `+-1` (up to rounding); a subnormal `m` is scaled up by `2^600` first
/// so that `1 / m` does not overflow.
fn by_largest(a: [f64; 3], m: f64) -> [f64; 3] {
    if (1.0 / m).is_finite() {
        scale(a, 1.0 / m)
    } else {
        let up = 2f64.powi(600);
        scale(scale(a, up), 1.0 / (m * up))
    }
}

/// `|a|`, without overflow or underflow: `sqrt(a . a)` when `a . a` is a
/// normal number below `1e300`, else `m |a / m|` with `m = max |a_i|` (a
/// vector of `1e-300` or `1e300` components has a length like any other).
#[inline]
pub fn norm(a: [f64; 3]) -> f64 {
    let l2 = dot(a, a);
    let m = a[0].abs().max(a[1].abs()).max(a[2].abs());
    if (l2.is_normal() && l2 < 1e300) || m == 0.0 || !m.is_finite() {
        return l2.sqrt();
    }
    let b = by_largest(a, m);
    m * dot(b, b).sqrt()
}

/// `a / |a|`, for any finite non-zero `a` however small or large (see [`norm`]).
#[inline]
pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l2 = dot(a, a);
    let m = a[0].abs().max(a[1].abs()).max(a[2].abs());
    let b = if (l2.is_normal() && l2 < 1e300) || m == 0.0 || !m.is_finite() { a } else { by_largest(a, m) };
    let l = dot(b, b).sqrt();
    [b[0] / l, b[1] / l, b[2] / l]
}
