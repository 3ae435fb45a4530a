//! The built Volume Octree and read access to its nodes.

use super::layout::{Layout, NodeId};

/// A Volume Octree: per node min, max and the nodal error envelope
/// `E_p`, `p = 0 .. L-k-1` (see [`super::build`]), stored in flat arrays
/// indexed by [`NodeId`]. The samples stay with the caller.
///
/// Equality compares the tree (layout, ranges, errors), not the build time.
#[derive(Debug, Clone)]
pub struct VolumeOctree {
    pub(crate) layout: Layout,
    pub(crate) min: Vec<f64>,
    pub(crate) max: Vec<f64>,
    pub(crate) errors: Vec<f32>,
    /// Q_p per node, laid out as `errors`.
    pub(crate) squared_errors: Vec<f32>,
    pub(crate) error_offset: Vec<usize>,
    pub(crate) build_ms: f64,
}

impl PartialEq for VolumeOctree {
    fn eq(&self, other: &Self) -> bool {
        self.layout == other.layout
            && self.min == other.min
            && self.max == other.max
            && self.errors == other.errors
            && self.squared_errors == other.squared_errors
            && self.error_offset == other.error_offset
    }
}

/// One node, borrowed from the octree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeRef<'a> {
    /// The node's id.
    pub id: NodeId,
    /// Level: 0 is the root.
    pub level: usize,
    /// Node coordinates within its level.
    pub coords: [usize; 3],
    /// Closed index box, clipped to the grid.
    pub lo: [usize; 3],
    /// Closed index box, clipped to the grid.
    pub hi: [usize; 3],
    /// Smallest sample in the box.
    pub min: f64,
    /// Largest sample in the box.
    pub max: f64,
    /// `errors[p]` = E_p normalised by the data range, p = 0 .. L-level-1
    /// (E_(L-level) = 0 is implied). Empty for a 1-cell root.
    pub errors: &'a [f32],
    /// `squared_errors[p]` = Q_p, the squared error of drawing the node at
    /// level p, summed over its samples, normalised by the squared data range
    /// (see [`super::build`]); laid out as `errors`.
    pub squared_errors: &'a [f32],
    /// True for leaf bricks (minimal resolution nodes).
    pub is_leaf: bool,
}

impl NodeRef<'_> {
    /// E_0 = 0: the data is trilinear over the node.
    pub fn is_homogeneous(&self) -> bool {
        self.errors.first().is_none_or(|&e| e == 0.0)
    }
    /// Terminal: never refined (homogeneous or a leaf brick).
    pub fn is_terminal(&self) -> bool {
        self.is_leaf || self.is_homogeneous()
    }
    /// E_p for any p, with E_p = 0 for p >= L - level.
    pub fn error(&self, p: usize) -> f32 {
        self.errors.get(p).copied().unwrap_or(0.0)
    }
    /// Q_p for any p, with Q_p = 0 for p >= L - level.
    pub fn squared_error(&self, p: usize) -> f32 {
        self.squared_errors.get(p).copied().unwrap_or(0.0)
    }
}

/// Counts, levels, memory and time of a built octree.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OctreeStats {
    /// Nodes reachable from the root through non-terminal nodes.
    pub node_count: usize,
    /// Reachable terminal nodes (the finest cut of the tree).
    pub terminal_count: usize,
    /// Reachable homogeneous nodes (E_0 = 0).
    pub homogeneous_count: usize,
    /// Reachable nodes per level.
    pub nodes_per_level: Vec<usize>,
    /// Number of levels.
    pub levels: usize,
    /// Leaf brick size in cells.
    pub leaf_size: usize,
    /// Root size in cells (the padded power of two).
    pub root_size: usize,
    /// Bytes owned by the octree (borrowed samples excluded).
    pub octree_bytes: usize,
    /// Build time in milliseconds.
    pub build_ms: f64,
    /// (min, max) of the data.
    pub value_range: (f64, f64),
}

impl VolumeOctree {
    pub(crate) fn from_parts(
        layout: Layout,
        min: Vec<f64>,
        max: Vec<f64>,
        errors: Vec<f32>,
        squared_errors: Vec<f32>,
        error_offset: Vec<usize>,
        build_ms: f64,
    ) -> VolumeOctree {
        VolumeOctree { layout, min, max, errors, squared_errors, error_offset, build_ms }
    }

    /// The level structure.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
    /// The root node's id.
    pub fn root(&self) -> NodeId {
        NodeId(0)
    }
    /// (min, max) of the whole grid.
    pub fn value_range(&self) -> (f64, f64) {
        (self.min[0], self.max[0])
    }

    /// The node `id`. Panics on an id not from this octree (a caller bug).
    pub fn node(&self, id: NodeId) -> NodeRef<'_> {
        let (level, coords) = self.layout.locate(id);
        self.node_at(id, level, coords)
    }

    /// The node `id` at `level` and `coords` (what [`Layout::locate`]
    /// says of `id`; a caller that walks the tree knows them).
    pub fn node_at(&self, id: NodeId, level: usize, coords: [usize; 3]) -> NodeRef<'_> {
        let (lo, hi) = self.layout.node_box(level, coords);
        let n = self.layout.error_count(level);
        let local = id.0 as usize - self.layout.level_offset(level);
        let start = self.error_offset[level] + local * n;
        NodeRef {
            id,
            level,
            coords,
            lo,
            hi,
            min: self.min[id.0 as usize],
            max: self.max[id.0 as usize],
            errors: &self.errors[start..start + n],
            squared_errors: &self.squared_errors[start..start + n],
            is_leaf: level == self.layout.leaf_level(),
        }
    }

    /// Children of `id` in the tree: empty for terminal nodes.
    pub fn children(&self, id: NodeId) -> Vec<NodeId> {
        let node = self.node(id);
        if node.is_terminal() {
            return Vec::new();
        }
        self.layout.children(node.level, node.coords).map(|(l, c)| self.layout.id(l, c)).collect()
    }

    /// Visits every reachable node depth first, children in z, y, x order.
    pub fn for_each_node(&self, mut f: impl FnMut(NodeRef<'_>)) {
        let mut stack = vec![self.root()];
        while let Some(id) = stack.pop() {
            f(self.node(id));
            let mut kids = self.children(id);
            kids.reverse();
            stack.extend(kids);
        }
    }

    /// Bytes owned by the octree: node arrays plus the layout tables.
    pub fn octree_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.min.capacity() * 8
            + self.max.capacity() * 8
            + self.errors.capacity() * 4
            + self.squared_errors.capacity() * 4
            + self.error_offset.capacity() * std::mem::size_of::<usize>()
            + self.layout.levels() * (3 + 1) * std::mem::size_of::<usize>()
    }

    /// Counts, levels, memory and build time.
    pub fn stats(&self) -> OctreeStats {
        let mut s = OctreeStats {
            node_count: 0,
            terminal_count: 0,
            homogeneous_count: 0,
            nodes_per_level: vec![0; self.layout.levels()],
            levels: self.layout.levels(),
            leaf_size: self.layout.leaf_size(),
            root_size: self.layout.root_size(),
            octree_bytes: self.octree_bytes(),
            build_ms: self.build_ms,
            value_range: self.value_range(),
        };
        self.for_each_node(|n| {
            s.node_count += 1;
            s.nodes_per_level[n.level] += 1;
            s.terminal_count += n.is_terminal() as usize;
            s.homogeneous_count += n.is_homogeneous() as usize;
        });
        s
    }
}
