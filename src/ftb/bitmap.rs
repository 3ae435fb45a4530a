//! Blocking bitmaps (paper 2, sections 3.2 and 4): a blocking quadtree kept
//! as the complete quadtree of its resolution, every node 2 bits (W, B or G),
//! level by level, left to right. Node `card` of depth `d` (its cardinal
//! number, `0 <= card < 4^d`) has index
//!
//! ```text
//! ind_num = ind_tab[d] + card,          ind_tab[d] = (4^d - 1) / 3      (1)
//! ```
//!
//! stored in byte `ind_num div 4` at bit pair `ind_num mod 4` (2). Its
//! children are `ind_tab[d + 1] + 4 card + j`, `j = 0..3` (3), and the face of
//! axis `i` of suboctant `oct` has cardinal number
//! `4 card + quad_tab[oct][i]` (4), `quad_tab` the paper's Table I.
//!
//! Three bitmaps of resolution `n` take `3 * 2/8 * (4^(n+1) - 1)/3 < 4^n` bytes
//! (the paper's bound).

/// The paper's Table I: `QUAD_TAB[oct][axis]` is the quadrant (0..3) of the
/// `axis` face of suboctant `oct` within its parent's face.
pub const QUAD_TAB: [[u8; 3]; 8] =
    [[1, 2, 0], [1, 3, 1], [3, 2, 2], [3, 3, 3], [0, 0, 0], [0, 1, 1], [2, 0, 2], [2, 1, 3]];

/// A node colour in a blocking quadtree.
pub const WHITE: u8 = 0;
/// Blocked.
pub const BLACK: u8 = 1;
/// Mixed: look at the four children.
pub const GRAY: u8 = 2;

/// The blocking quadtrees of one display (one per used axis), each a
/// complete-quadtree bitmap of depth `n`, packed one after the other in one
/// byte array: tree `tree`'s node `index` is bit pair `tree * nodes + index`.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockingBitmaps {
    bits: Vec<u8>,
    /// Nodes of one complete quadtree, `(4^(n+1) - 1) / 3`.
    nodes: usize,
    /// `ind_tab[d]`: index of the first node of depth `d`.
    ind_tab: Vec<usize>,
}

impl BlockingBitmaps {
    /// `trees` bitmaps of depths `0..=n`, every node white.
    pub fn new(trees: usize, n: u32) -> BlockingBitmaps {
        let ind_tab: Vec<usize> = (0..=n + 1).map(|d| ((1usize << (2 * d)) - 1) / 3).collect();
        let nodes = ind_tab[n as usize + 1];
        BlockingBitmaps { bits: vec![0; (trees * nodes).div_ceil(4)], nodes, ind_tab }
    }

    /// Bytes of the bitmaps.
    pub fn bytes(&self) -> usize {
        self.bits.len()
    }

    /// Index of node `card` at depth `depth`: formula (1).
    #[inline]
    pub fn index(&self, depth: u32, card: usize) -> usize {
        self.ind_tab[depth as usize] + card
    }

    /// Colour of node `index` of tree `tree`: formula (2).
    #[inline]
    pub fn get(&self, tree: usize, index: usize) -> u8 {
        let i = tree * self.nodes + index;
        (self.bits[i >> 2] >> ((i & 3) * 2)) & 3
    }

    /// Sets node `index` of tree `tree` to `colour`.
    #[inline]
    pub fn set(&mut self, tree: usize, index: usize, colour: u8) {
        let i = tree * self.nodes + index;
        let shift = (i & 3) * 2;
        let byte = &mut self.bits[i >> 2];
        *byte = (*byte & !(3 << shift)) | (colour << shift);
    }

    /// Where node `card` of depth `depth` of tree `tree` lives: the global
    /// bit-pair index that [`Self::get_at`] and the other `_at` calls take
    /// (formula (1) plus the tree's offset).
    #[inline]
    pub fn node(&self, tree: usize, depth: u32, card: usize) -> usize {
        tree * self.nodes + self.ind_tab[depth as usize] + card
    }

    /// Colour at global index `g`: formula (2).
    #[inline]
    pub fn get_at(&self, g: usize) -> u8 {
        (self.bits[g >> 2] >> ((g & 3) * 2)) & 3
    }

    /// Sets global index `g` to `colour`.
    #[inline]
    pub fn set_at(&mut self, g: usize, colour: u8) {
        let shift = (g & 3) * 2;
        let byte = &mut self.bits[g >> 2];
        *byte = (*byte & !(3 << shift)) | (colour << shift);
    }

    /// Global index of the first of the four children of global index `g` of
    /// tree `tree`: formula (3), `ind_tab[d + 1] + 4 card`, which is
    /// `4 ind_num + 1` because `ind_tab[d + 1] = 4 ind_tab[d] + 1`.
    #[inline]
    pub fn first_son_at(&self, tree: usize, g: usize) -> usize {
        4 * g + 1 - 3 * tree * self.nodes
    }

    /// The four children starting at global index `first`, as one byte
    /// (child `j` in bits `2j..2j + 2`). Siblings are consecutive bit pairs,
    /// so they are one or two bytes of the bitmap.
    #[inline]
    pub fn sons_at(&self, first: usize) -> u8 {
        let (byte, shift) = (first >> 2, (first & 3) * 2);
        if shift == 0 {
            self.bits[byte]
        } else {
            (u16::from_le_bytes([self.bits[byte], self.bits[byte + 1]]) >> shift) as u8
        }
    }

    /// Sets the four children starting at global index `first` to `sons` (as [`Self::sons_at`] reads them).
    #[inline]
    pub fn set_sons_at(&mut self, first: usize, sons: u8) {
        let (byte, shift) = (first >> 2, (first & 3) * 2);
        if shift == 0 {
            self.bits[byte] = sons;
        } else {
            let old = u16::from_le_bytes([self.bits[byte], self.bits[byte + 1]]);
            let [lo, hi] = ((old & !(0xff << shift)) | (u16::from(sons) << shift)).to_le_bytes();
            self.bits[byte] = lo;
            self.bits[byte + 1] = hi;
        }
    }

    /// Refine at global index `g` whose first child is at global index
    /// `first`: a W or B node becomes G with four children of its colour.
    #[inline]
    pub fn refine_at(&mut self, g: usize, first: usize) {
        let colour = self.get_at(g);
        if colour != GRAY {
            self.set_sons_at(first, colour * 0b0101_0101);
            self.set_at(g, GRAY);
        }
    }

    /// Compact at global index `g` whose first child is at global index
    /// `first`: the node becomes B when its four children are B.
    #[inline]
    pub fn compact_at(&mut self, g: usize, first: usize) {
        if self.sons_at(first) == BLACK * 0b0101_0101 {
            self.set_at(g, BLACK);
        }
    }

    /// Refine: a W or B node `card` of depth `depth` becomes G with four
    /// children of its colour; a G node is left as it is.
    #[inline]
    pub fn refine(&mut self, tree: usize, depth: u32, card: usize) {
        let index = self.index(depth, card);
        let colour = self.get(tree, index);
        if colour != GRAY {
            let first = self.index(depth + 1, 4 * card);
            for j in 0..4 {
                self.set(tree, first + j, colour);
            }
            self.set(tree, index, GRAY);
        }
    }

    /// Compact: node `card` of depth `depth` becomes B when its four children are B.
    #[inline]
    pub fn compact(&mut self, tree: usize, depth: u32, card: usize) {
        let first = self.index(depth + 1, 4 * card);
        if (0..4).all(|j| self.get(tree, first + j) == BLACK) {
            let index = self.index(depth, card);
            self.set(tree, index, BLACK);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indexing_and_bound() {
        let b = BlockingBitmaps::new(3, 8);
        assert_eq!(b.index(0, 0), 0);
        assert_eq!(b.index(1, 3), 4);
        assert_eq!(b.index(2, 0), 5);
        // Three bitmaps of a 256^3 octree take 4^8 = 65536 bytes (the paper's bound).
        assert_eq!(b.bytes(), 1 << 16);
    }

    #[test]
    fn refine_and_compact() {
        let mut b = BlockingBitmaps::new(2, 3);
        b.set(1, 0, BLACK);
        b.refine(1, 0, 0);
        assert_eq!(b.get(1, 0), GRAY);
        assert!((1..5).all(|i| b.get(1, i) == BLACK));
        assert!((0..5).all(|i| b.get(0, i) == WHITE), "tree 0 untouched");
        b.set(1, 2, WHITE);
        b.compact(1, 0, 0);
        assert_eq!(b.get(1, 0), GRAY);
        b.set(1, 2, BLACK);
        b.compact(1, 0, 0);
        assert_eq!(b.get(1, 0), BLACK);
    }

    #[test]
    fn first_son_and_sibling_bytes_agree_with_the_paper_formulas() {
        // Every node of every tree of a depth-4 bitmap set: formula (3) as
        // `first_son_at`, and refine/compact through the packed sibling
        // bytes equal to four single bit-pair writes.
        let trees = 3;
        let n = 4;
        for tree in 0..trees {
            for depth in 0..n {
                for card in 0..1usize << (2 * depth) {
                    let mut b = BlockingBitmaps::new(trees, n);
                    let g = b.node(tree, depth, card);
                    let first = b.node(tree, depth + 1, 4 * card);
                    assert_eq!(b.first_son_at(tree, g), first);
                    let after = (first + 4).min(trees * b.nodes - 1);
                    b.set_at(first - 1, GRAY);
                    b.set_at(after, GRAY);
                    b.set_at(g, BLACK);
                    b.refine_at(g, first);
                    assert_eq!(b.get_at(g), GRAY);
                    assert!((0..4).all(|j| b.get_at(first + j) == BLACK));
                    if after == first + 4 {
                        assert_eq!((b.get_at(first - 1), b.get_at(after)), (GRAY, GRAY), "neighbours kept");
                    }
                    b.set_at(first + 3, WHITE);
                    b.compact_at(g, first);
                    assert_eq!(b.get_at(g), GRAY, "three black children do not compact");
                    b.set_at(first + 3, BLACK);
                    b.compact_at(g, first);
                    assert_eq!(b.get_at(g), BLACK);
                }
            }
        }
    }

    #[test]
    #[allow(clippy::needless_range_loop)]
    fn quad_tab_maps_the_four_octants_of_a_face_column_to_distinct_quadrants() {
        // For each axis, the four suboctants on one side of it take the four quadrants.
        for axis in 0..3 {
            for side in 0..2 {
                let mut seen: Vec<u8> =
                    (0..8).filter(|oct| (oct >> axis) & 1 == side).map(|oct| QUAD_TAB[oct][axis]).collect();
                seen.sort();
                assert_eq!(seen, vec![0, 1, 2, 3], "axis {axis} side {side}");
            }
        }
    }
}
