//! The compositing step every renderer shares: opacity correction and the
//! two orders of blending premultiplied colour.
//!
//! A sample of straight colour `c` and opacity `a` classified for the
//! reference spacing `d0` but taken every `d` world units stands for a
//! thicker (or thinner) layer; its opacity becomes
//!
//! ```text
//! a' = 1 - (1 - a)^(d / d0) = -expm1((d / d0) ln_1p(-a))
//! ```
//!
//! (the second form keeps every digit for small `a`, where `1 - a` rounds).
//! Accumulators `(C, A)` hold premultiplied colour and opacity:
//!
//! ```text
//! back to front (over):   C = a' c + (1 - a') C,   A = a' + (1 - a') A
//! front to back (under):  C = C + (1 - A) a' c,    A = A + (1 - A) a'
//! ```
//!
//! Both keep `0 <= C <= A <= 1` for `a', c` in `[0, 1]`; `A` is clamped to
//! 1 against rounding.

/// Premultiplied `[r, g, b, a]`.
pub type Rgba = [f64; 4];

/// `a' = 1 - (1 - a)^ratio` with `ratio = d / d0`, computed as
/// `-expm1(ratio * ln_1p(-a))`; `a` is clamped to `[0, 1]` first.
#[inline]
pub fn correct_opacity(a: f64, ratio: f64) -> f64 {
    let a = a.clamp(0.0, 1.0);
    if ratio == 1.0 || a == 0.0 || a == 1.0 {
        return a;
    }
    (-(ratio * (-a).ln_1p()).exp_m1()).clamp(0.0, 1.0)
}

/// Back to front: the sample `(c, a)` (straight colour) goes over `acc`:
/// `C = a c + (1 - a) C`, `A = a + (1 - a) A`.
#[inline]
pub fn over(acc: Rgba, c: [f64; 3], a: f64) -> Rgba {
    let k = 1.0 - a;
    [a * c[0] + k * acc[0], a * c[1] + k * acc[1], a * c[2] + k * acc[2], (a + k * acc[3]).min(1.0)]
}

/// Front to back: the sample `(c, a)` (straight colour) goes under `acc`:
/// `C = C + (1 - A) a c`, `A = A + (1 - A) a`.
#[inline]
pub fn under(acc: Rgba, c: [f64; 3], a: f64) -> Rgba {
    let w = (1.0 - acc[3]) * a;
    [acc[0] + w * c[0], acc[1] + w * c[1], acc[2] + w * c[2], (acc[3] + w).min(1.0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (a) 4096 layers of alpha 1e-4, in either order, reach the closed form
    /// `1 - (1 - 1e-4)^4096` within 1e-4 (in fact within 1e-12: f64 accumulators).
    #[test]
    fn many_thin_layers_match_the_closed_form() {
        let (a, n) = (1e-4, 4096);
        let exact = 1.0 - (1.0f64 - a).powi(n);
        let (mut back, mut front) = ([0.0; 4], [0.0; 4]);
        for _ in 0..n {
            back = over(back, [1.0, 0.5, 0.25], a);
            front = under(front, [1.0, 0.5, 0.25], a);
        }
        for acc in [back, front] {
            assert!((acc[3] - exact).abs() < 1e-4, "{} vs {exact}", acc[3]);
            assert!((acc[3] - exact).abs() < 1e-12);
            assert!((acc[1] - 0.5 * exact).abs() < 1e-12);
        }
        // One layer of the whole thickness, by opacity correction, is the same.
        assert!((correct_opacity(a, n as f64) - exact).abs() < 1e-12);
    }

    /// (b) Alpha near 1 keeps `0 <= C <= A <= 1` and finite values, corrected or not.
    #[test]
    fn alpha_near_one_stays_bounded() {
        let a = 0.999999;
        for ratio in [1.0 / 4096.0, 0.25, 1.0, 8.0, 4096.0] {
            let a = correct_opacity(a, ratio);
            assert!(a.is_finite() && (0.0..=1.0).contains(&a), "{a} at ratio {ratio}");
            let (mut back, mut front) = ([0.0; 4], [0.0; 4]);
            for i in 0..10_000 {
                let c = [1.0, (i % 7) as f64 / 6.0, 0.0];
                back = over(back, c, a);
                front = under(front, c, a);
                for acc in [back, front] {
                    assert!(acc.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)), "{acc:?}");
                    assert!(acc[..3].iter().all(|&v| v <= acc[3] + 1e-15), "{acc:?}");
                }
            }
        }
        assert_eq!(correct_opacity(1.0, 0.001), 1.0);
        assert_eq!(correct_opacity(0.0, 1000.0), 0.0);
        assert_eq!(correct_opacity(1.5, 2.0), 1.0);
    }

    /// (c) A constant field sampled at spacing d/2 with corrected opacity
    /// composites to what spacing d gives, within 1e-6, in either order.
    #[test]
    fn opacity_correction_makes_spacing_irrelevant() {
        let c = [0.9, 0.6, 0.3];
        for a in [1e-3, 0.05, 0.3, 0.9] {
            let half = correct_opacity(a, 0.5);
            let (mut coarse, mut fine) = ([0.0; 4], [0.0; 4]);
            let (mut coarse_f, mut fine_f) = ([0.0; 4], [0.0; 4]);
            for _ in 0..50 {
                coarse = over(coarse, c, a);
                coarse_f = under(coarse_f, c, a);
            }
            for _ in 0..100 {
                fine = over(fine, c, half);
                fine_f = under(fine_f, c, half);
            }
            for k in 0..4 {
                assert!((coarse[k] - fine[k]).abs() < 1e-6, "a {a}: {coarse:?} vs {fine:?}");
                assert!((coarse_f[k] - fine_f[k]).abs() < 1e-6, "a {a}: {coarse_f:?} vs {fine_f:?}");
            }
        }
    }
}
