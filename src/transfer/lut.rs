//! A lookup table of a transfer function, for the compositor's inner loop.
//!
//! The function's points span `[lo, hi]` (the smallest and largest point
//! value of colour and opacity); the table splits it into `N` cells of width
//! `h = (hi - lo) / N` and holds the exact `[r, g, b, opacity]` at the cell
//! ends `v_k = lo + k h`. Inside a cell `[v_k, v_{k+1}]`, `u = (v - lo) / h`:
//!
//! ```text
//! f(v) = f(v_k) + (f(v_{k+1}) - f(v_k)) (u - k)      (linear interpolation)
//! ```
//!
//! A cell holding no point of either function (nor one at its ends) is
//! clean: both functions are linear over it, so the interpolation is exact
//! up to rounding, `|lookup - eval| <= 1e-6` per channel (the `f32` cell
//! values). A cell with a point in it (a kink or a step), and any value
//! outside `[lo, hi]`, is evaluated exactly by [`TransferFunction::eval`].

use super::function::TransferFunction;

/// Cells of the table.
pub(crate) const CELLS: usize = 4096;

/// The lookup table of a transfer function (see the module documentation).
pub(crate) struct Lut<'a> {
    tf: &'a TransferFunction,
    lo: f64,
    /// `1 / h`; 0 when the points span no interval (everything exact).
    inv_h: f64,
    /// `f(v_k)`, `k = 0 ..= CELLS`.
    ends: Vec<[f32; 4]>,
    /// Per cell: no point inside or on its ends.
    clean: Vec<bool>,
}

impl<'a> Lut<'a> {
    /// The table of `tf`.
    pub(crate) fn new(tf: &'a TransferFunction) -> Lut<'a> {
        let xs: Vec<f64> = tf.colors().iter().map(|p| p.0).chain(tf.opacities().iter().map(|p| p.0)).collect();
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let h = (hi - lo) / CELLS as f64;
        if !(h > 0.0 && h.is_finite() && (1.0 / h).is_finite()) {
            return Lut { tf, lo, inv_h: 0.0, ends: Vec::new(), clean: Vec::new() };
        }
        let inv_h = 1.0 / h;
        let ends = (0..=CELLS).map(|k| tf.eval(if k == CELLS { hi } else { lo + k as f64 * h })).collect();
        let mut clean = vec![true; CELLS];
        for x in xs {
            // The cells whose closed range may hold x (one either side for rounding).
            let k = ((x - lo) * inv_h).floor() as i64;
            for c in k - 1..=k + 1 {
                if (0..CELLS as i64).contains(&c) {
                    clean[c as usize] = false;
                }
            }
        }
        Lut { tf, lo, inv_h, ends, clean }
    }

    /// Straight `[r, g, b, opacity]` at `value` (see the module documentation).
    #[inline(always)]
    pub(crate) fn eval(&self, value: f64) -> [f64; 4] {
        let u = (value - self.lo) * self.inv_h;
        // Saturating; a u32 cast (of u >= 0) converts in one instruction either way.
        let k = u as u32;
        if u >= 0.0 && self.clean.get(k as usize) == Some(&true) {
            let (a, b, t) = (self.ends[k as usize], self.ends[k as usize + 1], u - k as f64);
            return std::array::from_fn(|c| a[c] as f64 + (b[c] as f64 - a[c] as f64) * t);
        }
        self.tf.eval(value).map(|c| c as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within 1e-6 of the exact function everywhere: across the range, at
    /// and next to every point (kinks and steps), and outside it.
    #[test]
    fn lookup_matches_eval() {
        let step = TransferFunction::new(
            vec![(0.0, [0.0, 0.0, 1.0]), (0.3, [0.2, 0.9, 0.1]), (1.0, [1.0, 0.0, 0.0])],
            vec![(0.2, 0.0), (0.4, 0.0), (0.6, 1.0), (0.6, 0.5), (0.8, 0.0)],
        )
        .unwrap();
        for tf in [TransferFunction::ramp(0.0, 1.0), TransferFunction::ramp(-3.0, 1200.0), step] {
            let lut = Lut::new(&tf);
            let (lo, hi) = (lut.lo, lut.lo + CELLS as f64 / lut.inv_h);
            let mut values: Vec<f64> =
                (0..200_000).map(|i| lo - 0.1 * (hi - lo) + 1.2 * (hi - lo) * i as f64 / 2e5).collect();
            for x in tf.colors().iter().map(|p| p.0).chain(tf.opacities().iter().map(|p| p.0)) {
                values.extend([
                    x,
                    x.next_down(),
                    x.next_up(),
                    x - 1e-9,
                    x + 1e-9,
                    x - 0.5 / lut.inv_h,
                    x + 0.5 / lut.inv_h,
                ]);
            }
            for v in values {
                let (a, b) = (lut.eval(v), tf.eval(v));
                for c in 0..4 {
                    assert!((a[c] - b[c] as f64).abs() <= 1e-6, "{v}: {a:?} vs {b:?}");
                }
            }
            assert!(lut.clean.iter().filter(|&&c| c).count() > CELLS / 2);
        }
        // One value only: no interval, every lookup exact.
        let flat = TransferFunction::new(vec![(2.0, [0.5; 3])], vec![(2.0, 0.25)]).unwrap();
        let lut = Lut::new(&flat);
        for v in [1.0, 2.0, 3.0] {
            assert_eq!(lut.eval(v), flat.eval(v).map(|c| c as f64));
        }
    }
}
