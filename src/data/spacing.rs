//! The sample spacings every renderer shares: the reference spacing `d0`
//! (the opacity unit and the full-resolution slice spacing) and the slice
//! spacing of a brick of a given stride.
//!
//! ```text
//! d0          = max(min_a s_a, max_a s_a / MAX_ANISOTROPY)
//! slice(s)    = min(s, c) d0,   c = the largest power of two <= max(1, E / (MIN_SLICES d0))
//! E           = min over axes of the volume's world extent (n_a - 1) s_a
//! ```
//!
//! Why the bounds: `d0` is the smallest spacing, but never below
//! `1 / MAX_ANISOTROPY` of the largest, so the slices across a volume (and
//! the reference ray caster's steps) are at most `MAX_ANISOTROPY sqrt(3)`
//! times its samples per axis, whatever its spacings (a `1e-7` spacing on one
//! axis would otherwise ask for `1e7` slices per unit of the others).
//! Slicing at the stride keeps one slice per texel layer, but a brick's
//! slices are a Riemann sum of the ray's integral: its count is right up to
//! one slice. A coarse brick of a smooth or constant part (a whole constant
//! volume is one brick of two texels per axis) would get one or two slices
//! across the volume, and a picture that depends on where the lattice cuts
//! it; capping the spacing at `c d0` keeps at least `MIN_SLICES` slices
//! across the volume's thinnest side. Both spacings scale with the spacings:
//! a volume at spacing `1e-6` or `1e6` is sliced like one at spacing 1.

use crate::data::grid::GridShape;

/// The largest spacing over the reference spacing `d0`.
pub const MAX_ANISOTROPY: f64 = 16.0;

/// Slices a brick of any stride keeps across the volume's thinnest side.
pub const MIN_SLICES: f64 = 16.0;

/// `d0 = max(min_a s_a, max_a s_a / MAX_ANISOTROPY)` (module documentation).
pub fn reference_spacing(shape: &GridShape) -> f64 {
    let lo = shape.spacing.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = shape.spacing.iter().copied().fold(0.0, f64::max);
    lo.max(hi / MAX_ANISOTROPY)
}

/// The largest stride sliced at its own spacing, `c` of the module
/// documentation: a power of two, at least 1.
pub fn max_slice_stride(shape: &GridShape) -> usize {
    let d0 = reference_spacing(shape);
    let extent =
        (0..3).map(|a| (shape.dims[a].saturating_sub(1)) as f64 * shape.spacing[a]).fold(f64::INFINITY, f64::min);
    let k = extent / (MIN_SLICES * d0);
    if k.is_nan() || k < 2.0 {
        return 1;
    }
    // 2^floor(log2 k), with k below 2^63 (k <= dims / MIN_SLICES * MAX_ANISOTROPY).
    let k = k.min(2f64.powi(62)) as u64;
    1usize << (63 - k.leading_zeros())
}

/// `slice(stride) = min(stride, c) d0` (module documentation).
pub fn slice_spacing(shape: &GridShape, stride: usize) -> f64 {
    stride.min(max_slice_stride(shape)) as f64 * reference_spacing(shape)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(dims: [usize; 3], spacing: [f64; 3]) -> GridShape {
        GridShape { dims, spacing, origin: [0.0; 3] }
    }

    #[test]
    fn isotropic_volumes_keep_the_smallest_spacing_and_their_strides() {
        let s = shape([257; 3], [0.5; 3]);
        assert_eq!(reference_spacing(&s), 0.5);
        assert_eq!(max_slice_stride(&s), 16); // 256 cells / 16 slices
        assert_eq!(slice_spacing(&s, 4), 2.0);
        assert_eq!(slice_spacing(&s, 64), 8.0);
    }

    #[test]
    fn thin_volumes_slice_at_full_resolution() {
        assert_eq!(max_slice_stride(&shape([32; 3], [1.0; 3])), 1);
        assert_eq!(max_slice_stride(&shape([2, 2, 1 << 20], [1.0; 3])), 1);
        assert_eq!(slice_spacing(&shape([32; 3], [1.0; 3]), 32), 1.0);
    }

    #[test]
    fn spacings_scale_and_anisotropy_is_bounded() {
        for scale in [1e-6, 1.0, 1e6] {
            let s = shape([129; 3], [scale; 3]);
            assert_eq!(reference_spacing(&s), scale);
            assert_eq!(max_slice_stride(&s), 8);
        }
        let thin = shape([33; 3], [1.0, 1.0, 1e-7]);
        assert_eq!(reference_spacing(&thin), 1.0 / MAX_ANISOTROPY);
        assert_eq!(max_slice_stride(&thin), 1);
        let ct = shape([65; 3], [0.5, 0.5, 3.0]); // ratio 6: d0 is the smallest spacing
        assert_eq!(reference_spacing(&ct), 0.5);
    }
}
