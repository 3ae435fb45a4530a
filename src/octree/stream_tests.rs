//! The streaming build against the in-core build: the same octree, bit for bit.

use super::stream_build::{build_streaming_into, row_planes};
use super::{BuildOptions, Layout, VolumeOctree};
use crate::base::error::Error;
use crate::data::grid::{Grid, ScalarType};
use crate::data::planes::{GridPlanes, PlaneSource};
use crate::data::volume::{SampleBuf, Volume};
use crate::datasets::{generate_dims, Dataset};

/// Every array of the octree as bits (NaN and signed zeros compared exactly).
fn bits(o: &VolumeOctree) -> (Vec<u64>, Vec<u64>, Vec<u32>, Vec<u32>) {
    (
        o.min.iter().map(|v| v.to_bits()).collect(),
        o.max.iter().map(|v| v.to_bits()).collect(),
        o.errors.iter().map(|v| v.to_bits()).collect(),
        o.squared_errors.iter().map(|v| v.to_bits()).collect(),
    )
}

fn same_octree(grid: &Grid<'_>, leaf: usize, what: &str) {
    let options = BuildOptions { leaf_size: leaf };
    let in_core = VolumeOctree::build(grid, &options).unwrap();
    let streamed = VolumeOctree::build_streaming(&GridPlanes(*grid), &options, &mut |_| true).unwrap();
    assert_eq!(streamed.octree.layout, in_core.layout, "{what} leaf {leaf}");
    assert_eq!(streamed.octree.error_offset, in_core.error_offset, "{what} leaf {leaf}");
    assert!(bits(&streamed.octree) == bits(&in_core), "{what} leaf {leaf}: the octrees differ");
    assert_eq!(streamed.nan_count, grid.nan_count(), "{what}");
}

#[test]
fn datasets_types_and_odd_shapes_give_the_in_core_octree() {
    let cases = [
        (Dataset::SheppLogan, [37, 20, 53], ScalarType::U8),
        (Dataset::Vessels, [40, 33, 70], ScalarType::F32),
        (Dataset::MarschnerLobb, [21, 19, 23], ScalarType::U16),
        (Dataset::Sphere, [17, 17, 17], ScalarType::I16),
        (Dataset::Ramp, [9, 5, 33], ScalarType::F64),
        (Dataset::Constant, [6, 7, 8], ScalarType::I32),
        (Dataset::SheppLogan, [2, 2, 2], ScalarType::U8),
        (Dataset::Vessels, [2, 2, 41], ScalarType::F32),
        (Dataset::Sphere, [3, 2, 65], ScalarType::I8),
        (Dataset::MarschnerLobb, [30, 2, 3], ScalarType::U32),
    ];
    for (dataset, dims, ty) in cases {
        let v = generate_dims(dataset, dims, ty);
        let grid = v.grid(None).unwrap();
        for leaf in [2, 4, 8, 16, 32] {
            same_octree(&grid, leaf, &format!("{dataset:?} {dims:?} {}", ty.name()));
        }
    }
}

#[test]
fn nan_holes_and_extreme_values_give_the_in_core_octree() {
    let dims = [23, 18, 37];
    let base = generate_dims(Dataset::SheppLogan, dims, ScalarType::F64);
    let SampleBuf::F64(values) = &base.samples else { unreachable!() };
    for (k, ty) in [(1.0, ScalarType::F32), (1.0, ScalarType::F64), (1e300, ScalarType::F64), (1e-310, ScalarType::F64)]
    {
        let mut scaled: Vec<f64> = values.iter().map(|v| v * k).collect();
        // Holes: a NaN block and scattered NaN.
        for (i, v) in scaled.iter_mut().enumerate() {
            let [x, y, z] = [i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1])];
            if (x < 5 && y < 6 && z > 20) || i % 97 == 3 {
                *v = f64::NAN;
            }
        }
        let v = Volume::new(SampleBuf::from_f64(&scaled, ty), dims, "holes");
        let grid = v.grid(None).unwrap();
        assert!(grid.nan_count() > 0);
        for leaf in [2, 4, 8, 16, 32] {
            same_octree(&grid, leaf, &format!("x{k} {}", ty.name()));
        }
    }
}

#[test]
fn every_plane_reaches_the_sink_once_in_order() {
    let v = generate_dims(Dataset::Vessels, [19, 11, 46], ScalarType::U16);
    let grid = v.grid(None).unwrap();
    let source = GridPlanes(grid);
    let mut seen = Vec::new();
    let mut most = 0;
    build_streaming_into::<u16>(&source, &BuildOptions { leaf_size: 4 }, &mut |_| true, &mut |z, stack| {
        most = most.max(stack.held().count());
        for k in z {
            let want = crate::data::planes::into_vec::<u16>(source.read_planes(k..k + 1)?).unwrap();
            assert_eq!(stack.plane(k), &want[..], "plane {k}");
            seen.push(k);
        }
        Ok(())
    })
    .unwrap();
    assert_eq!(seen, (0..46).collect::<Vec<_>>());
    // The stack held no more than the most planes one row reads, far fewer than the volume's.
    let layout = Layout::new([19, 11, 46], 4).unwrap();
    let bound = (0..12).map(|cz| row_planes(&layout, cz * 4, (cz * 4 + 4).min(45)).len()).max().unwrap();
    assert!(most <= bound && bound < 46 / 2, "{most} planes held, bound {bound}");
}

#[test]
fn bad_input_is_refused_and_progress_can_cancel() {
    // One sample wide: the same error as the in-core grid.
    let v = Volume::new(SampleBuf::U8(vec![1; 9]), [1, 1, 9], "thin");
    let e = VolumeOctree::build_streaming(&Thin(&v), &BuildOptions::default(), &mut |_| true).unwrap_err();
    assert!(matches!(e, Error::DimsTooSmall { .. }), "{e}");
    // An infinity is named with its position; NaN only is no data.
    let mut values = vec![0.5f32; 4 * 4 * 4];
    values[2 + 4 * (1 + 4 * 3)] = f32::INFINITY;
    let v = Volume::new(SampleBuf::F32(values), [4, 4, 4], "inf");
    let e = VolumeOctree::build_streaming(&Thin(&v), &BuildOptions { leaf_size: 2 }, &mut |_| true).unwrap_err();
    assert!(matches!(e, Error::NonFinite { first_ijk: [2, 1, 3], .. }), "{e}");
    let v = Volume::new(SampleBuf::F32(vec![f32::NAN; 27]), [3, 3, 3], "nan");
    let e = VolumeOctree::build_streaming(&Thin(&v), &BuildOptions { leaf_size: 2 }, &mut |_| true).unwrap_err();
    assert_eq!(e, Error::NoData { count: 27 });
    let v = generate_dims(Dataset::Sphere, [9, 9, 33], ScalarType::U8);
    let mut calls = 0;
    let e =
        VolumeOctree::build_streaming(&GridPlanes(v.grid(None).unwrap()), &BuildOptions { leaf_size: 2 }, &mut |_| {
            calls += 1;
            calls < 3
        })
        .unwrap_err();
    assert_eq!((e, calls), (Error::Cancelled, 3));
}

/// A volume's planes without the grid's checks (as a generator or a store hands them out).
struct Thin<'a>(&'a Volume);

impl PlaneSource for Thin<'_> {
    fn shape(&self) -> crate::data::grid::GridShape {
        self.0.shape
    }
    fn scalar_type(&self) -> ScalarType {
        self.0.samples.scalar_type()
    }
    fn read_planes(&self, z: std::ops::Range<usize>) -> crate::base::error::Result<SampleBuf> {
        let plane = self.0.shape.dims[0] * self.0.shape.dims[1];
        Ok(match &self.0.samples {
            SampleBuf::U8(v) => SampleBuf::U8(v[z.start * plane..z.end * plane].to_vec()),
            SampleBuf::F32(v) => SampleBuf::F32(v[z.start * plane..z.end * plane].to_vec()),
            other => panic!("{:?} is not used here", other.scalar_type()),
        })
    }
}
