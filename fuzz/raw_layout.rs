//! How a raw fuzz input gives its layout, shared by the `raw` fuzz target and
//! the deterministic fuzz test (`tests/fuzz_readers.rs`, through
//! `tests/seeds`).

use hybrid_octree::grid::ScalarType;
use hybrid_octree::io::RawOptions;

/// The scalar types by the index a raw fuzz input gives.
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

/// A raw fuzz input's layout and data: 3 x u16 dims, a type index (mod 8),
/// flags (bits 0-1: components - 1, bit 2: big endian), then the samples.
/// `None` for fewer than 8 bytes.
pub fn raw_layout(bytes: &[u8]) -> Option<(RawOptions, &[u8])> {
    let (head, data) = (bytes.get(..8)?, &bytes[8..]);
    let dims = [0, 1, 2].map(|a| usize::from(u16::from_le_bytes([head[2 * a], head[2 * a + 1]])));
    let mut raw = RawOptions::new(dims, TYPES[usize::from(head[6] % 8)]);
    raw.components = usize::from(head[7] & 3) + 1;
    raw.big_endian = head[7] & 4 != 0;
    Some((raw, data))
}
