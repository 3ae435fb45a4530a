//! The TIFF stack reader on arbitrary bytes (one multi-page `.tif`).
#![no_main]

#[path = "common.rs"]
mod common;

use hybrid_octree::io::{read_volume_bytes, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    common::cap_memory();
    common::check(read_volume_bytes("fuzz.tif", data, &ReadOptions::default()));
});
