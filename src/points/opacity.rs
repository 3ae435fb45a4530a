//! The opacity and colour a point adds over the volume (paper 3).
//!
//! Section 3.3: "the error value indicates how much the opacity should be
//! scaled so that, when combined with the volumetric data, the correct
//! opacity is presented". Over one sample's depth the volume gives
//! `a_v = alpha(f - e)` and the original `a_t = alpha(f)`, so the point adds
//!
//! ```text
//! a_p = max(0, (a_t - a_v) / (1 - a_v))      so that 1 - (1 - a_v)(1 - a_p) = a_t
//! ```
//!
//! (points only add: where the low resolution overestimates they add nothing,
//! section 4.1), in the colour of `f` ([`point_colour`]).

/// The straight colour of a point of opacity `a_p = (a_t - a_v) / (1 - a_v)`
/// over a volume sample `(c_v, a_v)` such that together they show the
/// original `(c_t, a_t)` premultiplied, `a_v c_v + (1 - a_v) a_p c_p = a_t c_t`:
///
/// ```text
/// c_p = (a_t c_t - a_v c_v) / (a_t - a_v)      clamped to [0, 1]
/// ```
///
/// (paper 3 section 4.1 draws `c_t`, which leaves the combined colour "the
/// average of the correct color and the color of the volume data"; this
/// removes that error wherever the clamp does not bind). Needs `a_t > a_v`.
pub fn point_colour(c_t: [f64; 3], a_t: f64, c_v: [f64; 3], a_v: f64) -> [f64; 3] {
    std::array::from_fn(|k| ((a_t * c_t[k] - a_v * c_v[k]) / (a_t - a_v)).clamp(0.0, 1.0))
}

/// `a_p = max(0, (a_t - a_v) / (1 - a_v))`: the opacity a point adds over a
/// volume of opacity `a_v` so that together they show `a_t`.
pub fn point_opacity(a_t: f64, a_v: f64) -> f64 {
    if a_t <= a_v || a_v >= 1.0 {
        0.0
    } else {
        (a_t - a_v) / (1.0 - a_v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_and_volume_together_give_the_original_opacity() {
        for (a_t, a_v) in [(0.5, 0.2), (0.9, 0.0), (0.3, 0.3), (1.0, 0.5), (1e-9, 0.0)] {
            let a_p = point_opacity(a_t, a_v);
            assert!((1.0 - (1.0 - a_v) * (1.0 - a_p) - a_t).abs() < 1e-12, "{a_t} {a_v}");
        }
        assert_eq!(point_opacity(0.2, 0.5), 0.0, "points never make the volume more transparent");
        assert_eq!(point_opacity(0.9, 1.0), 0.0);
    }

    #[test]
    fn point_and_volume_together_give_the_original_colour() {
        for (c_t, a_t, c_v, a_v) in [(0.8, 0.5, 0.6, 0.2), (0.3, 0.9, 0.5, 0.1), (1.0, 0.4, 0.0, 0.0)] {
            let a_p = point_opacity(a_t, a_v);
            let c_p = point_colour([c_t; 3], a_t, [c_v; 3], a_v)[0];
            // Premultiplied: the volume sample, then the point over it (front to back: under).
            let shown = a_v * c_v + (1.0 - a_v) * a_p * c_p;
            assert!((shown - a_t * c_t).abs() < 1e-12, "{c_t} {a_t} {c_v} {a_v}: {shown}");
        }
        // Where the exact colour is out of range, the clamp keeps it a colour.
        assert_eq!(point_colour([1.0; 3], 0.3, [0.0; 3], 0.29)[0], 1.0);
    }
}
