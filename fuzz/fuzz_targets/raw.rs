//! The raw reader on arbitrary bytes: the first 8 give the layout (3 x u16
//! dims, a type index mod 8, flags: bits 0-1 components - 1, bit 2 big
//! endian), the rest are the samples; decoded by `fuzz/raw_layout.rs`.
#![no_main]

#[path = "common.rs"]
mod common;

#[path = "../raw_layout.rs"]
mod raw_layout;

use hybrid_octree::io::{read_volume_bytes, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    common::cap_memory();
    let Some((raw, samples)) = raw_layout::raw_layout(data) else { return };
    common::check(read_volume_bytes("fuzz.raw", samples, &ReadOptions { raw: Some(raw) }));
});
