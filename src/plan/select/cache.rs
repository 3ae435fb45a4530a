//! The map in which one selection keeps what it computes once per brick
//! with points (its best next step; bricks without points keep theirs in
//! the dense `forms` table), which a [`Selector`](super::Selector) keeps
//! from one budget to the next.

use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A multiply-rotate hash for small integer keys (node ids and levels):
/// `h = (rotl(h, 5) ^ word) * K` per word, `K` the 64-bit golden-ratio
/// constant of Fibonacci hashing. The maps are only probed, never iterated,
/// so the hash affects speed, never a result.
#[derive(Default, Clone, Copy)]
pub(super) struct WordHasher(u64);

impl Hasher for WordHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u32(&mut self, word: u32) {
        self.write_u64(u64::from(word));
    }

    fn write_usize(&mut self, word: usize) {
        self.write_u64(word as u64);
    }

    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
}

/// A map keyed by node, level and points, hashed by [`WordHasher`].
pub(super) type NodeMap<K, V> = RefCell<HashMap<K, V, BuildHasherDefault<WordHasher>>>;
