//! The store through the bridge: its summary and levels, the octree made
//! from it, and brick texels read from it equal to the in-memory calls'.

use super::octree::HybridOctreeHandle;
use super::store::{build_octree_from_store, open_store, StoreHandle};
use super::test_support::{as_bytes, build_volume_octree, select_desc};
use super::{GridDesc, ScalarType};
use crate::octree::{BuildOptions, VolumeOctree};
use crate::store::{write_store, WriteOptions};
use std::path::PathBuf;

/// A fresh store path under the temporary folder, removed on drop.
pub(super) struct Tmp(pub(super) PathBuf);

impl Tmp {
    pub(super) fn new(name: &str) -> Tmp {
        Tmp(std::env::temp_dir().join(format!("ho-ffi-store-{}-{name}.ome.zarr", std::process::id())))
    }
}

impl Drop for Tmp {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A 21 x 18 x 13 f32 field with structure at every scale (odd sizes: every
/// coarse level's last plane is clamped), its description and a store of it
/// with leaves of 4.
pub(super) fn field(name: &str) -> (Vec<f32>, GridDesc, Tmp) {
    let dims = [21, 18, 13];
    let data: Vec<f32> = (0..dims[0] * dims[1] * dims[2])
        .map(|i| {
            let (x, y, z) = (i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1]));
            ((x * 7 + y * 3 + z * 11) % 17) as f32 * 0.25 + (x as f32 * 0.3).sin()
        })
        .collect();
    let desc = GridDesc {
        scalar_type: ScalarType::F32,
        dims,
        spacing: [0.5, 1.0, 2.0],
        origin: [1.0, -2.0, 3.0],
        components: 1,
        component: -1,
    };
    let tmp = Tmp::new(name);
    let grid = super::grid::grid_of(as_bytes(&data), &desc).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    write_store(&tmp.0, &grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    (data, desc, tmp)
}

fn open(tmp: &Tmp) -> Box<StoreHandle> {
    open_store(tmp.0.to_str().unwrap()).unwrap()
}

#[test]
fn the_summary_and_levels_are_the_stores() {
    let (data, desc, tmp) = field("summary");
    let store = open(&tmp);
    let s = store.summary().unwrap();
    assert_eq!((s.dims, s.spacing, s.origin), (desc.dims, desc.spacing, desc.origin));
    assert!(s.has_octree && s.scalar_type == ScalarType::F32 && s.warnings.is_empty());
    assert_eq!(s.level_dims.len(), 3 * s.levels);
    assert_eq!(s.level_dims[..3], desc.dims);
    // Level 1: samples min(2 i, n - 1), 11 x 10 x 7 (the last plane of each axis clamped).
    assert_eq!(s.level_dims[3..6], [11, 10, 7]);
    let mut bytes = vec![0u8; 11 * 10 * 7 * 4];
    store.read_level(1, &[0, 0, 0], &[10, 9, 6], &mut bytes).unwrap();
    let at = |i: usize, j: usize, k: usize| data[i + desc.dims[0] * (j + desc.dims[1] * k)];
    let read = |i: usize, j: usize, k: usize| {
        let o = 4 * (i + 11 * (j + 10 * k));
        f32::from_ne_bytes(bytes[o..o + 4].try_into().unwrap())
    };
    assert_eq!(read(3, 4, 5).to_bits(), at(6, 8, 10).to_bits());
    assert_eq!(read(10, 9, 6).to_bits(), at(20, 17, 12).to_bits(), "the clamped last sample");
    let e = store.read_level(1, &[0, 0, 0], &[11, 9, 6], &mut bytes).unwrap_err();
    assert!(e.contains("not inside level 1"), "{e}");
    let e = store.read_level(1, &[0, 0, 0], &[10, 9, 6], &mut bytes[1..]).unwrap_err();
    assert!(e.contains("buffer"), "{e}");
}

#[test]
fn brick_texels_from_the_store_are_the_in_memory_texels() {
    let (data, desc, tmp) = field("texels");
    let store = open(&tmp);
    let from_store = build_octree_from_store(&store, 8).unwrap();
    let in_memory: Box<HybridOctreeHandle> = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
    let (a, b) = (from_store.summary().unwrap(), in_memory.summary().unwrap());
    assert_eq!((a.node_count, a.leaf_size, a.input_bytes), (b.node_count, b.leaf_size, b.input_bytes));
    assert_eq!((a.value_min, a.value_max), (b.value_min, b.value_max));
    let mut strides = std::collections::BTreeSet::new();
    for (format, bordered, budget) in
        [(0, false, 6000), (0, true, 6000), (4, false, 6000), (2, true, 6000), (0, true, 1 << 30), (4, false, 1 << 30)]
    {
        let options = super::SelectDesc { texel_format: format, gradient_border: bordered, ..select_desc(budget) };
        let (s, m) = (from_store.select_bricks(&options).unwrap(), in_memory.select_bricks(&options).unwrap());
        let bricks = &s.selection.bricks;
        assert_eq!(bricks, &m.selection.bricks, "the same selection");
        strides.extend(bricks.iter().map(|b| b.stride));
        for (i, brick) in bricks.iter().enumerate() {
            let count = brick.texels.iter().map(|n| n + 2 * usize::from(bordered)).product::<usize>();
            let (mut got, mut want) = (vec![0f32; count], vec![0f32; count]);
            if format == 0 {
                s.brick_texels_from_store(&from_store, &store, i, bordered, &mut got, &mut []).unwrap();
                if bordered {
                    m.brick_texels_bordered(as_bytes(&data), &desc, i, &mut want).unwrap();
                } else {
                    m.brick_texels(as_bytes(&data), &desc, i, &mut want).unwrap();
                }
            } else {
                let width = if format == 4 { 1 } else { 4 };
                let (mut e_got, mut e_want) = (vec![0u8; count * width], vec![0u8; count * width]);
                s.brick_texels_from_store(&from_store, &store, i, bordered, &mut got, &mut e_got).unwrap();
                m.brick_texels_encoded(as_bytes(&data), &desc, i, bordered, &mut want, &mut e_want).unwrap();
                assert_eq!(e_got, e_want, "brick {i} format {format}: GPU bytes");
            }
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&want), "brick {i} format {format} bordered {bordered}");
        }
    }
    assert!(strides.len() > 1 && strides.contains(&1), "coarse and full-resolution bricks read: {strides:?}");
}

/// Another octree than the store's.
pub(super) fn in_memory_twin() -> Box<HybridOctreeHandle> {
    let data = vec![1.0f32; 27];
    build_volume_octree(as_bytes(&data), &super::test_support::f32_desc([3, 3, 3]), 2).unwrap()
}

#[test]
fn a_missing_chunk_is_found_by_the_octree_range() {
    let (_, _, tmp) = field("missing");
    // Level 0 of the field is one shard: deleted, Zarr reads every sample as the fill value 0.
    let shard = tmp.0.join("0/c/0/0/0");
    assert!(shard.exists(), "level 0's shard at {}", shard.display());
    let store = open(&tmp);
    let octree = build_octree_from_store(&store, 4).unwrap();
    std::fs::remove_file(&shard).unwrap();
    let all = octree.select_bricks(&select_desc(1 << 30)).unwrap();
    let bricks = &all.selection.bricks;
    assert!(bricks.iter().all(|b| b.stride == 1));
    let failures = (0..bricks.len())
        .filter_map(|i| {
            let n = bricks[i].texels.iter().product::<usize>();
            all.brick_texels_from_store(&octree, &store, i, false, &mut vec![0.0; n], &mut []).err()
        })
        .collect::<Vec<_>>();
    assert!(!failures.is_empty(), "a brick whose stored range excludes 0 reads the fill value");
    assert!(failures[0].contains("missing") && failures[0].contains("node"), "{}", failures[0]);
}

#[test]
fn what_a_store_cannot_give_is_refused_clearly() {
    let (_, _, tmp) = field("refused");
    let store = open(&tmp);
    let octree = build_octree_from_store(&store, 4).unwrap();
    let mip = octree.select_bricks(&super::SelectDesc { blend_mode: 1, ..select_desc(3000) }).unwrap();
    let coarse = mip.selection.bricks.iter().position(|b| b.stride > 1).expect("a coarse brick at this budget");
    let n = mip.selection.bricks[coarse].texels.iter().product::<usize>();
    let e = mip.brick_texels_from_store(&octree, &store, coarse, false, &mut vec![0.0; n], &mut []).unwrap_err();
    assert!(e.contains("maximum and minimum intensity") && e.contains("raise the budget"), "{e}");
    let e = mip.brick_texels_from_store(&octree, &store, 1 << 20, false, &mut [], &mut []).unwrap_err();
    assert!(e.contains("does not exist"), "{e}");
    let e = mip.brick_texels_from_store(&in_memory_twin(), &store, 0, false, &mut [], &mut []).unwrap_err();
    assert!(e.contains("another octree"), "{e}");
    let missing = std::env::temp_dir().join("ho-ffi-store-no-such-folder.ome.zarr");
    let e = open_store(missing.to_str().unwrap()).err().unwrap();
    assert!(e.contains("not a folder"), "{e}");
}
