//! The leaf kernel's fast path against the general kernel (the reference):
//! every leaf's min, max, raw, squared and hole statistics equal bit for bit,
//! and so the built octrees, on odd sizes, every leaf size, NaN holes,
//! constant and extreme volumes and several scalar types.

use hybrid_octree::grid::{Grid, GridVisitor, Sample, Samples, TypedGrid};
use hybrid_octree::octree::leaf_stats::{leaf_stats, LeafStats, Scratch};
use hybrid_octree::octree::trilinear::kernel_scale;
use hybrid_octree::octree::{BuildOptions, KernelPath, Layout, VolumeOctree};
use proptest::prelude::*;

/// The statistics of every leaf by one kernel path.
struct Leaves<'l> {
    layout: &'l Layout,
    scale: f64,
    path: KernelPath,
}

impl GridVisitor for Leaves<'_> {
    type Output = Vec<LeafStats>;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Vec<LeafStats> {
        let leaf = self.layout.leaf_level();
        let d = self.layout.level_dims(leaf);
        let mut scratch = Scratch::default();
        let mut out = Vec::new();
        for z in 0..d[2] {
            for y in 0..d[1] {
                for x in 0..d[0] {
                    let (lo, hi) = self.layout.node_box(leaf, [x, y, z]);
                    out.push(leaf_stats(&g, self.layout, lo, hi, self.scale, self.path, &mut scratch));
                }
            }
        }
        out
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Asserts that both paths give the same leaves and octree; returns the octree.
fn same_on_both_paths(grid: &Grid<'_>, leaf_size: usize) -> VolumeOctree {
    let options = BuildOptions { leaf_size };
    let fast = VolumeOctree::build_with_kernel(grid, &options, KernelPath::Fast, &mut |_| true).unwrap();
    let general = VolumeOctree::build_with_kernel(grid, &options, KernelPath::General, &mut |_| true).unwrap();
    fast.validate().unwrap();
    assert_eq!(fast, general, "octrees differ (dims {:?}, leaf {leaf_size})", grid.dims());
    let (lo, hi) = fast.value_range();
    let layout = fast.layout();
    let scale = kernel_scale(lo, hi);
    let a = grid.visit(Leaves { layout, scale, path: KernelPath::Fast });
    let b = grid.visit(Leaves { layout, scale, path: KernelPath::General });
    for (i, (a, b)) in a.iter().zip(&b).enumerate() {
        let at = format!("leaf {i} (dims {:?}, leaf size {leaf_size})", grid.dims());
        assert_eq!((a.min.to_bits(), a.max.to_bits()), (b.min.to_bits(), b.max.to_bits()), "{at}: min/max");
        assert_eq!(bits(&a.raw), bits(&b.raw), "{at}: raw errors");
        assert_eq!(bits(&a.squared), bits(&b.squared), "{at}: squared errors");
        assert_eq!(bits(&a.holes), bits(&b.holes), "{at}: holes");
    }
    fast
}

/// A smooth field with detail everywhere (no two neighbours equal), like VTK's Wavelet.
fn wavelet(dims: [usize; 3], i: usize) -> f64 {
    let (x, y, z) = (i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1]));
    let (x, y, z) = (x as f64 * 0.37, y as f64 * 0.29, z as f64 * 0.23);
    60.0 * x.sin() + 10.0 * (2.0 * y).cos() + 30.0 * (x * y * 0.1 + z).sin() + (x - y + z) * 0.5
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// Random odd and even sizes, every leaf size, plateaus and (sometimes) NaN holes.
    #[test]
    fn fast_path_equals_general_kernel(
        (dims, data) in (2usize..=37, 2usize..=29, 2usize..=23).prop_flat_map(|(x, y, z)| {
            let n = x * y * z;
            (Just([x, y, z]), prop::collection::vec(prop_oneof![
                8 => -100.0f32..100.0, 1 => Just(0.0f32), 1 => Just(-0.0f32), 1 => Just(1.0f32)], n))
        }),
        leaf_log2 in 1u32..6,
        nan_every in prop_oneof![Just(0usize), 50usize..400],
    ) {
        let mut data = data;
        if nan_every > 0 {
            for (i, v) in data.iter_mut().enumerate() {
                if (i * 7919) % nan_every == 0 {
                    *v = f32::NAN;
                }
            }
        }
        if data.iter().any(|v| !v.is_nan()) {
            let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
            same_on_both_paths(&grid, 1 << leaf_log2);
        }
    }
}

#[test]
fn smooth_field_in_every_scalar_type() {
    let dims = [67, 50, 45];
    let n = dims[0] * dims[1] * dims[2];
    let f: Vec<f64> = (0..n).map(|i| wavelet(dims, i)).collect();
    let f32s: Vec<f32> = f.iter().map(|&v| v as f32).collect();
    let u8s: Vec<u8> = f.iter().map(|&v| (v + 128.0).clamp(0.0, 255.0) as u8).collect();
    let i16s: Vec<i16> = f.iter().map(|&v| (v * 100.0) as i16).collect();
    for leaf_size in [4, 8, 16, 32] {
        let octree = same_on_both_paths(&Grid::scalar(Samples::F64(&f), dims).unwrap(), leaf_size);
        assert!(octree.node(octree.root()).error(0) > 0.0);
        same_on_both_paths(&Grid::scalar(Samples::F32(&f32s), dims).unwrap(), leaf_size);
        same_on_both_paths(&Grid::scalar(Samples::U8(&u8s), dims).unwrap(), leaf_size);
        same_on_both_paths(&Grid::scalar(Samples::I16(&i16s), dims).unwrap(), leaf_size);
    }
}

#[test]
fn nan_holes_in_a_smooth_field() {
    let dims = [49, 40, 33];
    let n = dims[0] * dims[1] * dims[2];
    // A NaN ball and scattered NaN samples: bricks inside, outside and across them.
    let f: Vec<f32> = (0..n)
        .map(|i| {
            let (x, y, z) = (i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1]));
            let r2 = (x as f64 - 30.0).powi(2) + (y as f64 - 12.0).powi(2) + (z as f64 - 20.0).powi(2);
            if r2 < 64.0 || i % 1013 == 0 {
                f32::NAN
            } else {
                wavelet(dims, i) as f32
            }
        })
        .collect();
    for leaf_size in [2, 8, 16] {
        let octree = same_on_both_paths(&Grid::scalar(Samples::F32(&f), dims).unwrap(), leaf_size);
        assert_eq!(octree.node(octree.root()).error(0), 1.0, "holes count as the full range");
    }
}

#[test]
fn constant_and_linear_volumes() {
    let dims = [33, 20, 18];
    let n = dims[0] * dims[1] * dims[2];
    let constant = vec![7.5f32; n];
    let octree = same_on_both_paths(&Grid::scalar(Samples::F32(&constant), dims).unwrap(), 8);
    assert_eq!(octree.node(octree.root()).error(0), 0.0);
    // Constant plateaus next to a ramp: constant bricks beside varying ones.
    let plateau: Vec<f32> = (0..n).map(|i| if i % dims[0] < 16 { 3.0 } else { (i % dims[0]) as f32 }).collect();
    same_on_both_paths(&Grid::scalar(Samples::F32(&plateau), dims).unwrap(), 4);
}

#[test]
fn extreme_values() {
    let dims = [19, 18, 17];
    let n = dims[0] * dims[1] * dims[2];
    let huge: Vec<f64> = (0..n).map(|i| wavelet(dims, i) * (f64::MAX / 1e3)).collect();
    same_on_both_paths(&Grid::scalar(Samples::F64(&huge), dims).unwrap(), 4);
    let tiny: Vec<f64> = (0..n).map(|i| wavelet(dims, i) * (f64::MIN_POSITIVE * 1e-10)).collect();
    same_on_both_paths(&Grid::scalar(Samples::F64(&tiny), dims).unwrap(), 8);
    let mixed: Vec<f64> = (0..n).map(|i| if i % 3 == 0 { f64::MAX / 4.0 } else { -f64::MAX / 4.0 }).collect();
    same_on_both_paths(&Grid::scalar(Samples::F64(&mixed), dims).unwrap(), 16);
}
