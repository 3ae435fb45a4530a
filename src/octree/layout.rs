//! Levels, node numbering and node boxes of the Volume Octree.
//!
//! ```text
//! level 0 (root)      one node of 2^L cells per axis, covering the grid padded to a power of two
//! level k             nodes of 2^(L-k) cells per axis
//! level L - log2(B)   leaf bricks of B cells per axis (B = leaf size)
//! ```
//!
//! `L = max(ceil(log2(max cells per axis)), log2(B))`. A node at level k with
//! integer coordinates `(i, j, k)` covers the closed index box
//! `[i*S, min((i+1)*S, nx-1)] x ...` with `S = 2^(L-k)`, sharing its face
//! samples with its neighbours. Only nodes that overlap the real grid exist:
//! level k has `ceil(cells_a / S)` nodes along axis a, so padding is virtual
//! (no node lies wholly in the padding, no padded copy of the data is made).
//!
//! Nodes are numbered level by level, x fastest inside a level:
//! `id = offset(k) + i + nx_k * (j + ny_k * k)`. The tree is implicit: the
//! children of `(i, j, k)` are the existing nodes `(2i + dx, 2j + dy, 2k + dz)`
//! of the next level, so no pointers are stored.

use crate::base::error::{Error, Result};

/// Index of a node in the level-by-level numbering.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct NodeId(pub u32);

/// The level structure of a Volume Octree over a grid of given dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Samples per axis of the grid.
    pub dims: [usize; 3],
    /// `L`: the root spans `2^L` cells per axis.
    pub root_log2: u32,
    /// `log2(B)`: a leaf brick spans `B` cells per axis.
    pub leaf_log2: u32,
    level_dims: Vec<[usize; 3]>,
    level_offset: Vec<usize>,
}

impl Layout {
    /// The layout for a grid of `dims` samples with leaf bricks of `leaf_size`
    /// cells (a power of two from 2 to 256).
    pub fn new(dims: [usize; 3], leaf_size: usize) -> Result<Layout> {
        if !(2..=256).contains(&leaf_size) || !leaf_size.is_power_of_two() {
            return Err(Error::BadLeafSize { leaf_size });
        }
        if dims.iter().any(|&d| d < 2) {
            return Err(Error::DimsTooSmall { dims });
        }
        let max_cells = dims.iter().map(|d| d - 1).max().unwrap_or(1);
        let leaf_log2 = leaf_size.trailing_zeros();
        let root_log2 = max_cells.next_power_of_two().trailing_zeros().max(leaf_log2);
        let levels = (root_log2 - leaf_log2 + 1) as usize;
        let mut level_dims = Vec::with_capacity(levels);
        let mut level_offset = Vec::with_capacity(levels + 1);
        let mut offset = 0usize;
        for k in 0..levels {
            let size = 1usize << (root_log2 as usize - k);
            let d = [0, 1, 2].map(|a| (dims[a] - 1).div_ceil(size));
            level_offset.push(offset);
            offset += d[0] * d[1] * d[2];
            level_dims.push(d);
        }
        level_offset.push(offset);
        if offset > u32::MAX as usize {
            return Err(Error::InvalidArgument(format!(
                "{offset} octree nodes do not fit a 32-bit node index; use a larger leaf brick size"
            )));
        }
        Ok(Layout { dims, root_log2, leaf_log2, level_dims, level_offset })
    }

    /// Number of levels (root is 0, leaves are `levels() - 1`).
    pub fn levels(&self) -> usize {
        self.level_dims.len()
    }
    /// The leaf level.
    pub fn leaf_level(&self) -> usize {
        self.levels() - 1
    }
    /// Leaf brick size B in cells.
    pub fn leaf_size(&self) -> usize {
        1 << self.leaf_log2
    }
    /// Root size 2^L in cells.
    pub fn root_size(&self) -> usize {
        1 << self.root_log2
    }
    /// Cells per axis of a node at `level`: `2^(L - level)`.
    pub fn node_size(&self, level: usize) -> usize {
        1 << (self.root_log2 as usize - level)
    }
    /// Nodes per axis at `level`.
    pub fn level_dims(&self, level: usize) -> [usize; 3] {
        self.level_dims[level]
    }
    /// First id of `level`; `level_offset(levels())` is the node array length.
    pub fn level_offset(&self, level: usize) -> usize {
        self.level_offset[level]
    }
    /// Total entries of the node arrays (all levels, reachable or not).
    pub fn node_slots(&self) -> usize {
        self.level_offset[self.levels()]
    }
    /// Number of nodal errors stored for a node at `level`: `L - level`
    /// (p = 0 .. L-level-1; e_(L-level) = 0 is not stored).
    pub fn error_count(&self, level: usize) -> usize {
        self.root_log2 as usize - level
    }

    /// Id of node `c` at `level`.
    pub fn id(&self, level: usize, c: [usize; 3]) -> NodeId {
        let d = self.level_dims[level];
        debug_assert!(c[0] < d[0] && c[1] < d[1] && c[2] < d[2]);
        NodeId((self.level_offset[level] + c[0] + d[0] * (c[1] + d[1] * c[2])) as u32)
    }

    /// The node one level up that holds `id`; `None` for the root.
    pub fn parent(&self, id: NodeId) -> Option<NodeId> {
        let (level, c) = self.locate(id);
        (level > 0).then(|| self.id(level - 1, c.map(|v| v / 2)))
    }

    /// Level and coordinates of `id`.
    pub fn locate(&self, id: NodeId) -> (usize, [usize; 3]) {
        let id = id.0 as usize;
        let level = self.level_offset.partition_point(|&o| o <= id) - 1;
        let local = id - self.level_offset[level];
        let d = self.level_dims[level];
        (level, [local % d[0], (local / d[0]) % d[1], local / (d[0] * d[1])])
    }

    /// Closed index box `[lo, hi]` of node `c` at `level`, clipped to the grid.
    pub fn node_box(&self, level: usize, c: [usize; 3]) -> ([usize; 3], [usize; 3]) {
        let s = self.node_size(level);
        let lo = [c[0] * s, c[1] * s, c[2] * s];
        let hi = [0, 1, 2].map(|a| (lo[a] + s).min(self.dims[a] - 1));
        (lo, hi)
    }

    /// Where each level's nodal errors start in the octree's error arrays
    /// (each node of level `k` holds [`Self::error_count`]`(k)` of them, in
    /// node order), and their total last: `levels() + 1` entries.
    pub fn error_offsets(&self) -> Vec<usize> {
        let mut offsets = Vec::with_capacity(self.levels() + 1);
        let mut total = 0usize;
        for level in 0..self.levels() {
            offsets.push(total);
            let d = self.level_dims(level);
            total += d[0] * d[1] * d[2] * self.error_count(level);
        }
        offsets.push(total);
        offsets
    }

    /// Children of node `c` at `level` (none at the leaf level), in z, y, x order.
    pub fn children(&self, level: usize, c: [usize; 3]) -> impl Iterator<Item = (usize, [usize; 3])> + '_ {
        let next = level + 1;
        let d = if next < self.levels() { self.level_dims[next] } else { [0; 3] };
        (0..8usize).filter_map(move |o| {
            let cc = [2 * c[0] + (o & 1), 2 * c[1] + ((o >> 1) & 1), 2 * c[2] + ((o >> 2) & 1)];
            (cc[0] < d[0] && cc[1] < d[1] && cc[2] < d[2]).then_some((next, cc))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_of_257_samples() {
        let l = Layout::new([257; 3], 16).unwrap();
        assert_eq!((l.root_log2, l.levels(), l.root_size()), (8, 5, 256));
        assert_eq!(l.level_dims(4), [16; 3]);
        assert_eq!(l.node_slots(), 1 + 8 + 64 + 512 + 4096);
        assert_eq!(l.error_count(0), 8);
        assert_eq!(l.error_count(4), 4);
    }

    #[test]
    fn non_power_of_two_is_padded_virtually() {
        let l = Layout::new([100, 40, 3], 8).unwrap();
        assert_eq!(l.root_size(), 128);
        assert_eq!(l.level_dims(l.leaf_level()), [13, 5, 1]);
        let (lo, hi) = l.node_box(l.leaf_level(), [12, 4, 0]);
        assert_eq!((lo, hi), ([96, 32, 0], [99, 39, 2]));
        assert_eq!(l.node_box(0, [0; 3]), ([0; 3], [99, 39, 2]));
    }

    #[test]
    fn tiny_grid_is_one_leaf() {
        let l = Layout::new([2, 2, 2], 16).unwrap();
        assert_eq!((l.levels(), l.node_slots()), (1, 1));
        assert_eq!(l.children(0, [0; 3]).count(), 0);
    }

    #[test]
    fn ids_round_trip_and_children_exist() {
        let l = Layout::new([70, 33, 20], 4).unwrap();
        for level in 0..l.levels() {
            let d = l.level_dims(level);
            for z in 0..d[2] {
                for y in 0..d[1] {
                    for x in 0..d[0] {
                        let id = l.id(level, [x, y, z]);
                        assert_eq!(l.locate(id), (level, [x, y, z]));
                        if level < l.leaf_level() {
                            assert!(l.children(level, [x, y, z]).count() >= 1);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn bad_leaf_sizes_are_refused() {
        for b in [0, 1, 3, 12, 512] {
            assert!(matches!(Layout::new([9; 3], b), Err(Error::BadLeafSize { .. })));
        }
    }
}
