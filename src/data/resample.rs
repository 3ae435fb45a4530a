//! Resampling a grid by magnification factors with cubic interpolation, as
//! VTK's `vtkImageResample` does with `InterpolationMode` `VTK_RESLICE_CUBIC`
//! (Imaging/Core: `vtkImageResample::RequestInformation`, then
//! `vtkImageReslice`'s permutation path with `vtkImageInterpolator`'s
//! separable cubic weights and its clamping border): the volume
//! `vtkSmartVolumeMapper` hands its low-resolution GPU mapper.
//!
//! Geometry, per axis `a` of `n_a` samples at spacing `s_a`, factor `f_a > 0`:
//!
//! ```text
//! extent'_a  = [ceil(0 f_a), floor((n_a - 1) f_a)]      n'_a = floor((n_a - 1) f_a) + 1
//! spacing'_a = s_a / f_a                                 origin' = origin
//! x          = i s'_a / s_a                              the input index of output sample i
//! ```
//!
//! Values: `x = i0 + t`, `i0 = floor(x)` by VTK's fixed-point floor (`x`
//! rounded to a multiple of `2^-16` first), the four taps `i0 - 1 ..= i0 + 2`
//! clamped to `[0, n_a - 1]` with Catmull-Rom weights (Keys' cubic, `a = -1/2`):
//!
//! ```text
//! w0 = -t/2 (t - 1)^2         w1 = ((3t - 2) t/2 - 1)(t - 1)
//! w2 = -((3t - 4) t - 1) t/2   w3 = t/2 t (t - 1)
//! v' = sum_k wz_k sum_j wy_j (wx_0 v_0 + wx_1 v_1 + wx_2 v_2 + wx_3 v_3)     (that order, in f64)
//! ```
//!
//! An axis with fewer than 4 samples folds the weights of the clamped taps
//! onto its samples; an axis whose `s'_a / s_a` is a whole number takes the
//! one sample `i0` (plain subsampling, VTK's "output pixels lie exactly on
//! top of the input pixels"). Integer types clamp `v'` to their range and
//! round it half up (VTK's fixed-point round); floating types keep it (f32:
//! rounded to f32). The weights reproduce linear data exactly wherever all
//! four taps lie inside the grid. Output planes are computed in parallel,
//! each voxel on its own: the result does not depend on the thread count.

use crate::base::error::{Error, Result};
use crate::base::limits::check_memory;
use crate::data::grid::{Grid, GridShape, Sample, Samples};
use crate::data::volume::{SampleBuf, Volume};
use rayon::prelude::*;

/// The bias of VTK's fixed-point floor and round (`vtkInterpolationMath`):
/// `x + 103079215104` has a resolution of `2^-16`.
const FLOOR_BIAS: f64 = 103_079_215_104.0;
/// `VTK_INTERPOLATE_FLOOR_TOL` (`2^-17`).
const FLOOR_TOL: f64 = 7.629_394_531_25e-6;

/// VTK's `vtkInterpolationMath::Floor`: `(floor(x), x - floor(x))` of `x`
/// rounded to a multiple of `2^-16`.
fn vtk_floor(x: f64) -> (i64, f64) {
    let y = x + (FLOOR_BIAS + FLOOR_TOL);
    let i = y as i64;
    (i - FLOOR_BIAS as i64, y - i as f64)
}

/// VTK's `vtkInterpolationMath::Round`: half up, after rounding `x` to a multiple of `2^-16`.
fn vtk_round(x: f64) -> f64 {
    let y = x + (FLOOR_BIAS + 0.5 + FLOOR_TOL);
    ((y as i64) - FLOOR_BIAS as i64) as f64
}

/// The Catmull-Rom weights of fraction `t` (module documentation; `vtkTricubicInterpWeights`).
fn cubic_weights(t: f64) -> [f64; 4] {
    let (fm1, fd2, ft3) = (t - 1.0, t * 0.5, t * 3.0);
    [-fd2 * fm1 * fm1, ((ft3 - 2.0) * fd2 - 1.0) * fm1, -((ft3 - 4.0) * t - 1.0) * fd2, t * fd2 * fm1]
}

/// The shape of `shape` resampled by `factors` (module documentation).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for a factor that is not finite and positive,
/// or one that leaves fewer than 2 samples on an axis.
pub fn resampled_shape(shape: &GridShape, factors: [f64; 3]) -> Result<GridShape> {
    let mut out = *shape;
    for (a, &f) in factors.iter().enumerate() {
        if !(f.is_finite() && f > 0.0) {
            return Err(Error::InvalidArgument(format!(
                "magnification factor {f} on axis {a}: give a finite number > 0 (1 keeps the samples)"
            )));
        }
        let last = ((shape.dims[a] - 1) as f64 * f).floor();
        if !(1.0..=(isize::MAX as f64 / 8.0)).contains(&last) {
            return Err(Error::InvalidArgument(format!(
                "magnification factor {f} leaves {} samples on axis {a} of {}: a grid needs at least 2 \
                 (give a larger factor)",
                last.max(-1.0) + 1.0,
                shape.dims[a]
            )));
        }
        out.dims[a] = last as usize + 1;
        out.spacing[a] = shape.spacing[a] / f;
    }
    out.check(1)?;
    Ok(out)
}

/// `grid` resampled by `factors` with VTK's cubic interpolation, at its own
/// scalar type, one component (module documentation).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for bad factors ([`resampled_shape`]) or when
/// the output would not fit in the memory left.
pub fn resample_cubic(grid: &Grid<'_>, factors: [f64; 3]) -> Result<Volume> {
    let shape = resampled_shape(grid.shape(), factors)?;
    let scalar = grid.samples().scalar_type();
    check_memory(
        (shape.point_count() as u128) * scalar.size() as u128,
        &format!("resampling to {:?} {} samples", shape.dims, scalar.name()),
        "give smaller magnification factors",
    )?;
    let (from, to) = (grid.shape(), &shape);
    let axes: [Taps; 3] = std::array::from_fn(|a| {
        // vtkImageReslice's index matrix: input (1 / s) times output (s', o'), one axis of it.
        let inv = 1.0 / from.spacing[a];
        Taps::new(from.dims[a], to.dims[a], inv * to.spacing[a], inv * to.origin[a] + -from.origin[a] / from.spacing[a])
    });
    let input = Input { dims: grid.dims(), components: grid.components(), component: grid.component() };
    let samples = match grid.samples() {
        Samples::U8(d) => SampleBuf::U8(input.resample(d, &axes)),
        Samples::I8(d) => SampleBuf::I8(input.resample(d, &axes)),
        Samples::U16(d) => SampleBuf::U16(input.resample(d, &axes)),
        Samples::I16(d) => SampleBuf::I16(input.resample(d, &axes)),
        Samples::U32(d) => SampleBuf::U32(input.resample(d, &axes)),
        Samples::I32(d) => SampleBuf::I32(input.resample(d, &axes)),
        Samples::F32(d) => SampleBuf::F32(input.resample(d, &axes)),
        Samples::F64(d) => SampleBuf::F64(input.resample(d, &axes)),
    };
    Ok(Volume { samples, shape, components: 1, name: format!("resampled {:?}", factors) })
}

/// A sample type written back from the interpolated `f64` as `vtkImageReslice` does.
trait Resliced: Sample {
    fn from_resliced(v: f64) -> Self;
}

macro_rules! resliced_int {
    ($($t:ty),*) => {$(
        impl Resliced for $t {
            #[inline]
            fn from_resliced(v: f64) -> $t {
                // Clamp to the type's range, then round (vtkResliceClamp).
                vtk_round(v.max(<$t>::MIN as f64).min(<$t>::MAX as f64)) as $t
            }
        }
    )*};
}
resliced_int!(u8, i8, u16, i16, u32, i32);

impl Resliced for f32 {
    #[inline]
    fn from_resliced(v: f64) -> f32 {
        v as f32
    }
}

impl Resliced for f64 {
    #[inline]
    fn from_resliced(v: f64) -> f64 {
        v
    }
}

/// One axis's taps: for each output sample its input indices and weights.
struct Taps {
    /// Taps per output sample: 4, fewer on an axis of fewer samples, 1 when subsampling.
    step: usize,
    index: Vec<[usize; 4]>,
    weight: Vec<[f64; 4]>,
}

impl Taps {
    /// The taps of `m` output samples at input index `x = shift + i scale` over `n` input samples.
    fn new(n: usize, m: usize, scale: f64, shift: f64) -> Taps {
        let last = n as i64 - 1;
        let clamp = |i: i64| i.clamp(0, last) as usize;
        let step = if vtk_floor(scale).1 == 0.0 && vtk_floor(shift).1 == 0.0 { 1 } else { n.min(4) };
        let (mut index, mut weight) = (Vec::with_capacity(m), Vec::with_capacity(m));
        for i in 0..m {
            let (i0, t) = vtk_floor(shift + i as f64 * scale);
            if step == 1 {
                index.push([clamp(i0); 4]);
                weight.push([1.0, 0.0, 0.0, 0.0]);
                continue;
            }
            let g = cubic_weights(t);
            let taps = [i0 - 1, i0, i0 + 1, i0 + 2].map(clamp);
            if step == 4 {
                index.push(taps);
                weight.push(g);
            } else {
                // Fewer than 4 samples: each sample takes the weights of the taps clamped onto it.
                let mut folded = [0.0; 4];
                for (tap, w) in taps.iter().zip(g) {
                    folded[*tap] += w;
                }
                index.push([0, 1, 2.min(n - 1), 3.min(n - 1)]);
                weight.push(folded);
            }
        }
        Taps { step, index, weight }
    }
}

/// The input's layout: dims and the component read.
struct Input {
    dims: [usize; 3],
    components: usize,
    component: usize,
}

impl Input {
    fn resample<T: Resliced>(&self, data: &[T], axes: &[Taps; 3]) -> Vec<T> {
        let [mx, my, mz] = [axes[0].index.len(), axes[1].index.len(), axes[2].index.len()];
        let (nx, nxy, c) = (self.dims[0], self.dims[0] * self.dims[1], self.components);
        let at = |i: usize| data[i * c + self.component].to_f64();
        let mut out = vec![T::from_resliced(0.0); mx * my * mz];
        out.par_chunks_mut(mx * my).enumerate().for_each(|(k, plane)| {
            let (iz, wz) = (&axes[2].index[k], &axes[2].weight[k]);
            for (j, row) in plane.chunks_mut(mx).enumerate() {
                let (iy, wy) = (&axes[1].index[j], &axes[1].weight[j]);
                for (i, v) in row.iter_mut().enumerate() {
                    let (ix, wx) = (&axes[0].index[i], &axes[0].weight[i]);
                    let mut result = 0.0;
                    for z in 0..axes[2].step {
                        if wz[z] == 0.0 {
                            continue;
                        }
                        for y in 0..axes[1].step {
                            let base = iz[z] * nxy + iy[y] * nx;
                            let x = |l: usize| if l < axes[0].step { wx[l] * at(base + ix[l]) } else { 0.0 };
                            result += wz[z] * wy[y] * (x(0) + x(1) + x(2) + x(3));
                        }
                    }
                    *v = T::from_resliced(result);
                }
            }
        });
        out
    }
}

#[cfg(test)]
#[path = "resample_tests.rs"]
mod tests;
