//! The HOPOINTS point-file reader on arbitrary bytes.
#![no_main]

use hybrid_octree::points::storage::from_bytes;
use hybrid_octree::Error;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match from_bytes(data, "fuzz.hop") {
        Ok(set) => assert!(set.points.iter().all(|p| (0..3).all(|a| usize::from(p.ijk[a]) < set.dims[a]))),
        Err(Error::Format { .. }) => {}
        Err(e) => panic!("unexpected error kind {e:?}"),
    }
});
