//! A cut being refined by the greedy: which brick each node of the cut
//! draws, in a byte per node slot (its level) and, for the few bricks that
//! took points, their point count.

use super::cache::WordHasher;
use crate::octree::NodeId;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// The cut: per node id, `1 + p` of its brick (0: not in the cut), and the
/// points of the bricks that took them. A brick of the cut is its node
/// drawn at `p` with those points, so node, level and points say all of it.
pub(super) struct Cut {
    levels: Vec<u8>,
    points: HashMap<NodeId, usize, BuildHasherDefault<WordHasher>>,
}

impl Cut {
    /// An empty cut of an octree with `slots` node ids.
    pub fn new(slots: usize) -> Cut {
        Cut { levels: vec![0; slots], points: HashMap::default() }
    }

    /// Puts the brick of node `id` at level `p` (below 255) with `points` points in the cut.
    pub fn put(&mut self, id: NodeId, p: usize, points: usize) {
        self.levels[id.0 as usize] = p as u8 + 1;
        if points > 0 {
            self.points.insert(id, points);
        }
    }

    /// Removes node `id`'s brick.
    pub fn take(&mut self, id: NodeId) {
        self.levels[id.0 as usize] = 0;
        if !self.points.is_empty() {
            self.points.remove(&id);
        }
    }

    /// Whether node `id`'s brick in the cut is at level `p` with `points` points.
    pub fn holds(&self, id: NodeId, p: usize, points: usize) -> bool {
        self.levels[id.0 as usize] == p as u8 + 1 && self.points_of(id) == points
    }

    fn points_of(&self, id: NodeId) -> usize {
        if self.points.is_empty() {
            0
        } else {
            self.points.get(&id).copied().unwrap_or(0)
        }
    }

    /// The bricks of the cut as `(node, p, points)`, by node id.
    pub fn each(&self, f: &mut impl FnMut(NodeId, usize, usize)) {
        for (i, &l) in self.levels.iter().enumerate() {
            if l > 0 {
                let id = NodeId(i as u32);
                f(id, usize::from(l - 1), self.points_of(id));
            }
        }
    }
}
