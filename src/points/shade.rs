//! The colour and opacity each point adds (paper 3, sections 3.3 and 4.1),
//! averaged over the point's voxel.
//!
//! A point stands for the error of one sample, but a renderer's rays do not
//! pass through samples: they see the trilinear field between them. A point
//! is drawn over its voxel, the cube `C_p` of one sample spacing around it
//! (its footprint is one sample spacing across, see [`super::footprint`]), so
//! what it must add is what the data's field has there beyond the low
//! resolution's, on average over the cube:
//!
//! ```text
//! A_t = mean over C_p of alpha(f),    C_t = mean over C_p of alpha(f) c(f)      (premultiplied)
//! A_v = mean over C_p of alpha(T_f),  C_v = mean over C_p of alpha(T_f) c(T_f)
//! ```
//!
//! (`f` the full-resolution trilinear field, the midpoint rule on 3 x 3 x 3
//! sub-cubes), and the point adds
//!
//! ```text
//! a_p = max(0, (A_t - A_v) / (1 - A_v)),    c_p = (C_t - C_v) / (A_t - A_v)  clamped to [0, 1]
//! ```
//!
//! ([`super::opacity::point_opacity`], [`super::opacity::point_colour`]). Taking
//! `alpha(f(p))` at the sample alone (section 4.1 read literally)
//! over-corrects structures about a voxel thin under a steep transfer
//! function: the field of a one-sample line is at its peak only on the line,
//! and a whole voxel of the peak's opacity is too much. Measured
//! (docs/BENCHMARKS.md): on the 64^3 phantom the voxel mean takes stride 4 +
//! points from 8 % to 45 % below stride 4 alone, on the mapper's test bars
//! from 40 % to 55 %; on the 256^3 phantom at 512 x 512 it reads 10 % above
//! the sample rule (40 % instead of 46 % below stride 4 alone).
//!
//! The shade depends on the transfer function, so renderers compute it per
//! table, from the grid the points were made from.

use super::opacity::{point_colour, point_opacity};
use super::set::PointSet;
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::transfer::lut::Lut;
use crate::transfer::TransferFunction;
use rayon::prelude::*;

/// What a point adds: straight colour and opacity (0: nothing, not drawn).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointShade {
    /// Straight colour `c_p`.
    pub rgb: [f32; 3],
    /// Opacity `a_p` over one sample spacing.
    pub alpha: f32,
}

/// Sub-cube centres per axis, in sample spacings from the point.
const OFFSETS: [f64; 3] = [-1.0 / 3.0, 0.0, 1.0 / 3.0];

/// The shade of every point of `set` (see the module documentation) under
/// `tf`, from `grid` (the grid the points were made from). Parallel over
/// points; each is computed on its own.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when `grid` is not the grid of `set`.
pub fn shade(grid: &Grid<'_>, set: &PointSet, tf: &TransferFunction) -> Result<Vec<PointShade>> {
    let dims = grid.shape().dims;
    if dims != set.dims {
        return Err(Error::InvalidArgument(format!(
            "the points were made for a {:?} grid, not this {:?} one: generate them from this grid",
            set.dims, dims
        )));
    }
    Ok(grid.visit(Kernel { set, lut: &Lut::new(tf) }))
}

/// The error each point corrects: the mean of `f - T_f` over its voxel (the
/// 27 sub-cube centres), what its voxel-mean shade adds back. A centre where
/// either is NaN (no data) adds 0: a point shades only where both exist.
pub fn voxel_mean_errors(grid: &Grid<'_>, set: &PointSet) -> Vec<f64> {
    struct Means<'a>(&'a PointSet);
    impl GridVisitor for Means<'_> {
        type Output = Vec<f64>;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<f64> {
            let set = self.0;
            set.points
                .par_iter()
                .map(|p| {
                    let c = p.ijk.map(usize::from);
                    let (full, low) = (sub_cube_values(&g, c, 1), sub_cube_values(&g, c, set.factor));
                    full.iter().zip(&low).map(|(f, t)| f - t).filter(|d| !d.is_nan()).sum::<f64>() / 27.0
                })
                .collect()
        }
    }
    grid.visit(Means(set))
}

/// The shading of every point, on the typed grid.
struct Kernel<'a> {
    set: &'a PointSet,
    lut: &'a Lut<'a>,
}

impl GridVisitor for Kernel<'_> {
    type Output = Vec<PointShade>;

    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<PointShade> {
        let set = self.set;
        // Premultiplied colour and opacity of a value.
        let rgba = |v: f64| {
            let [r, gr, b, a] = self.lut.eval(v);
            [r * a, gr * a, b * a, a]
        };
        set.points
            .par_iter()
            .map(|p| {
                let c = p.ijk.map(usize::from);
                // The field at the 27 sub-cube centres, full resolution and T_f.
                let (full, low) = (sub_cube_values(&g, c, 1), sub_cube_values(&g, c, set.factor));
                let (mut t, mut v) = ([0.0f64; 4], [0.0f64; 4]);
                for (&fv, &lv) in full.iter().zip(&low) {
                    let (st, sv) = (rgba(fv), rgba(lv));
                    for k in 0..4 {
                        t[k] += st[k] / 27.0;
                        v[k] += sv[k] / 27.0;
                    }
                }
                let alpha = point_opacity(t[3], v[3]);
                if alpha <= 0.0 {
                    return PointShade { rgb: [0.0; 3], alpha: 0.0 };
                }
                let straight = |s: [f64; 4]| [0, 1, 2].map(|k| if s[3] > 0.0 { s[k] / s[3] } else { 0.0 });
                let rgb = point_colour(straight(t), t[3], straight(v), v[3]);
                PointShade { rgb: rgb.map(|c| c as f32), alpha: alpha as f32 }
            })
            .collect()
    }
}

/// One axis of T_s at the sub-cube centres `c + OFFSETS[o]` (clamped to
/// the axis): the (at most 3) lattice nodes involved, clamped to the last
/// sample as [`crate::octree::trilinear`] clamps them, and per offset the
/// weight of each node, `1 - t` and `t` on its bracket `[x0, x0 + s]`.
fn axis(c: usize, s: usize, n: usize) -> ([usize; 3], [[f64; 3]; 3]) {
    let x = |o: f64| (c as f64 + o).clamp(0.0, (n - 1) as f64);
    let base = (x(OFFSETS[0]) / s as f64).floor() as usize * s;
    let nodes = [0, 1, 2].map(|i| (base + i * s).min(n - 1));
    let mut weights = [[0.0; 3]; 3];
    for (o, w) in OFFSETS.iter().zip(&mut weights) {
        let x = x(*o);
        let x0 = (x / s as f64).floor() as usize * s;
        let t = (x - x0 as f64) / s as f64;
        let i = (x0 - base) / s;
        w[i] += 1.0 - t;
        w[i + 1] += t;
    }
    (nodes, weights)
}

/// T_s (s = 1: the full-resolution field) at the 27 sub-cube centres of the
/// voxel of sample `c`, x fastest: the trilinear interpolation of the
/// stride-`s` lattice, as a separable sum over at most 3 x 3 x 3 nodes.
fn sub_cube_values<T: Sample>(g: &TypedGrid<'_, T>, c: [usize; 3], s: usize) -> [f64; 27] {
    let [(nx, wx), (ny, wy), (nz, wz)] = [0, 1, 2].map(|a| axis(c[a], s, g.dims[a]));
    // Contract z, then y, then x.
    let mut zs = [[[0.0; 3]; 3]; 3]; // [oz][j][i]
    for (k, &z) in nz.iter().enumerate() {
        for (j, &y) in ny.iter().enumerate() {
            for (i, &x) in nx.iter().enumerate() {
                let value = g.at(x, y, z);
                for oz in 0..3 {
                    zs[oz][j][i] += wz[oz][k] * value;
                }
            }
        }
    }
    let mut out = [0.0; 27];
    for oz in 0..3 {
        for oy in 0..3 {
            let row: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| wy[oy][j] * zs[oz][j][i]).sum());
            for ox in 0..3 {
                out[ox + 3 * (oy + 3 * oz)] = (0..3).map(|i| wx[ox][i] * row[i]).sum();
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{GridShape, Samples};
    use crate::points::opacity::point_opacity;
    use crate::points::{generate, PointOptions, PointSelect};

    fn grid(data: &[f32], n: usize) -> Grid<'_> {
        let shape = GridShape { dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3] };
        Grid::new(Samples::F32(data), shape, 1, None).unwrap()
    }

    /// Samples per axis of [`planes`].
    const PLANES_N: usize = 9;

    /// Every odd plane x = 2i + 1 at 0.75 over a background of 0.25, 9^3
    /// samples: T_2 misses the planes entirely.
    fn planes() -> Vec<f32> {
        let n = PLANES_N;
        (0..n * n * n).map(|i| if (i % n) % 2 == 1 { 0.75 } else { 0.25 }).collect()
    }

    fn ramp() -> TransferFunction {
        TransferFunction::new(vec![(0.0, [0.2, 0.4, 0.6]), (1.0, [1.0, 0.8, 0.2])], vec![(0.0, 0.0), (1.0, 0.5)])
            .unwrap()
    }

    #[test]
    fn a_plane_of_points_shades_as_its_voxel_mean() {
        // Every odd plane x = 2i + 1 raised by 0.5 over a background of 0.25:
        // T_2 misses the raise entirely and every sample of those planes is
        // a point. Around an inner point, f is uniform along y and z and
        // falls off linearly along x to the planes beside it.
        let (n, data) = (PLANES_N, planes());
        let g = grid(&data, n);
        let set = generate(&g, &PointOptions::new(2, PointSelect::Threshold(0.1))).unwrap();
        assert_eq!(set.points.len(), 4 * n * n);
        let shades = shade(&g, &set, &ramp()).unwrap();
        // A linear opacity ramp: the voxel mean of alpha is alpha of the voxel mean.
        // Across x, f falls linearly from 0.75 to 0.25 + 0.5 / 3 at the sub-cube centres +-1/3.
        let mean = (0.75 + 2.0 * (0.25 + 0.5 * (1.0 - 1.0 / 3.0))) / 3.0;
        let expected = point_opacity(0.5 * mean, 0.5 * 0.25);
        for (p, s) in set.points.iter().zip(&shades) {
            if p.ijk.iter().all(|&c| c > 0 && usize::from(c) < n - 1) {
                assert!((f64::from(s.alpha) - expected).abs() < 1e-5, "{:?}: {} vs {expected}", p.ijk, s.alpha);
            }
        }
    }

    #[test]
    fn a_voxel_mean_error_is_the_tent_averaged_error() {
        // The planes of the test above: e = 0.5 on the plane, falling to 0
        // at the planes beside it; over the voxel (x offsets 0, +-1/3) the
        // mean is (0.5 + 2 * 0.5 * 2/3) / 3. A rating of e^2 would be 1.65x m^2.
        let (n, data) = (PLANES_N, planes());
        let g = grid(&data, n);
        let set = generate(&g, &PointOptions::new(2, PointSelect::Threshold(0.1))).unwrap();
        let means = voxel_mean_errors(&g, &set);
        let want = (0.5 + 2.0 * 0.5 * 2.0 / 3.0) / 3.0;
        for (p, m) in set.points.iter().zip(&means) {
            assert!((m - want).abs() < 1e-9, "{:?}: {m} vs {want}", p.ijk);
        }
        let mass = crate::points::PointMass::with_errors(&set, 4, &means).unwrap();
        let (count, positive, removable) = mass.in_box([0; 3], [n - 1; 3]);
        assert_eq!((count, positive), (set.points.len(), set.points.len()));
        let eta = crate::points::mass::point_efficiency(2);
        assert!((removable - eta * set.points.len() as f64 * want * want / 0.25).abs() < 1e-6, "{removable}");
        let e = crate::points::PointMass::with_errors(&set, 4, &means[1..]).unwrap_err().to_string();
        assert!(e.contains("one per point"), "{e}");
    }

    #[test]
    fn a_one_sample_spike_adds_less_than_its_peak() {
        // One sample at 1 in a field of 0: the trilinear field is at its peak
        // only at the sample; the voxel mean of a steep opacity is far below it.
        let n = 9;
        let mut data = vec![0.0f32; n * n * n];
        data[5 + n * (5 + n * 5)] = 1.0;
        let g = grid(&data, n);
        let set = generate(&g, &PointOptions::new(2, PointSelect::Threshold(0.1))).unwrap();
        assert_eq!(set.points.len(), 1);
        let steep = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(0.0, 0.0), (0.5, 0.0), (1.0, 0.8)]).unwrap();
        let s = shade(&g, &set, &steep).unwrap()[0];
        assert!(s.alpha > 0.0 && f64::from(s.alpha) < 0.25 * 0.8, "{s:?}");
        assert!(s.rgb.iter().all(|&c| (0.0..=1.0).contains(&c)));
    }

    /// T_s at a fractional index the direct way: bracket each axis, 8 lerps.
    fn t_s_direct(g: &Grid<'_>, s: usize, x: [f64; 3]) -> f64 {
        let dims = g.shape().dims;
        let b = |a: usize| {
            let x0 = (x[a] / s as f64).floor() as usize * s;
            (x0, (x0 + s).min(dims[a] - 1), (x[a] - x0 as f64) / s as f64)
        };
        let ((x0, x1, tx), (y0, y1, ty), (z0, z1, tz)) = (b(0), b(1), b(2));
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let w = |xa| {
            let v0 = lerp(g.value(xa, y0, z0), g.value(xa, y0, z1), tz);
            let v1 = lerp(g.value(xa, y1, z0), g.value(xa, y1, z1), tz);
            lerp(v0, v1, ty)
        };
        lerp(w(x0), w(x1), tx)
    }

    struct SubCube([usize; 3], usize);
    impl GridVisitor for SubCube {
        type Output = [f64; 27];
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> [f64; 27] {
            sub_cube_values(&g, self.0, self.1)
        }
    }

    #[test]
    fn sub_cube_values_are_the_trilinear_field() {
        // 10 x 7 x 9 samples (not multiples of the strides), a non-linear field.
        let dims = [10usize, 7, 9];
        let data: Vec<f32> = (0..dims[0] * dims[1] * dims[2])
            .map(|i| {
                let (x, y, z) = (i % dims[0], i / dims[0] % dims[1], i / (dims[0] * dims[1]));
                ((x * x + 3 * y) as f32).sin() + (z as f32 * 0.7).cos()
            })
            .collect();
        let shape = GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] };
        let g = Grid::new(Samples::F32(&data), shape, 1, None).unwrap();
        for s in [1, 2, 4, 8] {
            for c in [[0, 0, 0], [9, 6, 8], [4, 3, 4], [8, 1, 5], [1, 5, 7]] {
                let got = g.visit(SubCube(c, s));
                for (n, v) in got.iter().enumerate() {
                    let o = [n % 3, n / 3 % 3, n / 9].map(|k| OFFSETS[k]);
                    let x = std::array::from_fn(|a| (c[a] as f64 + o[a]).clamp(0.0, (dims[a] - 1) as f64));
                    let want = t_s_direct(&g, s, x);
                    assert!((v - want).abs() < 1e-12, "s {s} c {c:?} offset {o:?}: {v} vs {want}");
                }
            }
        }
    }

    #[test]
    fn points_of_another_grid_are_refused() {
        let data = vec![0.0f32; 5 * 5 * 5];
        let mut spike = vec![0.0f32; 9 * 9 * 9];
        spike[5 + 9 * (5 + 9 * 5)] = 1.0;
        let set = generate(&grid(&spike, 9), &PointOptions::new(2, PointSelect::Threshold(0.1))).unwrap();
        let e = shade(&grid(&data, 5), &set, &ramp()).unwrap_err().to_string();
        assert!(e.contains("generate them from this grid"), "{e}");
    }
}
