//! The raw reader on arbitrary bytes: the first 8 give the layout (3 x u16
//! dims, a type index mod 8, flags: bits 0-1 components - 1, bit 2 big
//! endian), the rest are the samples; as `raw_layout` in tests/seeds.
#![no_main]

#[path = "common.rs"]
mod common;

use hybrid_octree::grid::ScalarType;
use hybrid_octree::io::{read_volume_bytes, RawOptions, ReadOptions};
use libfuzzer_sys::fuzz_target;

const TYPES: [ScalarType; 8] = [
    ScalarType::U8,
    ScalarType::I8,
    ScalarType::U16,
    ScalarType::I16,
    ScalarType::U32,
    ScalarType::I32,
    ScalarType::F32,
    ScalarType::F64,
];

fuzz_target!(|data: &[u8]| {
    common::cap_memory();
    let Some(head) = data.get(..8) else { return };
    let dims = [0, 1, 2].map(|a| usize::from(u16::from_le_bytes([head[2 * a], head[2 * a + 1]])));
    let mut raw = RawOptions::new(dims, TYPES[usize::from(head[6] % 8)]);
    raw.components = usize::from(head[7] & 3) + 1;
    raw.big_endian = head[7] & 4 != 0;
    common::check(read_volume_bytes("fuzz.raw", &data[8..], &ReadOptions { raw: Some(raw) }));
});
