//! The ray reductions of the blend modes besides Composite (maximum,
//! minimum, average, additive; formulas in [`crate::plan::blend`]): one
//! accumulator per pixel, fed by every brick's samples in any order, and its
//! resolve through the transfer function. The compositor and the reference
//! caster share it, so both take the same rule; only where the samples lie
//! differs.

use super::blend::Rgba;
use crate::plan::{Blend, BlendMode};

/// A pixel's reduction so far: the largest and smallest value, and the
/// weighted sum `sum_i w_i a(v_i) n(v_i)` with its weight `sum_i w_i`
/// (average: of the values it counts).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reduction {
    max: f64,
    min: f64,
    sum: f64,
    weight: f64,
}

impl Reduction {
    /// No sample yet.
    pub(crate) fn new() -> Reduction {
        Reduction { max: f64::NEG_INFINITY, min: f64::INFINITY, sum: 0.0, weight: 0.0 }
    }

    /// Takes the sample `v` standing for `w = l / d0` reference spacings;
    /// `lookup` is the transfer function (straight `[r, g, b, a]`). Maximum
    /// and minimum ignore `w`; NaN (no data) is no sample.
    #[inline]
    pub(crate) fn add(&mut self, blend: &Blend, v: f64, w: f64, lookup: impl Fn(f64) -> [f64; 4]) {
        if v.is_nan() {
            return;
        }
        match blend.mode {
            BlendMode::Mip => self.max = self.max.max(v),
            BlendMode::Minip => self.min = self.min.min(v),
            BlendMode::Average if !blend.averages(v) => {}
            BlendMode::Average | BlendMode::Additive => {
                self.sum += w * lookup(v)[3] * blend.normalise(v);
                self.weight += w;
            }
            BlendMode::Composite | BlendMode::Isosurface | BlendMode::Slice => {}
        }
    }

    /// The pixel (premultiplied): maximum and minimum `(a c, a)` of the
    /// extreme value, average `(g, g, g, 1)` with `g = sum / weight`,
    /// additive `(g, g, g, 1)` with `g = sum` when `crossed` (the ray crosses
    /// the volume's box), `g` clamped to `[0, 1]`; transparent without a sample.
    pub(crate) fn resolve(&self, blend: &Blend, crossed: bool, lookup: impl Fn(f64) -> [f64; 4]) -> Rgba {
        let extreme = |v: f64| {
            if v.is_finite() {
                let [r, g, b, a] = lookup(v);
                let a = a.clamp(0.0, 1.0);
                [a * r, a * g, a * b, a]
            } else {
                [0.0; 4]
            }
        };
        let grey = |g: f64| {
            let g = g.clamp(0.0, 1.0);
            [g, g, g, 1.0]
        };
        match blend.mode {
            BlendMode::Mip => extreme(self.max),
            BlendMode::Minip => extreme(self.min),
            BlendMode::Average if self.weight > 0.0 => grey(self.sum / self.weight),
            BlendMode::Additive if crossed => grey(self.sum),
            _ => [0.0; 4],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lookup(v: f64) -> [f64; 4] {
        [1.0, 0.5, 0.0, v / 2.0]
    }

    #[test]
    fn each_mode_reduces_as_vtk() {
        let values = [0.2, 0.8, f64::NAN, 0.4];
        let run = |mode, crossed| {
            let blend = Blend::new(mode, [0.0, 1.0]);
            let mut r = Reduction::new();
            for v in values {
                r.add(&blend, v, 2.0, lookup);
            }
            r.resolve(&blend, crossed, lookup)
        };
        assert_eq!(run(BlendMode::Mip, true), [0.4, 0.2, 0.0, 0.4]);
        assert_eq!(run(BlendMode::Minip, true), [0.1, 0.05, 0.0, 0.1]);
        let sum: f64 = 2.0 * (0.2 * 0.1 + 0.8 * 0.4 + 0.4 * 0.2);
        let avg = run(BlendMode::Average, true);
        assert!((avg[0] - sum / 6.0).abs() < 1e-15 && avg[3] == 1.0, "{avg:?}");
        let add = run(BlendMode::Additive, true);
        assert!((add[1] - sum).abs() < 1e-15 && add[3] == 1.0, "{add:?}");
        assert_eq!(run(BlendMode::Additive, false), [0.0; 4]);
        // No sample: nothing.
        for mode in [BlendMode::Mip, BlendMode::Minip, BlendMode::Average] {
            let blend = Blend::new(mode, [0.0, 1.0]);
            assert_eq!(Reduction::new().resolve(&blend, true, lookup), [0.0; 4]);
        }
        // AverageIPScalarRange: only 0.8 counts.
        let mut blend = Blend::new(BlendMode::Average, [0.0, 1.0]);
        blend.average_range = [0.5, 1.0];
        let mut r = Reduction::new();
        for v in values {
            r.add(&blend, v, 1.0, lookup);
        }
        assert!((r.resolve(&blend, true, lookup)[0] - 0.32).abs() < 1e-15);
    }
}
