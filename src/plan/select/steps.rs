//! The greedy's queue entries and the record of a run: what the refinement
//! (`refine`) queues and what its replay (`refine::greedy`) reads back.

use crate::octree::NodeId;
use std::cmp::Ordering;

/// A refinement step, as its push records it ([`Push`]).
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

/// A queued step, as small as the queue can order it by: its gain, its
/// node and its push in the run's record ([`Log`], which holds the step
/// and its kept entry).
///
/// Ordered by gain, ties to the smaller node id, then to the earlier push.
/// Of the queued steps of one node only those queued for the brick the cut
/// holds when they pop are decided (the others are stale and change
/// nothing), and steps queued for one brick are one step: so the cut a run
/// makes does not depend on how ties within a node fall. The push keeps
/// the order total all the same, and a queue rebuilt from the same pushes
/// pops them in the same order.
#[derive(Clone, Copy)]
pub(super) struct Queued {
    pub(super) gain: f64,
    pub(super) node: NodeId,
    pub(super) push: usize,
}

impl Queued {
    /// The queue entry of push `push` of `step`.
    pub(super) fn of(step: &Step, push: usize) -> Queued {
        Queued { gain: step.gain, node: step.node, push }
    }
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
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
        self.gain.total_cmp(&o.gain).then_with(|| o.node.cmp(&self.node)).then_with(|| o.push.cmp(&self.push))
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
