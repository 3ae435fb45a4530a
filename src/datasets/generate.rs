//! Sampling a dataset on a grid and converting it to a scalar type.
//!
//! Values are computed in `f64` in `[0, 1]` and mapped to the useful range of
//! the requested type ([`to_type_range`]), then rounded (saturating) for
//! integer types:
//!
//! | type     | stored value        | range            |
//! |----------|---------------------|------------------|
//! | u8       | `255 f`             | 0 ..= 255        |
//! | i8       | `127 f`             | 0 ..= 127        |
//! | u16      | `4095 f`            | 0 ..= 4095 (12-bit CT) |
//! | i16      | `4095 f - 1024`     | -1024 ..= 3071 (Hounsfield-like) |
//! | u32, i32 | `1e6 f`             | 0 ..= 1 000 000  |
//! | f32, f64 | `f`                 | 0 ..= 1          |

use super::dataset::Dataset;
use crate::base::error::{Error, Result};
use crate::base::limits::check_memory;
use crate::data::grid::{GridShape, ScalarType};
use crate::data::volume::{SampleBuf, Volume};
use rayon::prelude::*;

/// Checks, before anything is allocated, that `dims` samples of
/// `scalar_type` can be generated: at least 2 samples per axis, and the
/// bytes the generator holds at its peak,
///
/// ```text
/// bytes = 2 * nx * ny * nz * size_of(scalar_type)      (the z-slices and the joined array)
/// ```
///
/// computed without overflow, within the memory this process may use
/// ([`check_memory`]). Returns the volume's own bytes (half the peak).
pub fn check_generate(dims: [usize; 3], scalar_type: ScalarType) -> Result<u128> {
    if let Some(d) = dims.iter().find(|&&d| d < 2) {
        return Err(Error::InvalidArgument(format!(
            "a dataset of {d} samples along an axis is too small: use at least 2 samples per axis"
        )));
    }
    let bytes =
        dims.iter().try_fold(scalar_type.size() as u128, |acc, &d| acc.checked_mul(d as u128)).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "a {} x {} x {} {} dataset needs more than 2^128 bytes of memory: use a smaller --size",
                dims[0],
                dims[1],
                dims[2],
                scalar_type.name()
            ))
        })?;
    let what = format!("a {} x {} x {} {} dataset", dims[0], dims[1], dims[2], scalar_type.name());
    check_memory(2 * bytes, &what, "use a smaller --size or a smaller --type")?;
    Ok(bytes)
}

/// A cube of `size^3` samples of `dataset`; see [`generate_dims`].
pub fn generate(dataset: Dataset, size: usize, scalar_type: ScalarType) -> Volume {
    generate_dims(dataset, [size; 3], scalar_type)
}

/// `dims` samples of `dataset` as `scalar_type`, spacing 1, origin 0, the
/// array named after the dataset. Point `(i, j, k)` takes the value at
/// `t = (i / (nx - 1), j / (ny - 1), k / (nz - 1))` (0 on an axis of one sample).
/// Parallel over z-slices and deterministic.
pub fn generate_dims(dataset: Dataset, dims: [usize; 3], scalar_type: ScalarType) -> Volume {
    let field = |t: [f64; 3]| to_type_range(dataset.value(t), scalar_type);
    let samples = match scalar_type {
        ScalarType::U8 => SampleBuf::U8(fill(dims, &field, |v| v.round() as u8)),
        ScalarType::I8 => SampleBuf::I8(fill(dims, &field, |v| v.round() as i8)),
        ScalarType::U16 => SampleBuf::U16(fill(dims, &field, |v| v.round() as u16)),
        ScalarType::I16 => SampleBuf::I16(fill(dims, &field, |v| v.round() as i16)),
        ScalarType::U32 => SampleBuf::U32(fill(dims, &field, |v| v.round() as u32)),
        ScalarType::I32 => SampleBuf::I32(fill(dims, &field, |v| v.round() as i32)),
        ScalarType::F32 => SampleBuf::F32(fill(dims, &field, |v| v as f32)),
        ScalarType::F64 => SampleBuf::F64(fill(dims, &field, |v| v)),
    };
    Volume {
        samples,
        shape: GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] },
        components: 1,
        name: dataset.name().to_string(),
    }
}

/// Maps `f` in `[0, 1]` to the useful range of `scalar_type` (table in the module docs).
pub fn to_type_range(f: f64, scalar_type: ScalarType) -> f64 {
    match scalar_type {
        ScalarType::U8 => 255.0 * f,
        ScalarType::I8 => 127.0 * f,
        ScalarType::U16 => 4095.0 * f,
        ScalarType::I16 => 4095.0 * f - 1024.0,
        ScalarType::U32 | ScalarType::I32 => 1e6 * f,
        ScalarType::F32 | ScalarType::F64 => f,
    }
}

/// Box-normalised coordinate of sample `i` on an axis of `n` samples.
fn normalised(i: usize, n: usize) -> f64 {
    if n > 1 {
        i as f64 / (n - 1) as f64
    } else {
        0.0
    }
}

/// Evaluates `field` at every point, x fastest, one z-slice per rayon task
/// (rayon's `collect` keeps the order of the slices).
fn fill<T: Send>(
    dims: [usize; 3],
    field: &(dyn Fn([f64; 3]) -> f64 + Sync),
    convert: impl Fn(f64) -> T + Sync,
) -> Vec<T> {
    let [nx, ny, nz] = dims;
    let convert = &convert;
    (0..nz)
        .into_par_iter()
        .flat_map_iter(|k| {
            let tz = normalised(k, nz);
            (0..ny).flat_map(move |j| {
                let ty = normalised(j, ny);
                (0..nx).map(move |i| convert(field([normalised(i, nx), ty, tz])))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::Samples;

    fn range(v: &Volume) -> (f64, f64) {
        let g = v.grid(None).unwrap();
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        let [nx, ny, nz] = v.shape.dims;
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let x = g.value(i, j, k);
                    r = (r.0.min(x), r.1.max(x));
                }
            }
        }
        r
    }

    #[test]
    fn dims_and_length() {
        let v = generate_dims(Dataset::SheppLogan, [5, 7, 9], ScalarType::U16);
        assert_eq!(v.shape.dims, [5, 7, 9]);
        assert_eq!(v.samples.len(), 5 * 7 * 9);
        assert_eq!(v.samples.scalar_type(), ScalarType::U16);
        assert_eq!(v.name, "shepp-logan");
        assert_eq!(v.shape.spacing, [1.0; 3]);
        assert_eq!(v.shape.origin, [0.0; 3]);
    }

    #[test]
    fn values_stay_in_the_type_range() {
        for d in Dataset::ALL {
            let (lo, hi) = range(&generate(d, 17, ScalarType::F64));
            assert!(lo >= 0.0 && hi <= 1.0, "{d}: {lo}..{hi}");
            let (lo, hi) = range(&generate(d, 17, ScalarType::I16));
            assert!(lo >= -1024.0 && hi <= 3071.0, "{d}: {lo}..{hi}");
        }
        let (lo, hi) = range(&generate(Dataset::SheppLogan, 33, ScalarType::U8));
        assert_eq!((lo, hi), (0.0, 255.0));
        let (lo, hi) = range(&generate(Dataset::MarschnerLobb, 33, ScalarType::F64));
        assert!(lo < 0.1 && hi > 0.9, "Marschner-Lobb should span [0, 1]: {lo}..{hi}");
    }

    #[test]
    fn ramp_is_exactly_linear() {
        let v = generate(Dataset::Ramp, 17, ScalarType::F64);
        let g = v.grid(None).unwrap();
        for (i, j, k) in [(0, 0, 0), (3, 5, 7), (16, 16, 16), (16, 0, 9)] {
            let expected = (i as f64 + 2.0 * j as f64 + 5.0 * k as f64) / (8.0 * 16.0);
            assert_eq!(g.value(i, j, k), expected);
        }
        // Every second difference along every axis is exactly zero.
        for k in 0..17 {
            for j in 0..17 {
                for i in 1..16 {
                    assert_eq!(g.value(i + 1, j, k) - g.value(i, j, k), g.value(i, j, k) - g.value(i - 1, j, k));
                }
            }
        }
    }

    #[test]
    fn generation_is_deterministic_across_thread_counts() {
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let four = rayon::ThreadPoolBuilder::new().num_threads(4).build().unwrap();
        for d in Dataset::ALL {
            let a = one.install(|| generate(d, 20, ScalarType::F32));
            let b = four.install(|| generate(d, 20, ScalarType::F32));
            assert_eq!(a, b, "{d}");
        }
    }

    #[test]
    fn shepp_logan_skull_is_where_expected() {
        // y = -1 + 2 * 61 / 64 = 0.906: between the inner (0.874) and outer (0.92) y semi-axes.
        let v = generate(Dataset::SheppLogan, 65, ScalarType::U8);
        let g = v.grid(None).unwrap();
        assert_eq!(g.value(32, 61, 32), 255.0, "skull");
        assert_eq!(g.value(32, 32, 32), 51.0, "brain: 0.2 * 255");
        assert_eq!(g.value(0, 0, 0), 0.0, "air");
        let i16v = generate(Dataset::SheppLogan, 65, ScalarType::I16);
        assert!(matches!(i16v.samples.as_samples(), Samples::I16(s) if s[0] == -1024));
    }

    #[test]
    fn ramp_octree_is_one_homogeneous_root() {
        use crate::octree::{BuildOptions, VolumeOctree};
        for ty in [ScalarType::F32, ScalarType::F64] {
            let v = generate(Dataset::Ramp, 65, ty);
            let octree = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
            octree.validate().unwrap();
            let stats = octree.stats();
            assert_eq!((stats.node_count, stats.homogeneous_count), (1, 1), "{ty:?}");
        }
        // Marschner-Lobb is the opposite: refined down to the leaves.
        let v = generate(Dataset::MarschnerLobb, 65, ScalarType::F32);
        let octree = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
        octree.validate().unwrap();
        assert_eq!(octree.stats().terminal_count, 512);
    }

    #[test]
    fn constant_is_constant() {
        let v = generate(Dataset::Constant, 9, ScalarType::U16);
        assert_eq!(range(&v), (2048.0, 2048.0)); // round(0.5 * 4095)
    }
}
