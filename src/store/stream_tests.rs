//! The one-pass writer against [`write_store`]: the same store, file for
//! file and byte for byte; a store written elsewhere gets the in-core octree.

use super::tests::Tmp;
use super::*;
use crate::data::grid::{Grid, ScalarType};
use crate::data::planes::GridPlanes;
use crate::data::volume::{SampleBuf, Volume};
use crate::datasets::generate::DatasetPlanes;
use crate::datasets::{generate_dims, Dataset};
use crate::octree::{BuildOptions, VolumeOctree};
use std::collections::BTreeMap;
use std::path::Path;

/// Every file under `dir` by its relative path, with its bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            } else {
                let rel = e.path().strip_prefix(dir).unwrap().display().to_string();
                out.insert(rel, std::fs::read(e.path()).unwrap());
            }
        }
    }
    out
}

#[test]
fn one_pass_writes_the_store_write_store_writes() {
    let cases = [
        (Dataset::SheppLogan, [37, 20, 53], ScalarType::U8, 8, 1 << 30),
        (Dataset::Vessels, [41, 33, 70], ScalarType::U16, 4, 41 * 33 * 2 * 2 * 16),
        (Dataset::MarschnerLobb, [17, 9, 33], ScalarType::F32, 16, 1 << 20),
        (Dataset::Sphere, [2, 2, 2], ScalarType::I8, 2, 1 << 20),
    ];
    for (dataset, dims, ty, leaf, limit) in cases {
        let mut v = generate_dims(dataset, dims, ty);
        if let SampleBuf::F32(values) = &mut v.samples {
            for x in values.iter_mut().step_by(11) {
                *x = f32::NAN;
            }
        }
        let grid = v.grid(None).unwrap();
        let options = WriteOptions { memory_limit: limit, name: "same".into() };
        let build = BuildOptions { leaf_size: leaf };
        let (a, b) = (Tmp::new("in-core"), Tmp::new("one-pass"));
        let octree = VolumeOctree::build(&grid, &build).unwrap();
        let want = write_store(&a.0, &grid, &octree, &options, &mut |_, _| {}).unwrap();
        let mut last = (0, 1);
        let got = write_store_streaming(&b.0, &GridPlanes(grid), &build, &options, &mut |d, t| last = (d, t)).unwrap();
        assert_eq!(got.summary, want, "{dataset:?}");
        assert_eq!(last, (want.samples, want.samples), "progress ends at every sample written");
        assert_eq!(got.streamed.octree, octree);
        assert_eq!(got.streamed.nan_count, grid.nan_count());
        let (fa, fb) = (files(&a.0), files(&b.0));
        assert_eq!(fa.keys().collect::<Vec<_>>(), fb.keys().collect::<Vec<_>>(), "{dataset:?}: other files");
        for (name, bytes) in &fa {
            assert!(bytes == &fb[name], "{dataset:?}: {name} differs");
        }
        // Read back: every level is the subsampled volume, the octree the in-core one.
        let store = Store::open(&b.0).unwrap();
        assert_eq!(store.octree().unwrap().unwrap(), octree);
        assert_eq!(store.read_volume().unwrap().samples.as_bytes(), v.samples.as_bytes());
        for p in 0..want.levels {
            let m = pyramid::level_dims(dims, p);
            let level = store.read_level_box(p, [0; 3], m.map(|n| n - 1)).unwrap();
            let lg = level.grid(None).ok();
            for (i, j, k) in [(0, 0, 0), (m[0] - 1, m[1] - 1, m[2] - 1), (m[0] / 2, m[1] - 1, m[2] / 3)] {
                let x = [0, 1, 2].map(|a| pyramid::level_position(dims[a], p, [i, j, k][a]));
                let want = grid.value(x[0], x[1], x[2]).to_bits();
                let at = i + m[0] * (j + m[1] * k);
                let got = match (&level.samples, &lg) {
                    (SampleBuf::F32(s), _) => (s[at] as f64).to_bits(),
                    (_, Some(g)) => g.value(i, j, k).to_bits(),
                    _ => unreachable!(),
                };
                assert_eq!(got, want, "{dataset:?} level {p}");
            }
        }
    }
}

#[test]
fn a_generator_is_converted_without_the_volume_and_errors_leave_nothing() {
    let source = DatasetPlanes { dataset: Dataset::Vessels, dims: [33, 33, 33], scalar_type: ScalarType::U8 };
    let v = generate_dims(Dataset::Vessels, [33, 33, 33], ScalarType::U8);
    let (a, b) = (Tmp::new("gen-core"), Tmp::new("gen-pass"));
    let build = BuildOptions { leaf_size: 8 };
    let octree = VolumeOctree::build(&v.grid(None).unwrap(), &build).unwrap();
    write_store(&a.0, &v.grid(None).unwrap(), &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    write_store_streaming(&b.0, &source, &build, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    // The metadata names the image "image" in both (the default name).
    assert!(files(&a.0) == files(&b.0), "the generator's store differs");
    // An infinity stops the pass; the half-written store is removed.
    let mut values = vec![1.0f32; 5 * 5 * 40];
    values[5 * 5 * 30 + 7] = f32::INFINITY;
    let bad = Volume::new(SampleBuf::F32(values), [5, 5, 40], "inf");
    let c = Tmp::new("inf");
    let e = write_store_streaming(
        &c.0,
        &GridPlanes(Grid::unscanned(bad.samples.as_samples(), bad.shape, 1, None).unwrap()),
        &build,
        &WriteOptions::default(),
        &mut |_, _| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("infinite"), "{e}");
    assert!(!c.0.exists());
}

#[test]
fn a_foreign_store_builds_the_in_core_octree_once() {
    // A Zarr v2 / NGFF 0.4 image with small uncompressed chunks, written by hand.
    let dims = [23usize, 18, 29];
    let v = generate_dims(Dataset::SheppLogan, dims, ScalarType::U16);
    let t = Tmp::new("foreign");
    std::fs::create_dir_all(t.0.join("0")).unwrap();
    std::fs::write(t.0.join(".zgroup"), r#"{"zarr_format": 2}"#).unwrap();
    let attrs = serde_json::json!({"multiscales": [{"version": "0.4", "datasets": [{"path": "0"}],
        "axes": [{"name": "z", "type": "space"}, {"name": "y", "type": "space"}, {"name": "x", "type": "space"}]}]});
    std::fs::write(t.0.join(".zattrs"), attrs.to_string()).unwrap();
    let c = [8usize, 8, 8];
    let zarray = serde_json::json!({"zarr_format": 2, "shape": [dims[2], dims[1], dims[0]], "chunks": c,
        "dtype": "<u2", "compressor": null, "fill_value": 0, "order": "C", "filters": null, "dimension_separator": "/"});
    std::fs::write(t.0.join("0/.zarray"), zarray.to_string()).unwrap();
    let g = v.grid(None).unwrap();
    for cz in 0..dims[2].div_ceil(8) {
        for cy in 0..dims[1].div_ceil(8) {
            for cx in 0..dims[0].div_ceil(8) {
                let mut bytes = Vec::new();
                for z in cz * 8..cz * 8 + 8 {
                    for y in cy * 8..cy * 8 + 8 {
                        for x in cx * 8..cx * 8 + 8 {
                            let s = if x < dims[0] && y < dims[1] && z < dims[2] { g.value(x, y, z) as u16 } else { 0 };
                            bytes.extend_from_slice(&s.to_le_bytes());
                        }
                    }
                }
                let dir = t.0.join(format!("0/{cz}/{cy}"));
                std::fs::create_dir_all(&dir).unwrap();
                std::fs::write(dir.join(cx.to_string()), bytes).unwrap();
            }
        }
    }
    let store = Store::open(&t.0).unwrap();
    assert!(!store.has_octree());
    for leaf in [4, 8] {
        let want = VolumeOctree::build(&g, &BuildOptions { leaf_size: leaf }).unwrap();
        assert_eq!(store.volume_octree(leaf).unwrap(), want, "leaf {leaf}");
    }
    // Kept: the same octree again without reading the store (its level 0 removed).
    std::fs::remove_dir_all(t.0.join("0/0")).unwrap();
    let want = VolumeOctree::build(&g, &BuildOptions { leaf_size: 4 }).unwrap();
    assert_eq!(store.volume_octree(4).unwrap(), want);
}

#[test]
fn the_same_samples_give_the_same_bytes() {
    // Shards of many subchunks, encoded in parallel: laid out in C order every time.
    let v = generate_dims(Dataset::Vessels, [41, 33, 70], ScalarType::U16);
    let grid = v.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let options = WriteOptions { memory_limit: 41 * 33 * 2 * 2 * 16, name: "same".into() };
    let first = Tmp::new("same-0");
    write_store(&first.0, &grid, &octree, &options, &mut |_, _| {}).unwrap();
    let want = files(&first.0);
    for i in 1..6 {
        let again = Tmp::new(&format!("same-{i}"));
        write_store(&again.0, &grid, &octree, &options, &mut |_, _| {}).unwrap();
        assert!(files(&again.0) == want, "write {i} differs");
    }
}
