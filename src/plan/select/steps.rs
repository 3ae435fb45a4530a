//! The greedy's queue entries and the record of a run: what the refinement
//! (`refine`) queues and what its replay (`refine::greedy`) reads back.

use crate::octree::NodeId;
use std::cmp::Ordering;

/// A refinement step in the queue.
#[derive(Debug, Clone, Copy)]
pub(super) struct Step {
    /// Weighted error removed per byte added.
    pub(super) gain: f64,
    pub(super) node: NodeId,
    /// The node's p when the step was queued (stale steps are skipped).
    pub(super) p: usize,
    /// The node's point count when the step was queued (likewise).
    pub(super) points: usize,
}

impl PartialEq for Step {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Step {}
impl PartialOrd for Step {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Step {
    /// By gain, ties to the smaller node id (then level, then points: one
    /// order for any two steps, whatever the queue's history).
    fn cmp(&self, o: &Self) -> Ordering {
        self.gain
            .total_cmp(&o.gain)
            .then_with(|| o.node.cmp(&self.node))
            .then_with(|| o.p.cmp(&self.p))
            .then_with(|| o.points.cmp(&self.points))
    }
}

/// A queued step: its kept entry (`Caches::entries`) and its push in the
/// run's record ([`Log`]).
pub(super) struct Queued {
    pub(super) step: Step,
    pub(super) index: usize,
    pub(super) push: usize,
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.step == o.step
    }
}
impl Eq for Queued {}
impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        self.step.cmp(&o.step)
    }
}

/// Not popped, not taken out (yet).
pub(super) const NEVER: usize = usize::MAX;

/// One pop of the queue: the bytes and transparent nodes before it, the
/// bytes after its step if taken (`NEVER`: a stale step, no decision) and
/// whether it was.
#[derive(Clone, Copy)]
pub(super) struct Pop {
    pub(super) bytes: usize,
    pub(super) skipped: usize,
    pub(super) need: usize,
    pub(super) taken: bool,
}

/// A step pushed before pop `at` (while pop `at - 1` was taken; 0: the
/// start), popped at pop `popped`.
#[derive(Clone, Copy)]
pub(super) struct Push {
    pub(super) step: Step,
    pub(super) index: usize,
    pub(super) at: usize,
    pub(super) popped: usize,
}

/// A brick (node, p, points) put in the cut before pop `at`, taken out at
/// pop `taken`.
#[derive(Clone, Copy)]
pub(super) struct Put {
    pub(super) node: NodeId,
    pub(super) p: usize,
    pub(super) points: usize,
    pub(super) at: usize,
    pub(super) taken: usize,
}

/// The record of one start's run ([`Refiner::grow`]): its pops, pushes and
/// puts in order, and its bytes and transparent nodes at the end.
#[derive(Default)]
pub(super) struct Log {
    pub(super) pops: Vec<Pop>,
    pub(super) pushes: Vec<Push>,
    pub(super) puts: Vec<Put>,
    pub(super) bytes: usize,
    pub(super) skipped: usize,
}
