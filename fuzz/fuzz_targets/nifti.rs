//! The NIfTI-1 reader on arbitrary bytes: `.nii.gz` when they start with the
//! gzip magic, `.nii` otherwise.
#![no_main]

#[path = "common.rs"]
mod common;

use hybrid_octree::io::{read_volume_bytes, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    common::cap_memory();
    let name = if data.starts_with(&[0x1f, 0x8b]) { "fuzz.nii.gz" } else { "fuzz.nii" };
    common::check(read_volume_bytes(name, data, &ReadOptions::default()));
});
