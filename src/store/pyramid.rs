//! The store's resolution levels: level `p` holds exactly the samples a
//! brick texture of stride `s = 2^p` reads, so `T_s` drawn from the store
//! is `T_s` drawn in core, bit for bit.
//!
//! A brick of stride `s` reads the grid at `min(lo + i s, hi)`, `lo` a
//! multiple of `s` and `hi` either a multiple of `s` or the grid's last
//! sample `n - 1` (see [`crate::octree::layout::Layout::node_box`]); its
//! gradient border reads one stride further, clamped to `[0, n - 1]`. All
//! of these are positions of the clamped lattice
//!
//! ```text
//! x_p(i) = min(i 2^p, n - 1),   i = 0 .. m_p - 1,   m_p = ceil((n - 1) / 2^p) + 1
//! ```
//!
//! and level `p` stores `f(x_p(i))` per axis: the exact stride-`2^p`
//! subsampling of level 0 (no filtering), with the grid's last sample as the
//! last plane when `n - 1` is not a multiple of `2^p`. A position `x` of the
//! lattice is level index `ceil(x / 2^p)`.

/// Samples per axis of level `p` for `n` samples at level 0: `m_p = ceil((n - 1) / 2^p) + 1`.
pub fn level_len(n: usize, p: usize) -> usize {
    (n - 1).div_ceil(1 << p) + 1
}

/// [`level_len`] per axis.
pub fn level_dims(dims: [usize; 3], p: usize) -> [usize; 3] {
    dims.map(|n| level_len(n, p))
}

/// The level-0 index `x_p(i) = min(i 2^p, n - 1)` of sample `i` of level `p`.
pub fn level_position(n: usize, p: usize, i: usize) -> usize {
    (i << p).min(n - 1)
}

/// The level-`p` index `ceil(x / 2^p)` of level-0 position `x`, a position
/// of the level's lattice (a multiple of `2^p` or `n - 1`).
pub fn level_index(x: usize, p: usize) -> usize {
    x.div_ceil(1 << p)
}

/// The number of levels a store holds for an octree whose root node spans
/// `root_size` cells: strides `1, 2, .., root_size` (the root brick's
/// coarsest texture, two samples per axis), `log2(root_size) + 1` levels.
pub fn level_count(root_size: usize) -> usize {
    root_size.max(1).trailing_zeros() as usize + 1
}

/// The level of stride `s`: `log2 s`, `None` unless `s` is a power of two.
pub fn level_of_stride(s: usize) -> Option<usize> {
    s.is_power_of_two().then(|| s.trailing_zeros() as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_hold_the_clamped_lattice() {
        // 10 samples: stride 4 reads 0, 4, 8 and the last sample 9.
        assert_eq!(level_len(10, 2), 4);
        assert_eq!((0..4).map(|i| level_position(10, 2, i)).collect::<Vec<_>>(), vec![0, 4, 8, 9]);
        assert_eq!(level_index(9, 2), 3);
        assert_eq!(level_index(8, 2), 2);
        // 9 samples: 8 cells, stride 4 lands on the last sample exactly.
        assert_eq!((0..level_len(9, 2)).map(|i| level_position(9, 2, i)).collect::<Vec<_>>(), vec![0, 4, 8]);
        assert_eq!(level_len(2, 5), 2);
    }

    #[test]
    fn the_coarsest_level_has_two_samples_per_axis() {
        for (dims, root) in [([2, 2, 2], 1), ([17, 17, 17], 16), ([197, 233, 189], 256), ([9, 9, 9], 16)] {
            let count = level_count(root);
            assert_eq!(level_dims(dims, count - 1), [2, 2, 2], "{dims:?}");
        }
        assert_eq!(level_count(256), 9);
    }
}
