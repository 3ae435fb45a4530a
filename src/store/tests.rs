//! Stores written and read back: exact levels, the same octree, hostile stores refused.

use super::pyramid::{level_dims, level_position};
use super::*;
use crate::data::grid::{Grid, ScalarType};
use crate::datasets::{generate, Dataset};
use crate::octree::{BuildOptions, VolumeOctree};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh path under the system's temporary folder (removed by [`Tmp`]'s drop).
pub(super) struct Tmp(pub(super) PathBuf);

impl Tmp {
    pub(super) fn new(name: &str) -> Tmp {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        Tmp(std::env::temp_dir().join(format!("ho-store-{}-{n}-{name}.ome.zarr", std::process::id())))
    }
}

impl Drop for Tmp {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The samples' bytes (NaN compared bit for bit).
fn bytes(s: &crate::data::volume::SampleBuf) -> Vec<u8> {
    s.as_bytes().to_vec()
}

fn write(grid: &Grid<'_>, leaf: usize, path: &std::path::Path) -> VolumeOctree {
    let octree = VolumeOctree::build(grid, &BuildOptions { leaf_size: leaf }).unwrap();
    write_store(path, grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    octree
}

#[test]
fn levels_are_the_exact_strides_and_the_octree_reads_back() {
    for (dims, ty, leaf) in
        [([37, 20, 19], ScalarType::U8, 8), ([17, 33, 9], ScalarType::F32, 16), ([5, 6, 7], ScalarType::I16, 2)]
    {
        let mut v = generate(Dataset::SheppLogan, dims[0].max(dims[1]).max(dims[2]), ty);
        // Cut the cube down to dims (odd shapes exercise the clamped last plane).
        let full = v.shape.dims;
        let g = v.grid(None).unwrap();
        let mut values = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    values.push(g.value(i, j, k));
                }
            }
        }
        assert!(full.iter().all(|&n| n >= dims[0].max(dims[1]).max(dims[2])));
        if ty == ScalarType::F32 {
            // Holes of no data (NaN) survive the store, bit for bit, and are counted.
            for i in (0..values.len()).step_by(7) {
                values[i] = f64::NAN;
            }
        }
        v = crate::data::volume::Volume::new(crate::data::volume::SampleBuf::from_f64(&values, ty), dims, "cut");
        v.shape.spacing = [0.5, 1.0, 2.0];
        v.shape.origin = [1.0, -2.0, 3.0];
        let grid = v.grid(None).unwrap();
        let tmp = Tmp::new("exact");
        let octree = write(&grid, leaf, &tmp.0);
        let store = Store::open(&tmp.0).unwrap();
        assert!(store.has_octree());
        assert_eq!(store.shape, *grid.shape());
        assert_eq!(store.scalar_type, ty);
        assert_eq!(store.octree().unwrap().unwrap(), octree);
        let back = store.read_volume().unwrap();
        assert_eq!(bytes(&back.samples), bytes(&v.samples));
        assert!(ty != ScalarType::F32 || grid.nan_count() > 0);
        assert_eq!(store.metadata().unwrap().nan_count, grid.nan_count());
        let levels = store.metadata().unwrap().levels;
        for p in 0..levels {
            let m = level_dims(dims, p);
            let level = store.read_level_box(p, [0; 3], m.map(|n| n - 1)).unwrap();
            let lg = level.grid(None).unwrap();
            for k in 0..m[2] {
                for j in 0..m[1] {
                    for i in 0..m[0] {
                        let x = [
                            level_position(dims[0], p, i),
                            level_position(dims[1], p, j),
                            level_position(dims[2], p, k),
                        ];
                        assert_eq!(
                            lg.value(i, j, k).to_bits(),
                            grid.value(x[0], x[1], x[2]).to_bits(),
                            "{dims:?} level {p}"
                        );
                    }
                }
            }
            // A box inside the level is the same samples.
            if m.iter().all(|&n| n > 2) {
                let part = store.read_level_box(p, [1, 1, 1], [m[0] - 1, 2, m[2] - 1]).unwrap();
                let pg = part.grid(None).unwrap();
                assert_eq!(pg.value(0, 0, 0).to_bits(), lg.value(1, 1, 1).to_bits());
                assert_eq!(pg.value(m[0] - 2, 1, m[2] - 2).to_bits(), lg.value(m[0] - 1, 2, m[2] - 1).to_bits());
            }
        }
    }
}

#[test]
fn nothing_is_overwritten_and_bad_boxes_are_refused() {
    let v = generate(Dataset::Sphere, 17, ScalarType::U8);
    let grid = v.grid(None).unwrap();
    let tmp = Tmp::new("twice");
    write(&grid, 8, &tmp.0);
    let octree = VolumeOctree::build(&grid, &BuildOptions::default()).unwrap();
    let again = write_store(&tmp.0, &grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap_err();
    assert!(again.to_string().contains("already exists"), "{again}");
    let store = Store::open(&tmp.0).unwrap();
    let outside = store.read_level_box(0, [0; 3], [17, 0, 0]).unwrap_err();
    assert!(outside.to_string().contains("not inside level 0"), "{outside}");
    let small = write_store(
        &Tmp::new("small").0,
        &grid,
        &octree,
        &WriteOptions { memory_limit: 100, ..WriteOptions::default() },
        &mut |_, _| {},
    );
    assert!(small.unwrap_err().to_string().contains("raise --memory-mb"));
}

#[test]
fn damaged_stores_are_refused_with_the_reason() {
    let v = generate(Dataset::SheppLogan, 33, ScalarType::U8);
    let grid = v.grid(None).unwrap();
    let tmp = Tmp::new("damaged");
    write(&grid, 8, &tmp.0);
    // A forged octree: errors that break the envelope's invariants.
    let meta_path = tmp.0.join("hybrid_octree/errors/zarr.json");
    assert!(meta_path.exists());
    let store = Store::open(&tmp.0).unwrap();
    let array = super::zarr::open_array(&store.storage_for_tests(), "t", "/hybrid_octree/errors").unwrap();
    let n = array.shape()[0];
    array
        .store_array_subset(
            &zarrs::array::ArraySubset::new_with_ranges(std::slice::from_ref(&(0..n))),
            vec![7.0f32; n as usize],
        )
        .unwrap();
    let e = store.octree().unwrap_err().to_string();
    assert!(e.contains("stored Volume Octree is damaged") && e.contains("convert"), "{e}");
    // Not a folder, not an image.
    let file = Tmp::new("file");
    std::fs::write(&file.0, b"x").unwrap();
    assert!(Store::open(&file.0).err().unwrap().to_string().contains("not a folder"));
    let bare = Tmp::new("bare");
    std::fs::create_dir_all(&bare.0).unwrap();
    std::fs::write(bare.0.join("zarr.json"), br#"{"zarr_format":3,"node_type":"group","attributes":{}}"#).unwrap();
    assert!(Store::open(&bare.0).err().unwrap().to_string().contains("no OME-NGFF"));
    // Metadata that lies about the dims.
    let root = tmp.0.join("zarr.json");
    let mut json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&root).unwrap()).unwrap();
    json["attributes"]["hybrid_octree"]["dims"] = serde_json::json!([33, 33, 34]);
    std::fs::write(&root, json.to_string()).unwrap();
    let e = Store::open(&tmp.0).err().unwrap().to_string();
    assert!(e.contains("does not describe level 0"), "{e}");
}

/// A foreign NGFF 0.4 / Zarr v2 store of one uint8 array with `shape`
/// (z, y, x) and `chunks`, no chunk written (every sample the fill value).
fn declared_store(name: &str, shape: [u64; 3], chunks: [u64; 3]) -> Tmp {
    let t = Tmp::new(name);
    std::fs::create_dir_all(t.0.join("0")).unwrap();
    std::fs::write(t.0.join(".zgroup"), r#"{"zarr_format": 2}"#).unwrap();
    let attrs = serde_json::json!({"multiscales": [{"version": "0.4", "datasets": [{"path": "0"}],
        "axes": [{"name": "z", "type": "space"}, {"name": "y", "type": "space"}, {"name": "x", "type": "space"}]}]});
    std::fs::write(t.0.join(".zattrs"), attrs.to_string()).unwrap();
    let zarray = serde_json::json!({"zarr_format": 2, "shape": shape, "chunks": chunks, "dtype": "|u1",
        "compressor": null, "fill_value": 0, "order": "C", "filters": null});
    std::fs::write(t.0.join("0/.zarray"), zarray.to_string()).unwrap();
    t
}

#[test]
fn declared_shapes_beyond_what_is_addressable_are_refused_before_reading() {
    // 2^21 x 2^21 x 2^22 samples: a count that wraps to 0 in 64 bits.
    let t = declared_store("overflow", [1 << 21, 1 << 21, 1 << 22], [64, 64, 64]);
    let e = Store::open(&t.0).err().expect("an overflowing shape opens").to_string();
    assert!(e.contains("overflow"), "{e}");
    // A small store opens and reads its fill value.
    let t = declared_store("small", [3, 4, 5], [2, 2, 2]);
    let v = Store::open(&t.0).unwrap().read_volume().unwrap();
    assert_eq!(v.shape.dims, [5, 4, 3]);
}

/// A foreign store of more chunks than a pass over its samples may visit
/// (1-sample chunks over 400 x 300 x 200: 24,000,000 > 2^24) is refused
/// before its streaming octree pass and before any plane is read, naming
/// the count and the fix; one of 64^3 chunks over the same shape passes the
/// check (its octree is not built here).
#[test]
fn stores_of_too_many_chunks_are_refused_before_a_pass() {
    use crate::data::planes::PlaneSource;
    let t = declared_store("many-chunks", [200, 300, 400], [1, 1, 1]);
    let store = Store::open(&t.0).unwrap();
    assert_eq!(store.spatial_chunks(), 24_000_000);
    for e in [store.volume_octree(8).unwrap_err(), store.read_planes(0..1).unwrap_err()] {
        let e = e.to_string();
        assert!(e.contains("24000000 chunks") && e.contains("too small") && e.contains("64^3"), "{e}");
    }
    let t = declared_store("fewer-chunks", [200, 300, 400], [64, 64, 64]);
    let store = Store::open(&t.0).unwrap();
    assert_eq!(store.spatial_chunks(), 4 * 5 * 7);
    store.check_streamable().unwrap();
}
