//! The central-difference gradient of a brick's texture (the rule of
//! [`crate::render::shade`]) with the texels its seven trilinear samples
//! share read once.
//!
//! The samples `F(u ± e_a)` one texel from `u` have `u`'s fractional
//! weights `t`, so they interpolate the same z-pairs, y-pairs and x-pairs
//! one texel over. With `C(dx, dy, dz)` the texel at `i0 + (dx, dy, dz)`,
//! `i0 = floor(u)`, and the interpolation order of
//! [`Texture::at_texel`] (z, then y, then x):
//!
//! ```text
//! Z(dx, dy, dz) = lerp(C(dx, dy, dz), C(dx, dy, dz + 1), t_z)
//! Y(dx, dy, dz) = lerp(Z(dx, dy, dz), Z(dx, dy + 1, dz), t_y)
//! F(u)          = lerp(Y(0, 0, 0), Y(1, 0, 0), t_x)
//! F(u + e_x)    = lerp(Y(1, 0, 0), Y(2, 0, 0), t_x)
//! F(u + e_y)    = lerp(Y(0, 1, 0), Y(1, 1, 0), t_x)
//! F(u + e_z)    = lerp(Y(0, 0, 1), Y(1, 0, 1), t_x)
//! ```
//!
//! and likewise at `-1`. These are the operations [`Texture::at_texel`]
//! does at `u ± e_a`, so the gradient is the one of
//! [`crate::render::shade::gradient`] over `at_texel` up to rounding (the
//! fraction of `u + 1` may round apart from that of `u`). It computes one
//! address instead of six and clamps nothing. A point whose
//! neighbours reach a clamped face (`i0 - 1 < 0` or `i0 + 2 > n - 1` on an
//! axis) takes the general rule.
//!
//! The compositor finds a sample's cell once ([`TexelPoint`]) for both its
//! value and its gradient, and each brick's `1 / (2 h)` once ([`Steps`]).

use super::{Texel, Texture};
use crate::octree::trilinear::{lerp, lerp_scaled};
use crate::render::shade::gradient;

/// A brick's lattice step: the world length `h` of one texel step per
/// axis, and the central difference's factor `1 / (2 h)`, made once per
/// brick rather than divided by at every sample.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Steps {
    h: [f64; 3],
    inv_2h: [f64; 3],
}

impl Steps {
    /// The steps of world length `h` per axis.
    pub(crate) fn new(h: [f64; 3]) -> Steps {
        Steps { h, inv_2h: h.map(|h| 0.5 / h) }
    }
}

/// A sample's texel coordinates `u` with its clamp-free cell (see
/// [`Texture::point`]), found once for the sample's value and gradient.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TexelPoint {
    /// The texel coordinates.
    pub(crate) u: [f64; 3],
    /// The cell's first texel's offset, the pitches and the weights `t`,
    /// when `u` lies in `[1, n - 3]` on every axis.
    cell: Option<(usize, [usize; 3], [f64; 3])>,
}

impl<S: Texel> Texture<S> {
    /// The point `u` with its clamp-free cell, if any.
    #[inline(always)]
    pub(crate) fn point(&self, u: [f64; 3]) -> TexelPoint {
        TexelPoint { u, cell: self.inner_cell(u) }
    }

    /// [`Self::at_texel`] at `p`: from its cell when it has one (inside,
    /// where the clamp changes nothing: the same value).
    #[inline(always)]
    pub(crate) fn value_at(&self, p: &TexelPoint) -> f64 {
        match p.cell {
            Some((base, pitch, t)) => self.cell_value(base, pitch, t),
            None => self.at_texel(p.u),
        }
    }

    /// The gradient `g_a = (F(u + e_a) - F(u - e_a)) / (2 h_a)` at texel
    /// point `p` ([`crate::render::shade`]), `steps` the world length of one
    /// texel step per axis (module documentation). The usual case, finite
    /// lattice differences in a clamp-free cell, is inlined into the caller;
    /// the others ([`Self::gradient_apart`]) are not.
    #[inline(always)]
    pub(crate) fn gradient_at(&self, p: &TexelPoint, steps: &Steps) -> [f64; 3] {
        if let (true, false, Some((base, pitch, t))) = (self.lattice_finite, self.lattice.is_empty(), p.cell) {
            return self.lattice_gradient::<true>(base, pitch, t, steps);
        }
        self.gradient_apart(p.u, steps)
    }

    /// The cell of `u` (its first texel's offset, the pitches, the weights
    /// `t`) when `u` lies in `[1, n - 3]` on every axis, where the six
    /// neighbours `u ± e_a` need no clamp; `None` elsewhere.
    #[inline(always)]
    fn inner_cell(&self, u: [f64; 3]) -> Option<(usize, [usize; 3], [f64; 3])> {
        let mut i0 = [0usize; 3];
        let mut t = [0.0; 3];
        for a in 0..3 {
            // last = n - 1.
            if !(u[a] >= 1.0 && u[a] < self.last[a] - 1.0) {
                return None;
            }
            let i = u[a] as u32;
            (i0[a], t[a]) = (i as usize, u[a] - i as f64);
        }
        let pitch = [1, self.n[0], self.n[0] * self.n[1]];
        Some((i0[0] + pitch[1] * i0[1] + pitch[2] * i0[2], pitch, t))
    }

    /// [`Self::gradient_at`] near the faces (the general rule), from lattice
    /// differences that are not all finite, or from the texels' shared reads.
    #[inline(never)]
    fn gradient_apart(&self, u: [f64; 3], steps: &Steps) -> [f64; 3] {
        let Some((base, pitch, t)) = self.inner_cell(u) else {
            return gradient(|v| self.at_texel(v), u, steps.h);
        };
        if !self.lattice.is_empty() {
            return if self.lattice_finite {
                self.lattice_gradient::<true>(base, pitch, t, steps)
            } else {
                self.lattice_gradient::<false>(base, pitch, t, steps)
            };
        }
        // Texels from C(-1, -1, -1) to C(2, 2, 2): one bounds check.
        let lo = base - pitch[0] - pitch[1] - pitch[2];
        let d = &self.data[lo..=base + 2 * (pitch[0] + pitch[1] + pitch[2])];
        let at = |dx: isize, dy: isize, dz: isize| {
            let o = (base - lo) as isize + dx + dy * pitch[1] as isize + dz * pitch[2] as isize;
            d[o as usize].get()
        };
        let z = |dx, dy, dz| lerp(at(dx, dy, dz), at(dx, dy, dz + 1), t[2]);
        let y = |dx, dy, dz| lerp(z(dx, dy, dz), z(dx, dy + 1, dz), t[1]);
        let x = |dy, dz, from| lerp(y(from, dy, dz), y(from + 1, dy, dz), t[0]);
        let y00 = [y(-1, 0, 0), y(0, 0, 0), y(1, 0, 0), y(2, 0, 0)];
        let up_down = [
            (lerp(y00[2], y00[3], t[0]), lerp(y00[0], y00[1], t[0])),
            (x(1, 0, 0), x(-1, 0, 0)),
            (x(0, 1, 0), x(0, -1, 0)),
        ];
        let step = if S::CODED { self.step } else { 1.0 };
        [0, 1, 2].map(|a| step * (up_down[a].0 - up_down[a].1) * steps.inv_2h[a])
    }

    /// The lattice differences `D_a(i) = C(i + e_a) - C(i - e_a)` of
    /// every texel with both neighbours on every axis (0 on the outermost
    /// layer, which [`Self::gradient_at`] never reads), as `f32`.
    ///
    /// Trilinear interpolation is linear in the texels and `F(u ± e_a)`
    /// share `u`'s weights, so
    ///
    /// ```text
    /// F(u + e_a) - F(u - e_a) = sum_corners w_c (C(c + e_a) - C(c - e_a)) = trilinear(D_a)(u)
    /// ```
    ///
    /// and the gradient is one three-channel interpolation instead of six.
    pub(crate) fn lattice_differences(&self) -> Vec<[f32; 3]> {
        let n = self.n;
        let pitch = [1, n[0], n[0] * n[1]];
        let mut out = vec![[0.0f32; 3]; self.data.len()];
        // A code's differences in values: times the decoding's step.
        let step = if S::CODED { self.step } else { 1.0 };
        for k in 1..n[2].saturating_sub(1) {
            for j in 1..n[1].saturating_sub(1) {
                for i in 1..n[0].saturating_sub(1) {
                    let o = i + pitch[1] * j + pitch[2] * k;
                    out[o] = pitch.map(|p| (step * (self.data[o + p].get() - self.data[o - p].get())) as f32);
                }
            }
        }
        out
    }

    /// [`Self::gradient_at`] from the [`Self::lattice_differences`]: their
    /// trilinear interpolation at the cell of texel `base` with weights `t`,
    /// over `2 h`. `FINITE` when every difference is: `b - a` of two finite
    /// `f32` cannot overflow an `f64`, so [`lerp`]'s overflow test is left
    /// out (the same values, branch-free).
    #[inline(always)]
    fn lattice_gradient<const FINITE: bool>(
        &self,
        base: usize,
        pitch: [usize; 3],
        t: [f64; 3],
        steps: &Steps,
    ) -> [f64; 3] {
        let d = &self.lattice[base..=base + pitch[0] + pitch[1] + pitch[2]];
        // Written out as always-inlined functions: closures and array maps
        // here are not inlined, and this is the inner loop of shading.
        #[inline(always)]
        fn mix<const FINITE: bool>(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
            if FINITE {
                [lerp_scaled(a[0], b[0], t), lerp_scaled(a[1], b[1], t), lerp_scaled(a[2], b[2], t)]
            } else {
                [lerp(a[0], b[0], t), lerp(a[1], b[1], t), lerp(a[2], b[2], t)]
            }
        }
        #[inline(always)]
        fn corner(d: &[[f32; 3]], o: usize) -> [f64; 3] {
            let c = d[o];
            [f64::from(c[0]), f64::from(c[1]), f64::from(c[2])]
        }
        #[inline(always)]
        fn w<const FINITE: bool>(d: &[[f32; 3]], o: usize, pitch: [usize; 3], t: [f64; 3]) -> [f64; 3] {
            let v0 = mix::<FINITE>(corner(d, o), corner(d, o + pitch[2]), t[2]);
            let v1 = mix::<FINITE>(corner(d, o + pitch[1]), corner(d, o + pitch[1] + pitch[2]), t[2]);
            mix::<FINITE>(v0, v1, t[1])
        }
        let g = mix::<FINITE>(w::<FINITE>(d, 0, pitch, t), w::<FINITE>(d, pitch[0], pitch, t), t[0]);
        let k = steps.inv_2h;
        [g[0] * k[0], g[1] * k[1], g[2] * k[2]]
    }
}

#[cfg(test)]
mod tests {
    use super::super::Texture;
    use super::Steps;
    use crate::render::shade::gradient;

    /// A bordered-size texture of `n` texels per axis holding an uneven field.
    fn ramp_texture(n: [usize; 3]) -> Texture<f32> {
        let data = (0..n[0] * n[1] * n[2])
            .map(|i| {
                let (x, y, z) = (i % n[0], (i / n[0]) % n[1], i / (n[0] * n[1]));
                ((x * x) as f32).sin() + 0.3 * (y * z) as f32 - 0.7 * (z as f32).sqrt()
            })
            .collect();
        let last = n.map(|n| (n - 1) as f64);
        Texture {
            lo: [0; 3],
            hi: n.map(|n| n - 3),
            stride: 1,
            n,
            border: 1,
            last,
            data,
            step: 1.0,
            bias: 0.0,
            lattice: Vec::new(),
            lattice_finite: true,
        }
    }

    /// The lattice differences give the general rule's gradient to the
    /// rounding of their `f32` storage, inside, at and near every face; the
    /// branch-free interpolation of finite differences gives `lerp`'s values,
    /// and a point's cell the clamped read's value, bit for bit.
    #[test]
    fn the_lattice_differences_give_the_general_gradient() {
        let mut texture = ramp_texture([7, 6, 8]);
        texture.lattice = texture.lattice_differences();
        // The same differences, interpolated with lerp's overflow test.
        let tested = Texture { lattice_finite: false, ..texture.clone() };
        let h = [0.5, 1.0, 2.0];
        for k in 0..=28 {
            for j in 0..=20 {
                for i in 0..=24 {
                    let u = [i as f64 * 0.25, j as f64 * 0.25 + 0.01, k as f64 * 0.25];
                    let p = texture.point(u);
                    let fast = texture.gradient_at(&p, &Steps::new(h));
                    assert_eq!(fast, tested.gradient_at(&p, &Steps::new(h)), "at {u:?}");
                    // The value from the point's cell is the clamped read's.
                    assert_eq!(texture.value_at(&p).to_bits(), texture.at_texel(u).to_bits(), "at {u:?}");
                    let general = gradient(|v| texture.at_texel(v), u, h);
                    for a in 0..3 {
                        assert!(
                            (fast[a] - general[a]).abs() <= 1e-6 * (1.0 + general[a].abs()),
                            "at {u:?}: {fast:?} against {general:?}"
                        );
                    }
                }
            }
        }
    }

    /// The general rule to rounding (`u + 1` and `u` round their fractions
    /// apart), inside, at and near every face.
    #[test]
    fn the_shared_reads_give_the_general_gradient() {
        let texture = ramp_texture([7, 6, 8]);
        let h = [0.5, 1.0, 2.0];
        let mut checked = 0;
        for k in 0..=28 {
            for j in 0..=20 {
                for i in 0..=24 {
                    let u = [i as f64 * 0.25, j as f64 * 0.25 + 0.01, k as f64 * 0.25];
                    let fast = texture.gradient_at(&texture.point(u), &Steps::new(h));
                    let general = gradient(|v| texture.at_texel(v), u, h);
                    for a in 0..3 {
                        assert!((fast[a] - general[a]).abs() <= 1e-12, "at {u:?}: {fast:?} against {general:?}");
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 10_000);
    }
}
