//! The .vti reader on arbitrary bytes.
#![no_main]

#[path = "common.rs"]
mod common;

use hybrid_octree::io::{read_volume_bytes, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    common::cap_memory();
    common::check(read_volume_bytes("fuzz.vti", data, &ReadOptions::default()));
});
