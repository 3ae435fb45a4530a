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
use crate::data::planes::PlaneSource;
use crate::data::volume::{SampleBuf, Volume};
use rayon::prelude::*;

/// Checks, before anything is allocated, that `dims` samples of
/// `scalar_type` can be generated: at least 2 samples per axis, and the
/// volume's bytes,
///
/// ```text
/// bytes = nx * ny * nz * size_of(scalar_type)
/// ```
///
/// computed without overflow, within the memory this process may use
/// ([`check_memory`]): the generator writes every sample once, in place, and
/// whoever reads the volume back holds it whole. Returns the bytes.
pub fn check_generate(dims: [usize; 3], scalar_type: ScalarType) -> Result<u128> {
    if let Some(d) = dims.iter().find(|&&d| d < 2) {
        return Err(Error::InvalidArgument(format!(
            "a dataset of {d} samples along an axis is too small: use at least 2 samples per axis"
        )));
    }
    let bytes =
        dims.iter().try_fold(scalar_type.size() as u128, |acc, &d| acc.checked_mul(d as u128)).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "a {} x {} x {} {} dataset needs more than 2^128 bytes of memory: use a smaller --size (or --dims)",
                dims[0],
                dims[1],
                dims[2],
                scalar_type.name()
            ))
        })?;
    let what = format!("a {} x {} x {} {} dataset", dims[0], dims[1], dims[2], scalar_type.name());
    check_memory(bytes, &what, "use a smaller --size (or --dims) or a smaller --type")?;
    Ok(bytes)
}

/// A cube of `size^3` samples of `dataset`; see [`generate_dims`].
pub fn generate(dataset: Dataset, size: usize, scalar_type: ScalarType) -> Volume {
    generate_dims(dataset, [size; 3], scalar_type)
}

/// `dims` samples of `dataset` as `scalar_type`, spacing 1, origin 0, the
/// array named after the dataset. Point `(i, j, k)` takes the value at
/// `t = (i / (nx - 1), j / (ny - 1), k / (nz - 1))` (0 on an axis of one sample).
/// Written in place at the native type, one z-slice per rayon task: deterministic.
pub fn generate_dims(dataset: Dataset, dims: [usize; 3], scalar_type: ScalarType) -> Volume {
    Volume {
        samples: generate_slab(dataset, dims, scalar_type, 0..dims[2]),
        shape: GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] },
        components: 1,
        name: dataset.name().to_string(),
    }
}

/// The z-slices `slices` of [`generate_dims`]'s volume, x fastest: the same
/// values, so a volume generated slab by slab ([`generate_slabs`]) is the
/// whole volume's bytes in order.
pub fn generate_slab(
    dataset: Dataset,
    dims: [usize; 3],
    scalar_type: ScalarType,
    slices: std::ops::Range<usize>,
) -> SampleBuf {
    let n = dims[0] * dims[1] * slices.len();
    let k0 = slices.start;
    let d = dataset;
    match scalar_type {
        ScalarType::U8 => SampleBuf::U8(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::U8).round() as u8)),
        ScalarType::I8 => SampleBuf::I8(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::I8).round() as i8)),
        ScalarType::U16 => SampleBuf::U16(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::U16).round() as u16)),
        ScalarType::I16 => SampleBuf::I16(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::I16).round() as i16)),
        ScalarType::U32 => SampleBuf::U32(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::U32).round() as u32)),
        ScalarType::I32 => SampleBuf::I32(fill(d, dims, k0, n, |v| to_type_range(v, ScalarType::I32).round() as i32)),
        ScalarType::F32 => SampleBuf::F32(fill(d, dims, k0, n, |v| v as f32)),
        ScalarType::F64 => SampleBuf::F64(fill(d, dims, k0, n, |v| v)),
    }
}

/// [`generate_dims`]'s volume as a [`PlaneSource`]: any planes, computed
/// when asked, so a pass over z never holds the volume.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DatasetPlanes {
    /// The dataset.
    pub dataset: Dataset,
    /// Samples per axis (at least 2 each).
    pub dims: [usize; 3],
    /// The samples' type.
    pub scalar_type: ScalarType,
}

impl PlaneSource for DatasetPlanes {
    fn shape(&self) -> GridShape {
        GridShape { dims: self.dims, spacing: [1.0; 3], origin: [0.0; 3] }
    }
    fn scalar_type(&self) -> ScalarType {
        self.scalar_type
    }
    fn read_planes(&self, z: std::ops::Range<usize>) -> Result<SampleBuf> {
        if z.start > z.end || z.end > self.dims[2] {
            return Err(Error::InvalidArgument(format!("planes {z:?} are outside the dataset's {}", self.dims[2])));
        }
        let plane = self.dims[0] as u128 * self.dims[1] as u128;
        check_memory(
            plane * z.len() as u128 * self.scalar_type.size() as u128,
            &format!("{} planes of {}x{}", z.len(), self.dims[0], self.dims[1]),
            "use a smaller --size",
        )?;
        Ok(generate_slab(self.dataset, self.dims, self.scalar_type, z))
    }
}

/// Bytes of one slab of [`generate_slabs`] (at least one z-slice).
pub const SLAB_BYTES: usize = 64 << 20;

/// Generates [`generate_dims`]'s volume slab by slab, in z order, handing
/// each slab (whole z-slices, about [`SLAB_BYTES`]) to `sink`: a writer
/// holds one slab, never the volume. Stops at `sink`'s first error.
pub fn generate_slabs<E>(
    dataset: Dataset,
    dims: [usize; 3],
    scalar_type: ScalarType,
    sink: &mut dyn FnMut(SampleBuf) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    let slice_bytes = (dims[0] * dims[1] * scalar_type.size()).max(1);
    let per_slab = (SLAB_BYTES / slice_bytes).clamp(1, dims[2].max(1));
    let mut k = 0;
    while k < dims[2] {
        let end = (k + per_slab).min(dims[2]);
        sink(generate_slab(dataset, dims, scalar_type, k..end))?;
        k = end;
    }
    Ok(())
}
/// Maps `f` in `[0, 1]` to the useful range of `scalar_type` (table in the module docs).
#[inline(always)]
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

/// Evaluates `dataset` at the `n` points from z-slice `k0` on, x fastest,
/// a row at a time ([`Dataset::row`]), converted by `convert` (the
/// [`to_type_range`] map and the rounding) into a buffer of the final type:
/// one z-slice per rayon task, each writing its own part of the buffer (the
/// order does not depend on the threads).
fn fill<T: Send + Copy + Default>(
    dataset: Dataset,
    dims: [usize; 3],
    k0: usize,
    n: usize,
    convert: impl Fn(f64) -> T + Sync,
) -> Vec<T> {
    let [nx, ny, nz] = dims;
    let mut out = vec![T::default(); n];
    out.par_chunks_mut((nx * ny).max(1)).enumerate().for_each_init(
        || vec![0.0f64; nx],
        |values, (dk, slice)| {
            let tz = normalised(k0 + dk, nz);
            for (j, row) in slice.chunks_mut(nx.max(1)).enumerate() {
                dataset.row(normalised(j, ny), tz, values);
                for (v, &f) in row.iter_mut().zip(values.iter()) {
                    *v = convert(f);
                }
            }
        },
    );
    out
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
    fn slabs_are_the_volume_in_order() {
        let dims = [7, 5, 9];
        let whole = generate_dims(Dataset::Vessels, dims, ScalarType::U16);
        let mut joined = Vec::new();
        let mut slabs = 0;
        generate_slabs::<()>(Dataset::Vessels, dims, ScalarType::U16, &mut |s| {
            slabs += 1;
            if let SampleBuf::U16(v) = s {
                joined.extend(v);
            }
            Ok(())
        })
        .unwrap();
        assert_eq!(SampleBuf::U16(joined), whole.samples);
        assert_eq!(slabs, 1);
        let part = generate_slab(Dataset::Vessels, dims, ScalarType::U16, 3..5);
        assert_eq!(part.as_samples().len(), 7 * 5 * 2);
        assert!(
            matches!((&part, &whole.samples), (SampleBuf::U16(p), SampleBuf::U16(w)) if p[..] == w[3 * 35..5 * 35])
        );
    }

    #[test]
    fn constant_is_constant() {
        let v = generate(Dataset::Constant, 9, ScalarType::U16);
        assert_eq!(range(&v), (2048.0, 2048.0)); // round(0.5 * 4095)
    }
}
