//! The greedy refinement of one start (see [`super`]): a priority queue
//! over the cut, recorded so that the next selection under another budget
//! replays what that budget leaves unchanged.
//!
//! The budget enters the greedy in one place: a popped step is taken when
//! the bytes after it fit, `need = bytes - cost + added <= budget`; one that
//! does not fit queues its brick's best smaller step in its place.
//! Everything else (which steps are queued, the order they pop in, the
//! cut they change) follows from the steps taken before. So a run under
//! budget `B'` takes the same steps as the recorded run under `B` up to
//! the first pop `t` where `(need <= B') != taken`, and from there on
//! continues as a run of its own. The state before pop `t` is rebuilt
//! from the record:
//!
//! ```text
//! queue before pop t = steps pushed before pop t, not popped before it
//! cut before pop t   = bricks put before pop t, not taken out before it
//! ```
//!
//! Queued steps are totally ordered ([`Queued`]'s `Ord`), so a queue
//! rebuilt from the same pushes pops them in the same order: the run
//! equals a fresh one.

use super::super::steps::{Log, Pop, Push, Put, Queued, Step, NEVER};
use super::{Brick, NodeId, Refiner, Replacement};
use std::collections::BinaryHeap;

/// A run in progress: its record, the cut (per node id, its put, or
/// `NEVER`), the queue, the bytes and the transparent nodes.
struct Run {
    log: Log,
    cut: Vec<usize>,
    queue: BinaryHeap<Queued>,
    bytes: usize,
    skipped: usize,
}

impl Run {
    /// The state of `log` before its first pop that `budget` decides
    /// otherwise (or at its end), its record cut there.
    fn resume(mut log: Log, budget: usize, slots: usize) -> Run {
        let pops = &log.pops;
        let t = pops.iter().position(|p| p.need != NEVER && (p.need <= budget) != p.taken).unwrap_or(pops.len());
        let (bytes, skipped) = pops.get(t).map_or((log.bytes, log.skipped), |p| (p.bytes, p.skipped));
        log.pops.truncate(t);
        log.pushes.truncate(log.pushes.partition_point(|p| p.at <= t));
        log.puts.truncate(log.puts.partition_point(|p| p.at <= t));
        let mut waiting = Vec::new();
        for (k, push) in log.pushes.iter_mut().enumerate() {
            if push.popped != NEVER && push.popped >= t {
                push.popped = NEVER;
            }
            if push.popped == NEVER {
                waiting.push(Queued::of(&push.step, k));
            }
        }
        let mut cut = vec![NEVER; slots];
        for (k, put) in log.puts.iter_mut().enumerate() {
            if put.taken != NEVER && put.taken >= t {
                put.taken = NEVER;
            }
            if put.taken == NEVER {
                cut[put.node.0 as usize] = k;
            }
        }
        Run { log, cut, queue: BinaryHeap::from(waiting), bytes, skipped }
    }

    /// Puts node `id` at level `p` with `points` points in the cut.
    fn put(&mut self, id: NodeId, p: usize, points: usize) {
        let at = self.log.pops.len();
        self.cut[id.0 as usize] = self.log.puts.len();
        self.log.puts.push(Put { node: id, p, points, at, taken: NEVER });
    }

    /// Queues step `index` (of [`Refiner::step_index`]), if any.
    fn push(&mut self, refiner: &Refiner<'_>, index: Option<usize>) {
        if let Some(index) = index {
            let step = refiner.caches.entries.borrow()[index].step;
            let k = self.log.pushes.len();
            self.log.pushes.push(Push { step, index, at: self.log.pops.len(), popped: NEVER });
            self.queue.push(Queued::of(&step, k));
        }
    }

    /// Whether the cut holds the brick `step` was queued for.
    fn holds(&self, step: &Step) -> bool {
        self.cut[step.node.0 as usize] != NEVER && {
            let put = &self.log.puts[self.cut[step.node.0 as usize]];
            put.p == step.p && put.points == step.points
        }
    }
}

impl Refiner<'_> {
    /// The own bricks of a raise or a split (none for points), as (node,
    /// level), appended to `out` in order: a raise's form, a split's
    /// children in octree order.
    fn replacement_bricks(&self, replacement: &Replacement, out: &mut Vec<(NodeId, usize)>) {
        let store = self.caches.forms.borrow();
        let mut own = |node, q, _, _| out.push((node, q));
        match *replacement {
            Replacement::Points(..) => {}
            Replacement::Raise(form, _) => store.each_own(form, &mut own),
            Replacement::Split(split, _) => {
                for &form in store.kids_of(store.splits[split as usize].kids) {
                    store.each_own(form, &mut own);
                }
            }
        }
    }

    /// Greedy refinement from `start` (the start's level `p` of the root's
    /// form; none: the root at `p = 0`), whose bricks and transparent
    /// nodes `bricks` makes, until nothing fits: the cut (by node id), its
    /// bytes, its transparent nodes. Replays the start's record when the
    /// steps are kept (see the module documentation).
    pub(super) fn grow(
        &self,
        start: Option<usize>,
        bricks: impl FnOnce() -> (Vec<Brick>, usize),
    ) -> (Vec<Brick>, usize, usize) {
        let slots = self.octree.layout().node_slots();
        let kept = {
            let mut logs = self.caches.logs.borrow_mut();
            logs.iter().position(|(s, _)| *s == start).map(|i| logs.swap_remove(i).1)
        };
        let mut run = match kept {
            Some(log) => Run::resume(log, self.options.budget_bytes, slots),
            None => {
                let (bricks, skipped) = bricks();
                let mut run =
                    Run { log: Log::default(), cut: vec![NEVER; slots], queue: BinaryHeap::new(), bytes: 0, skipped };
                for b in &bricks {
                    run.bytes += Self::cost(b);
                    run.put(b.node, b.p, b.point_count);
                    run.push(self, self.step_index(b, true));
                }
                run
            }
        };
        let mut bricks = Vec::new();
        while let Some(Queued { push, .. }) = run.queue.pop() {
            let t = run.log.pops.len();
            let Push { step, index, .. } = run.log.pushes[push];
            run.log.pushes[push].popped = t;
            let mut pop = Pop { bytes: run.bytes, skipped: run.skipped, need: NEVER, taken: false };
            if run.holds(&step) {
                let (cost, added, hidden, replacement) = {
                    let entries = self.caches.entries.borrow();
                    let e = &entries[index];
                    (e.cost, e.added, e.hidden, e.replacement)
                };
                pop.need = run.bytes - cost + added;
                // Does not fit: cheaper steps of other nodes may.
                pop.taken = pop.need <= self.options.budget_bytes;
                if pop.taken {
                    run.log.pops.push(pop);
                    run.bytes = pop.need;
                    run.log.puts[run.cut[step.node.0 as usize]].taken = t;
                    run.cut[step.node.0 as usize] = NEVER;
                    run.skipped += hidden;
                    if let Replacement::Points(count, _) = replacement {
                        let b = self.brick_with_points(step.node, step.p, count);
                        run.put(b.node, b.p, b.point_count);
                        run.push(self, self.step_index(&b, true));
                    }
                    bricks.clear();
                    self.replacement_bricks(&replacement, &mut bricks);
                    for &(node, q) in &bricks {
                        run.put(node, q, 0);
                        run.push(self, self.own_step_index(node, q));
                    }
                    continue;
                }
            }
            run.log.pops.push(pop);
            // A step that did not fit leaves its brick a smaller one (pushed
            // after the pop: the pop's decision made it).
            if pop.need != NEVER {
                run.push(self, self.fallback_index(index));
            }
        }
        let (bytes, skipped) = (run.bytes, run.skipped);
        run.log.bytes = bytes;
        run.log.skipped = skipped;
        let mut bricks = Vec::new();
        for &k in run.cut.iter().filter(|&&k| k != NEVER) {
            let put = &run.log.puts[k];
            bricks.push(self.brick_with_points(put.node, put.p, put.points));
        }
        self.caches.logs.borrow_mut().push((start, run.log));
        (bricks, bytes, skipped)
    }
}
