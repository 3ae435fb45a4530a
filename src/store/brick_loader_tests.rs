//! The background brick reader: the volumes of the frame's own reads, only
//! what the last request names, the RAM budget kept, failures handed on.

use super::brick_loader::{BrickLoader, BrickRead};
use super::tests::Tmp;
use super::*;
use crate::data::grid::ScalarType;
use crate::datasets::{generate, Dataset};
use crate::octree::{BuildOptions, VolumeOctree};
use std::sync::Arc;
use std::time::{Duration, Instant};

fn store_of(name: &str) -> (Tmp, Arc<Store>) {
    let v = generate(Dataset::SheppLogan, 45, ScalarType::U8);
    let grid = v.grid(None).unwrap();
    let tmp = Tmp::new(name);
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    write_store(&tmp.0, &grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    let store = Arc::new(Store::open(&tmp.0).unwrap());
    (tmp, store)
}

/// Every stride-`stride` brick of `edge` cells over the store's grid.
fn bricks(store: &Store, stride: usize, edge: usize, border: usize) -> Vec<BrickRead> {
    let d = store.shape.dims;
    let mut out = Vec::new();
    for z in (0..d[2] - 1).step_by(edge) {
        for y in (0..d[1] - 1).step_by(edge) {
            for x in (0..d[0] - 1).step_by(edge) {
                let lo = [x, y, z];
                let texels = [0, 1, 2].map(|a| ((lo[a] + edge).min(d[a] - 1) - lo[a]).div_ceil(stride) + 1);
                out.push(BrickRead { stride, lo, texels, border });
            }
        }
    }
    out
}

/// Waits until `done` holds (at most 20 s).
fn until(mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < Duration::from_secs(20), "the loader did not get there in 20 s");
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn loaded_bricks_are_the_frames_own_reads() {
    let (_tmp, store) = store_of("loaded");
    let loader = BrickLoader::start(Arc::clone(&store)).unwrap();
    let mut wanted = bricks(&store, 1, 8, 1);
    wanted.extend(bricks(&store, 2, 16, 0));
    loader.request(&wanted, usize::MAX);
    until(|| loader.status().pending == 0);
    let status = loader.status();
    assert_eq!(status.ready, wanted.len());
    assert_eq!(status.reads, wanted.len() as u64);
    let mut bytes = 0;
    for read in &wanted {
        assert!(loader.is_ready(read));
        let got = loader.take(read).unwrap();
        let own = store.read_texels(read.stride, read.lo, read.texels, read.border).unwrap();
        assert_eq!(got.samples.as_bytes(), own.samples.as_bytes(), "{read:?}");
        assert_eq!(got.shape.dims, own.shape.dims);
        bytes += own.samples.as_bytes().len();
        assert!(loader.take(read).is_none(), "taken once");
    }
    assert_eq!(loader.status().bytes_read, bytes as u64);
    assert_eq!(loader.status().ready_bytes, 0);
}

#[test]
fn a_new_request_drops_what_it_does_not_name() {
    let (_tmp, store) = store_of("dropped");
    let loader = BrickLoader::start(Arc::clone(&store)).unwrap();
    let all = bricks(&store, 1, 8, 0);
    loader.request(&all, usize::MAX);
    until(|| loader.status().pending == 0);
    // Half of them wanted now: the others' volumes are let go.
    let half: Vec<BrickRead> = all.iter().step_by(2).copied().collect();
    loader.request(&half, usize::MAX);
    let status = loader.status();
    assert_eq!((status.pending, status.ready), (0, half.len()));
    assert!(all.iter().skip(1).step_by(2).all(|r| !loader.is_ready(r)));
    // Nothing wanted: nothing held, nothing more read.
    loader.request(&[], usize::MAX);
    let reads = loader.status().reads;
    assert_eq!(loader.status().ready, 0);
    std::thread::sleep(Duration::from_millis(20));
    assert_eq!(loader.status().reads, reads);
}

#[test]
fn reads_stop_at_the_memory_budget_until_bricks_are_taken() {
    let (_tmp, store) = store_of("budget");
    let loader = BrickLoader::start(Arc::clone(&store)).unwrap();
    let wanted = bricks(&store, 1, 8, 1);
    let each = 11 * 11 * 11; // the first bricks: 8 cells, 9 texels and a border on each side, u8
                             // Room for three bricks: the fourth read waits until one is taken.
    loader.request(&wanted, 3 * each);
    until(|| loader.status().ready == 3);
    std::thread::sleep(Duration::from_millis(30));
    let status = loader.status();
    assert_eq!((status.ready, status.ready_bytes), (3, 3 * each));
    assert_eq!(status.pending, wanted.len() - 3);
    let first = wanted.iter().find(|r| loader.is_ready(r)).copied().unwrap();
    loader.take(&first).unwrap();
    until(|| loader.status().ready == 3 && loader.status().reads == 4);
    assert!(loader.status().ready_bytes <= 3 * each);
}

#[test]
fn a_failed_read_is_handed_on_and_nothing_more_is_read() {
    let (tmp, store) = store_of("failed");
    // Level 0's chunks overwritten with bytes no codec decodes.
    let mut damaged = 0;
    let mut stack = vec![tmp.0.join("0")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.file_name().is_some_and(|n| n != "zarr.json") {
                std::fs::write(&path, b"not a zstd frame").unwrap();
                damaged += 1;
            }
        }
    }
    assert!(damaged > 0);
    let loader = BrickLoader::start(Arc::clone(&store)).unwrap();
    let wanted = bricks(&store, 1, 8, 0);
    loader.request(&wanted, usize::MAX);
    until(|| loader.failure().is_some());
    let message = loader.failure().unwrap();
    let own = store.read_texels(1, wanted[0].lo, wanted[0].texels, 0).unwrap_err().to_string();
    assert!(message.contains(store.label()), "{message}");
    assert_eq!(message, own);
    std::thread::sleep(Duration::from_millis(20));
    assert_eq!(loader.status().reads, 0);
    assert_eq!(loader.status().ready, 0);
}
