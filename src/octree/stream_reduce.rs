//! The reduction up the tree of [`super::build`], fed one z-row of nodes at
//! a time: a row of level `k` waits until the row beside it (same parent
//! row) arrives, then makes the parents' row of level `k - 1`. Children are
//! folded in the order [`super::build`]'s reduction takes them (z, y, x), so
//! maxima and sums, and the octree, are the same bit for bit; memory is two
//! rows per level plus each node's own strides, never all leaves at once.

use super::build::{normalise, squared_error};
use super::layout::Layout;
use super::leaf_stats::{LeafStats, HOLE};
use super::volume_octree::VolumeOctree;
use crate::base::error::Result;
use crate::base::limits::check_memory;

/// One z-row of nodes of a level: per node min, max and, per stride
/// `2^j`, `j = 1 ..= L`, the raw error, squared error and holes.
#[derive(Debug, Clone, Default)]
struct Row {
    min: Vec<f64>,
    max: Vec<f64>,
    /// `[node * L + j - 1]`.
    raw: Vec<f64>,
    squared: Vec<f64>,
    holes: Vec<f64>,
}

/// The streaming reduction; see the module docs.
#[derive(Debug)]
pub struct StreamReduce {
    layout: Layout,
    strides: usize,
    min: Vec<f64>,
    max: Vec<f64>,
    /// Each node's own raw errors, strides `2^1 ..= 2^(L - k)`, laid out as the octree's errors.
    raw: Vec<f64>,
    squared: Vec<f64>,
    holes: Vec<f64>,
    error_offset: Vec<usize>,
    /// Per level, the rows waiting for their sibling row: (z index, row).
    pending: Vec<Vec<(usize, Row)>>,
}

impl StreamReduce {
    /// A reduction over `layout`, its memory checked before it is allocated.
    pub fn new(layout: Layout) -> Result<StreamReduce> {
        let error_offset = layout.error_offsets();
        let total = error_offset[layout.levels()];
        let slots = layout.node_slots();
        check_memory(
            (total as u128) * 3 * 8 + (slots as u128) * 16,
            "the streaming octree build's node arrays",
            "use a larger --leaf-size",
        )?;
        Ok(StreamReduce {
            strides: layout.root_log2 as usize,
            min: vec![0.0; slots],
            max: vec![0.0; slots],
            raw: vec![0.0; total],
            squared: vec![0.0; total],
            holes: vec![0.0; total],
            pending: vec![Vec::new(); layout.levels()],
            error_offset,
            layout,
        })
    }

    /// Takes leaf row `z` (the leaves in x-fastest order).
    pub fn push_leaves(&mut self, z: usize, leaves: Vec<LeafStats>) {
        let l = self.strides;
        let mut row = Row {
            min: Vec::with_capacity(leaves.len()),
            max: Vec::with_capacity(leaves.len()),
            raw: Vec::with_capacity(leaves.len() * l),
            squared: Vec::with_capacity(leaves.len() * l),
            holes: Vec::with_capacity(leaves.len() * l),
        };
        for s in leaves {
            row.min.push(s.min);
            row.max.push(s.max);
            row.raw.extend_from_slice(&s.raw);
            row.squared.extend_from_slice(&s.squared);
            row.holes.extend_from_slice(&s.holes);
        }
        self.push_row(self.layout.leaf_level(), z, row);
    }

    /// Stores row `z` of `level` and, when its parents' row is complete, reduces it.
    fn push_row(&mut self, level: usize, z: usize, row: Row) {
        let (l, n) = (self.strides, self.layout.error_count(level));
        let d = self.layout.level_dims(level);
        let first = self.layout.level_offset(level) + z * d[0] * d[1];
        let errors = self.error_offset[level] + z * d[0] * d[1] * n;
        for i in 0..d[0] * d[1] {
            self.min[first + i] = row.min[i];
            self.max[first + i] = row.max[i];
            let (at, from) = (errors + i * n, i * l);
            self.raw[at..at + n].copy_from_slice(&row.raw[from..from + n]);
            self.squared[at..at + n].copy_from_slice(&row.squared[from..from + n]);
            self.holes[at..at + n].copy_from_slice(&row.holes[from..from + n]);
        }
        if level == 0 {
            return;
        }
        self.pending[level].push((z, row));
        let parent_z = z / 2;
        if z.is_multiple_of(2) && 2 * parent_z + 1 < d[2] {
            return;
        }
        let rows = std::mem::take(&mut self.pending[level]);
        let parent = self.parents(level, &rows);
        self.push_row(level - 1, parent_z, parent);
    }

    /// The row of level `level - 1` whose children are `rows` (one or two
    /// rows of `level`, in z order), each parent folding its children in
    /// z, y, x order as [`super::build`]'s reduction does.
    fn parents(&self, level: usize, rows: &[(usize, Row)]) -> Row {
        let l = self.strides;
        let d = self.layout.level_dims(level);
        let pd = self.layout.level_dims(level - 1);
        let count = pd[0] * pd[1];
        let mut out = Row {
            min: vec![f64::INFINITY; count],
            max: vec![f64::NEG_INFINITY; count],
            raw: vec![0.0; count * l],
            squared: vec![0.0; count * l],
            holes: vec![0.0; count * l],
        };
        for y in 0..pd[1] {
            for x in 0..pd[0] {
                let p = x + pd[0] * y;
                for (_, row) in rows {
                    for dy in 0..2 {
                        for dx in 0..2 {
                            let (cx, cy) = (2 * x + dx, 2 * y + dy);
                            if cx >= d[0] || cy >= d[1] {
                                continue;
                            }
                            let c = cx + d[0] * cy;
                            out.min[p] = out.min[p].min(row.min[c]);
                            out.max[p] = out.max[p].max(row.max[c]);
                            for j in 0..l {
                                let (a, b) = (p * l + j, c * l + j);
                                out.raw[a] = out.raw[a].max(row.raw[b]);
                                out.squared[a] += row.squared[b];
                                out.holes[a] += row.holes[b];
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// The octree, once every leaf row has been pushed: the errors of
    /// `scale` times the data normalised by its range, as [`super::build`].
    pub fn finish(self, scale: f64, build_ms: f64) -> VolumeOctree {
        debug_assert!(self.pending.iter().all(Vec::is_empty));
        let range = self.max[0] * scale - self.min[0] * scale;
        let range2 = if range > 0.0 { range * range } else { 1.0 };
        let layout = &self.layout;
        let total = self.error_offset[layout.levels()];
        let mut errors = vec![0.0f32; total];
        let mut squared_errors = vec![0.0f32; total];
        for level in 0..layout.levels() {
            let n = layout.error_count(level);
            let count = layout.level_offset(level + 1) - layout.level_offset(level);
            for local in 0..count {
                let at = self.error_offset[level] + local * n;
                let (r, q, h) = (&self.raw[at..at + n], &self.squared[at..at + n], &self.holes[at..at + n]);
                for (p, e2) in squared_errors[at..at + n].iter_mut().enumerate() {
                    *e2 = squared_error(q[n - p - 1], h[n - p - 1], range2);
                }
                let mut envelope = 0.0f64;
                for p in (0..n).rev() {
                    envelope = envelope.max(r[n - p - 1]);
                    errors[at + p] = if envelope == HOLE { 1.0 } else { normalise(envelope, range) };
                }
            }
        }
        VolumeOctree::from_parts(self.layout, self.min, self.max, errors, squared_errors, self.error_offset, build_ms)
    }
}
