//! Greedy refinement under a texture budget (see the module documentation of
//! [`super`]).

use super::brick::{brick_bytes, importance, make_brick, texels, Brick, SelectOptions, Selection};
use super::cache::NodeMap;
use super::estimate::{estimated_error, seen_rms_error, Seen};
use super::forms::{Forms, NONE, NO_STEP};
use super::mass::{error_mass, gain};
use super::steps::{Log, Step};
use super::view::ViewImportance;
use crate::base::error::{Error, Result};
use crate::octree::{NodeId, NodeRef, VolumeOctree};
use crate::points::PointMass;

mod cheapest;
mod greedy;

/// Selects a cut and levels for `octree` (see the module documentation).
/// `visible(min, max)` says whether a node with that value range shows under
/// the transfer function; return `true` to keep every node.
pub fn select(octree: &VolumeOctree, options: &SelectOptions, visible: impl Fn(f64, f64) -> bool) -> Result<Selection> {
    select_impl(octree, options, &visible, None, None, &Caches::default())
}

/// [`select`] weighted by what the viewer sees ([`ViewImportance`]: the
/// screen-space and visibility importance of a camera), with the points of
/// `points` if given.
pub fn select_in_view(
    octree: &VolumeOctree,
    options: &SelectOptions,
    visible: impl Fn(f64, f64) -> bool,
    points: Option<&PointMass>,
    view: &ViewImportance,
) -> Result<Selection> {
    select_impl(octree, options, &visible, points, Some(view), &Caches::default())
}

/// [`select`] where bricks of stride `points.factor` may also take their
/// points (see the module documentation); the budget covers both.
pub fn select_with_points(
    octree: &VolumeOctree,
    options: &SelectOptions,
    visible: impl Fn(f64, f64) -> bool,
    points: &PointMass,
) -> Result<Selection> {
    select_impl(octree, options, &visible, Some(points), None, &Caches::default())
}

/// What a selection computes once and reuses: the cheapest forms
/// ([`Refiner::cheapest`]) and splits by (node, p) and the best next step
/// of a brick by (node, p, points taken), in [`Forms`].
/// The forms are pure functions of the octree, the visibility test, the
/// options other than the budget, the tolerance and the region of
/// interest, and of the levels where the view stops refinement
/// ([`ViewImportance::coarsest_levels`]); the steps also of the tolerance
/// and the importance (the region of interest and the view weights). One
/// selection fills them, and a [`super::Selector`] keeps what the next
/// one's inputs leave valid.
#[derive(Default)]
pub(super) struct Caches {
    /// The forms, the splits and the steps of bricks without points.
    forms: std::cell::RefCell<Forms>,
    /// Counts the importance functions the forms' weighted masses were
    /// kept for ([`Refiner::form_mass`]).
    epoch: u64,
    /// By (node, p, points) of a brick with points: its next step in
    /// `entries`, none when it has none.
    steps: NodeMap<(NodeId, usize, usize), Option<usize>>,
    entries: std::cell::RefCell<Vec<StepEntry>>,
    /// The record of each start's last run (none: the root at `p = 0`;
    /// the level of the root's form otherwise), made with these steps.
    logs: std::cell::RefCell<Vec<(Option<usize>, Log)>>,
    /// Per node id: its importance `Imp(n)`, NaN until computed; empty
    /// until the first is.
    imp: std::cell::RefCell<Vec<f64>>,
    /// Per node id: its view weight `Imp_view` and the levels below full
    /// resolution where its refinement stops ([`ViewImportance`]), NaN
    /// until computed; empty without a view.
    seen: std::cell::RefCell<Vec<(f32, u8)>>,
}

impl Caches {
    /// Drops the steps (they depend on the tolerance) and the runs made
    /// with them, keeps the forms.
    pub(super) fn forget_steps(&mut self) {
        self.steps.get_mut().clear();
        self.forms.get_mut().forget_steps();
        self.entries.get_mut().clear();
        self.logs.get_mut().clear();
    }

    /// Drops what depends on the importance (the steps, the forms'
    /// weighted masses, and with `view_changed` the view weights), keeps
    /// the forms.
    pub(super) fn reweigh(&mut self, view_changed: bool) {
        self.forget_steps();
        self.epoch += 1;
        self.imp.get_mut().clear();
        if view_changed {
            self.seen.get_mut().clear();
        }
    }
}

/// [`select`] (without points) or [`select_with_points`], filling and
/// weighted by `view` if given ([`select_in_view`]), reusing `caches` (see
/// [`Caches`]: the caller keeps them only for the same octree, visibility
/// test, points, view and options other than the budget).
pub(super) fn select_impl(
    octree: &VolumeOctree,
    options: &SelectOptions,
    visible: &dyn Fn(f64, f64) -> bool,
    points: Option<&PointMass>,
    view: Option<&ViewImportance>,
    caches: &Caches,
) -> Result<Selection> {
    check_options(options)?;
    let root = octree.node(octree.root());
    let (region, slice) = (options.region, options.slice);
    // A node shows when the transfer function shows its values, the kept
    // region does not remove its box and the slice plane (if any) cuts it.
    let shows = move |n: &NodeRef<'_>| {
        let (lo, hi) = (n.lo.map(|v| v as f64), n.hi.map(|v| v as f64));
        visible(n.min, n.max)
            && region.as_ref().is_none_or(|r| !r.removes_box(lo, hi))
            && slice.as_ref().is_none_or(|s| s.cuts_box(lo, hi))
    };
    if !shows(&root) {
        return Ok(Selection {
            bricks: Vec::new(),
            texture_bytes: 0,
            point_bytes: 0,
            budget_bytes: options.budget_bytes,
            max_error: 0.0,
            estimated_error: 0.0,
            estimated_rms_error: 0.0,
            skipped: 1,
            warning: None,
        });
    }
    let refiner = Refiner {
        octree,
        options,
        visible,
        shows: &shows,
        points,
        view: view.filter(|v| !v.is_empty()),
        root_log2: octree.layout().root_log2 as usize,
        slots: octree.layout().node_slots(),
        caches,
    };
    let coarsest = refiner.brick_of(root.id, 0);
    let mut warning = None;
    if coarsest.bytes > options.budget_bytes {
        warning = Some(format!(
            "the budget of {} bytes is below the coarsest representation ({} bytes): drawing that anyway; \
             raise the budget for any refinement",
            options.budget_bytes, coarsest.bytes
        ));
    }
    let (cut, skipped) = refiner.best_cut(&root, coarsest);
    Ok(refiner.selection(cut, skipped, warning))
}

/// The options' own errors: a budget of 0 bytes, a tolerance that is not a
/// number `>= 0`, a region of interest without a finite centre and a radius
/// `> 0`, 0 bytes per texel.
fn check_options(options: &SelectOptions) -> Result<()> {
    if options.budget_bytes == 0 {
        return Err(Error::InvalidArgument(
            "the texture budget is 0 bytes: give a budget of at least a few kilobytes".into(),
        ));
    }
    if !(options.tolerance >= 0.0 && options.tolerance.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "error tolerance {} must be a number >= 0 (a fraction of the data range)",
            options.tolerance
        )));
    }
    if let Some(r) = &options.roi {
        if !(r.radius > 0.0 && r.radius.is_finite()) || r.center.iter().any(|c| !c.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "region of interest (centre {:?}, radius {}) needs a finite centre and a radius > 0",
                r.center, r.radius
            )));
        }
    }
    if let Some(region) = &options.region {
        if let Some(c) = &region.cropping {
            c.check()?;
        }
        for p in region.planes() {
            p.check()?;
        }
    }
    if let Some(plane) = &options.slice {
        plane.check()?;
    }
    if !(options.texel_error >= 0.0 && options.texel_error.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "texel quantization error {} must be a finite number >= 0 (a fraction of the data range)",
            options.texel_error
        )));
    }
    if options.bytes_per_texel == 0 {
        return Err(Error::InvalidArgument("bytes per texel must be at least 1".into()));
    }
    Ok(())
}

/// A brick's next step: the queued step, the bricks that replace the
/// brick, the transparent nodes they leave out, the brick's bytes and
/// theirs (textures and points).
struct StepEntry {
    step: Step,
    replacement: Replacement,
    hidden: usize,
    cost: usize,
    added: usize,
    /// The brick's best step of fewer bytes than this one
    /// ([`Refiner::fallback_index`]): none until computed, then its index
    /// in `Caches::entries` if it has one.
    fallback: std::cell::Cell<Option<Option<usize>>>,
}

/// A candidate step: its gain, the bricks that replace the brick, and the
/// transparent nodes they leave out.
type Candidate = (f64, Replacement, usize);

/// The bricks of a step: the brick taking its points, or the kept forms
/// they come from (a raise's one form, a split's children), read only when
/// the step is taken.
#[derive(Clone, Copy)]
enum Replacement {
    /// The brick with its points: their count and bytes.
    Points(usize, usize),
    /// A form's index in [`Forms::forms`], and its bytes.
    Raise(u32, usize),
    /// A split's index in [`Forms::splits`], and its bytes.
    Split(u32, usize),
}

impl Replacement {
    /// Bytes the bricks hold (textures and points).
    fn cost(&self) -> usize {
        match *self {
            Replacement::Points(_, bytes) | Replacement::Raise(_, bytes) | Replacement::Split(_, bytes) => bytes,
        }
    }
}

/// One selection: its inputs and the [`Caches`] every step shares.
struct Refiner<'a> {
    octree: &'a VolumeOctree,
    options: &'a SelectOptions,
    visible: &'a dyn Fn(f64, f64) -> bool,
    /// `visible` on the node's values, and its box not removed by [`SelectOptions::region`].
    shows: &'a dyn Fn(&NodeRef<'_>) -> bool,
    points: Option<&'a PointMass>,
    /// What the viewer sees of each node ([`ViewImportance`]), or none.
    view: Option<&'a ViewImportance>,
    /// `L`: the root's level count, `log2` of the root's size.
    root_log2: usize,
    /// The octree's node count ([`crate::octree::Layout::node_slots`]).
    slots: usize,
    caches: &'a Caches,
}

impl Refiner<'_> {
    /// The finest level of node `n`: full resolution, the largest brick, or
    /// the finest whose texels the viewer can tell apart ([`ViewImportance::coarsest_levels`]).
    fn max_p(&self, n: &NodeRef<'_>) -> usize {
        self.max_p_at(n.level, self.seen(n).1)
    }

    /// [`Refiner::max_p`] of a node of level `level` whose refinement the
    /// view stops `coarsest` levels below full resolution.
    fn max_p_at(&self, level: usize, coarsest: usize) -> usize {
        let full = self.root_log2 - level;
        full.saturating_sub(coarsest).min(self.options.max_brick_log2 as usize)
    }

    /// `Imp(n) = Imp_roi(n) Imp_view(n)` of node `id`.
    /// Computed once per node and importance.
    fn importance_of(&self, id: NodeId) -> f64 {
        let mut imp = self.caches.imp.borrow_mut();
        if imp.is_empty() {
            imp.resize(self.octree.layout().node_slots(), f64::NAN);
        }
        let slot = &mut imp[id.0 as usize];
        if slot.is_nan() {
            let n = self.octree.node(id);
            *slot = importance(self.options.roi.as_ref(), n.lo, n.hi) * self.seen(&n).0;
        }
        *slot
    }

    /// Brick `b` (of a [`Form`], importance 1) with its node's importance.
    fn weigh(&self, b: &Brick) -> Brick {
        Brick { importance: self.importance_of(b.node), ..*b }
    }

    /// `(Imp_view(n), coarsest levels)` of node `n`, computed once per node
    /// and view (`(1, 0)` without a view).
    fn seen(&self, n: &NodeRef<'_>) -> (f64, usize) {
        let Some(view) = self.view else { return (1.0, 0) };
        let mut seen = self.caches.seen.borrow_mut();
        if seen.is_empty() {
            seen.resize(self.octree.layout().node_slots(), (f32::NAN, 0));
        }
        let slot = &mut seen[n.id.0 as usize];
        if slot.0.is_nan() {
            // Levels below full resolution never exceed the octree's depth (< 64).
            *slot = (view.weight(n) as f32, view.coarsest_levels(n).min(63) as u8);
        }
        (f64::from(slot.0), usize::from(slot.1))
    }

    /// The coarsest levels of [`Refiner::seen`] of node `id`, if known
    /// without its node (0 without a view).
    fn seen_levels(&self, id: NodeId) -> Option<usize> {
        if self.view.is_none() {
            return Some(0);
        }
        let seen = self.caches.seen.borrow();
        seen.get(id.0 as usize).filter(|s| !s.0.is_nan()).map(|s| usize::from(s.1))
    }

    /// `T(n)`: the transmittance in front of node `id` ([`super::Transmittance`]), 1 without a visibility estimate.
    fn transmittance(&self, id: NodeId) -> f64 {
        self.view.map_or(1.0, |v| v.transmittance(self.octree.layout(), id))
    }

    /// The weighted error `Imp(n) e_p(n)` the tolerance is compared with.
    fn weighted(b: &Brick) -> f64 {
        b.importance * b.error as f64
    }

    /// Node `id` drawn at level `p`, with its importance.
    fn brick_of(&self, id: NodeId, p: usize) -> Brick {
        self.weigh(&self.form_brick(id, p))
    }

    /// `bytes(n, p)`: what [`Refiner::form_brick`] holds, without making it.
    fn bytes_at(&self, n: &NodeRef<'_>, p: usize) -> usize {
        let stride = 1usize << (self.root_log2 - n.level - p);
        brick_bytes(texels(n.lo, n.hi, stride), self.options.bytes_per_texel, self.options.gradient_border)
    }

    /// Node `id` drawn at level `p`, with an importance of 1 (a [`Form`]'s brick).
    fn form_brick(&self, id: NodeId, p: usize) -> Brick {
        let n = self.octree.node(id);
        let mut b = make_brick(self.octree, &n, p, 1.0, self.options.bytes_per_texel, self.options.gradient_border);
        // Peak-keeping texels: a coarse brick's error is at least E_pool (see [`error_mass`]).
        if let Some(inv_range) = self.pooled().filter(|_| p < n.errors.len()) {
            b.error = b.error.max(((n.max - n.min) * inv_range) as f32);
        }
        // The texels' quantization error, at every level alike (`E_p + e_q`).
        b.error += self.options.texel_error as f32;
        b
    }

    /// The squared error the points a brick took correct (0 without points).
    fn removed(&self, b: &Brick) -> f64 {
        match self.points {
            Some(pm) if b.point_count > 0 => pm.in_box(b.lo, b.hi).2,
            _ => 0.0,
        }
    }

    /// The error mass of a brick: `Imp(n) mass(n, p)` ([`error_mass`]), its
    /// squared error summed over its samples, less what its points correct.
    fn mass(&self, b: &Brick) -> f64 {
        self.mass_in(b, &self.octree.node(b.node))
    }

    /// [`Refiner::mass`] of brick `b` of node `n`.
    fn mass_in(&self, b: &Brick, n: &NodeRef<'_>) -> f64 {
        b.importance * error_mass(n, b.p, self.removed(b), self.pooled())
    }

    /// `Some(1 / data range)` when coarse bricks hold peak-keeping texels
    /// ([`SelectOptions::pooled`]; see [`error_mass`]).
    fn pooled(&self) -> Option<f64> {
        let (lo, hi) = self.octree.value_range();
        (self.options.pooled && hi > lo).then(|| 1.0 / (hi - lo))
    }

    /// Bytes a brick holds: its texture and its points.
    fn cost(b: &Brick) -> usize {
        b.bytes + b.point_bytes
    }

    /// The best next step of a brick in the cut, if it still violates the
    /// tolerance: the best of [`Refiner::raise`], [`Refiner::split`] and
    /// [`Refiner::take_points`], if it removes any error.
    /// Computed once per (node, p, points taken): a brick in the cut is
    /// always [`Refiner::brick_of`] its node and level, with or without its
    /// points, so the key says all the step depends on.
    ///
    /// Returns its index in `Caches::entries`; `b` is a brick of a
    /// [`Form`] (importance 1) or, with `weighted`, a brick with its importance.
    fn step_index(&self, b: &Brick, weighted: bool) -> Option<usize> {
        let key = (b.node, b.p, b.point_count);
        if b.point_count == 0 {
            if let Some(kept) = self.kept_step(b.node, b.p) {
                return kept;
            }
        }
        // Bricks with points, and steps past what an entry can name.
        if let Some(&known) = self.caches.steps.borrow().get(&key) {
            return known;
        }
        let index = self.best_step(&if weighted { *b } else { self.weigh(b) }).map(|entry| self.keep_entry(entry));
        let named = match index {
            None => Some(NO_STEP),
            Some(i) => u32::try_from(i).ok().filter(|&i| i < NO_STEP),
        };
        match named {
            Some(step) if b.point_count == 0 => {
                let width = self.root_log2 - b.level + 1;
                self.caches.forms.borrow_mut().entry(b.node, b.p, width, self.slots).step = step;
            }
            _ => {
                self.caches.steps.borrow_mut().insert(key, index);
            }
        }
        index
    }

    /// [`Refiner::step_index`] of node `id`'s own brick at level `q` (of a
    /// [`Form`]), made only when its step is not kept.
    fn own_step_index(&self, id: NodeId, q: usize) -> Option<usize> {
        self.kept_step(id, q).unwrap_or_else(|| self.step_index(&self.form_brick(id, q), false))
    }

    /// The kept step of node `id`'s brick at level `p` without points, if
    /// computed (none inside: it has none).
    fn kept_step(&self, id: NodeId, p: usize) -> Option<Option<usize>> {
        let e = self.caches.forms.borrow().get(id, p).filter(|e| e.step != NONE)?;
        Some((e.step != NO_STEP).then_some(e.step as usize))
    }

    /// Keeps `entry` in `Caches::entries`; its index.
    fn keep_entry(&self, entry: StepEntry) -> usize {
        let mut entries = self.caches.entries.borrow_mut();
        entries.push(entry);
        entries.len() - 1
    }

    /// [`Refiner::step_index`]'s step, computed.
    fn best_step(&self, b: &Brick) -> Option<StepEntry> {
        self.best_step_below(b, usize::MAX)
    }

    /// The step the greedy tries when step `index` of a brick does not
    /// fit: the brick's best step whose bricks hold fewer bytes than that
    /// step's (a raise to a lower level, a split or its points), if any.
    /// So a brick whose best step is too large for what is left of the
    /// budget still refines by a smaller one. Computed once per entry; its
    /// index in `Caches::entries`.
    fn fallback_index(&self, index: usize) -> Option<usize> {
        let (known, step, added) = {
            let entries = self.caches.entries.borrow();
            let e = &entries[index];
            (e.fallback.get(), e.step, e.added)
        };
        if let Some(known) = known {
            return known;
        }
        let b = self.brick_with_points(step.node, step.p, step.points);
        let found = self.best_step_below(&b, added).map(|entry| self.keep_entry(entry));
        self.caches.entries.borrow()[index].fallback.set(Some(found));
        found
    }

    /// The best step of brick `b` (with its importance) whose bricks hold
    /// fewer than `below` bytes: the best of [`Refiner::raise`],
    /// [`Refiner::split`] and [`Refiner::take_points`], if it removes any
    /// error and `b` still violates the tolerance.
    fn best_step_below(&self, b: &Brick, below: usize) -> Option<StepEntry> {
        if Self::weighted(b) <= self.options.tolerance || b.error == 0.0 {
            return None;
        }
        let n = self.octree.node(b.node);
        let mass = self.mass_in(b, &n);
        let fits = |c: &Candidate| c.1.cost() < below;
        let raise = self.raise(b, &n, mass, below);
        let split = self.split(b, &n, mass).filter(fits);
        let take_points = self.take_points(b, &n, mass).filter(fits);
        let better = |x: Option<Candidate>, y: Option<Candidate>| match (x, y) {
            (Some(r), Some(s)) => Some(if s.0 > r.0 { s } else { r }),
            (r, s) => r.or(s),
        };
        let best = better(better(raise, split), take_points);
        best.filter(|s| s.0 > 0.0).map(|(gain, replacement, hidden)| StepEntry {
            step: Step { gain, node: b.node, p: b.p, points: b.point_count },
            added: replacement.cost(),
            replacement,
            hidden,
            cost: Self::cost(b),
            fallback: std::cell::Cell::new(None),
        })
    }

    /// Raise `p` to the level `q` in `(p, max]` that removes the most error
    /// mass per byte: the same box, `2^(q-p)` times the texels per axis.
    /// (Looking past `p + 1` matters: across a sharp edge `e_p` stays near its
    /// maximum until full resolution, so one level alone may buy nothing.)
    /// `mass` is the brick's [`Refiner::mass`], as in the split and the
    /// points; only levels whose form holds fewer than `below` bytes count.
    fn raise(&self, b: &Brick, n: &NodeRef<'_>, mass: f64, below: usize) -> Option<Candidate> {
        (b.p + 1..=self.max_p(n))
            .filter_map(|q| {
                let up = self.cheapest(n, q);
                let (bytes, hidden) = self.form_size(up);
                (bytes < below)
                    .then(|| (gain(mass - self.form_mass(up), bytes as f64 - Self::cost(b) as f64), up, bytes, hidden))
            })
            .max_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(gain, up, bytes, hidden)| (gain, Replacement::Raise(up, bytes), hidden))
    }

    /// Split: the children at the same stride (`p - 1`), each in its
    /// cheapest form ([`Refiner::cheapest`]), which pays a little border
    /// and lets each child refine on its own.
    ///
    /// A split at the same stride removes no error by itself unless parts
    /// of the node drop out; it pays off through the raises of single
    /// children it allows, when raising the whole node does not fit. So it
    /// is ranked by the better of its own gain and its best one-step
    /// lookahead: the split followed by the best raise of one child,
    /// `(removed by both) / (bytes of both)`.
    fn split(&self, b: &Brick, n: &NodeRef<'_>, mass: f64) -> Option<Candidate> {
        if n.is_terminal() || b.p == 0 {
            return None;
        }
        let split = self.split_of(n, b.p);
        let (children, hidden, added) = {
            let store = self.caches.forms.borrow();
            let s = &store.splits[split as usize];
            (store.kids_of(s.kids).to_vec(), s.hidden, s.bytes)
        };
        let split_bytes = added as f64 - Self::cost(b) as f64;
        let mut after = 0.0;
        for &form in &children {
            after += self.form_mass(form);
        }
        let direct = gain(mass - after, split_bytes);
        let mut ahead: f64 = 0.0;
        let mut owns = Vec::new();
        for &form in &children {
            self.caches
                .forms
                .borrow()
                .each_own(form, &mut |node, q, own_mass, bytes| owns.push((node, q, own_mass, bytes)));
        }
        for (node, q, own_mass, bytes) in owns {
            let cn = self.octree.node(node);
            // The own brick's weighted mass, `Imp(c) mass(c, p_c)` (no points), and its bytes.
            let mass_c = self.importance_of(node) * own_mass;
            let cost_c = bytes as f64;
            for up in q + 1..=self.max_p(&cn) {
                let up = self.cheapest(&cn, up);
                let (up_mass, up_bytes) = (self.form_mass(up), self.form_size(up).0 as f64 - cost_c);
                let removed = mass - after + mass_c - up_mass;
                if removed > 0.0 {
                    ahead = ahead.max(removed / (split_bytes + up_bytes).max(1.0));
                }
            }
        }
        Some((direct.max(ahead), Replacement::Split(split, added), hidden))
    }

    /// Take the brick's points (a brick at the points' stride that has none
    /// yet): their removable squared error for their bytes.
    fn take_points(&self, b: &Brick, n: &NodeRef<'_>, mass: f64) -> Option<Candidate> {
        self.points.filter(|pm| b.stride == pm.factor && b.point_count == 0).and_then(|pm| {
            let (count, _, removable) = pm.in_box(b.lo, b.hi);
            let bytes = count * pm.point_bytes;
            (count > 0 && removable > 0.0).then(|| {
                let with = Brick { point_count: count, point_bytes: bytes, ..*b };
                (gain(mass - self.mass_in(&with, n), bytes as f64), Replacement::Points(count, Self::cost(&with)), 0)
            })
        })
    }

    /// [`Refiner::brick_of`] node `id` at level `p`, holding `count` points
    /// (what [`Refiner::take_points`] makes).
    fn brick_with_points(&self, id: NodeId, p: usize, count: usize) -> Brick {
        let b = self.brick_of(id, p);
        match self.points {
            Some(pm) if count > 0 => Brick { point_count: count, point_bytes: count * pm.point_bytes, ..b },
            _ => b,
        }
    }

    /// Two starts, the better (smaller error mass) wins unless the first
    /// meets the tolerance: the root at `p = 0` (`coarsest`), and the root at
    /// the finest level whose cheapest form fits the budget (a greedy that
    /// starts coarse spends early bytes on what is cheap to fix and may miss
    /// a fine uniform level that fits; on data with detail everywhere that
    /// level is the better cut). A start from the root that meets the
    /// tolerance needs no other (it spends the fewest bytes). Returns the cut
    /// (by node id) and its transparent nodes.
    fn best_cut(&self, root: &NodeRef<'_>, coarsest: Brick) -> (Vec<Brick>, usize) {
        let from_root = self.grow(None, || (vec![coarsest], 0));
        let fine = || {
            (1..=self.max_p(root))
                .rev()
                .find(|&p| self.form_size(self.cheapest(root, p)).0 <= self.options.budget_bytes)
        };
        let form_bricks = |p: usize| {
            let form = self.cheapest(root, p);
            let mut bricks = Vec::new();
            self.form_bricks(form, &mut bricks);
            for b in &mut bricks {
                *b = self.weigh(b);
            }
            (bricks, self.form_size(form).1)
        };
        let total_mass = |cut: &[Brick]| cut.iter().map(|b| self.mass(b)).sum::<f64>();
        let meets = from_root.0.iter().all(|b| Self::weighted(b) <= self.options.tolerance);
        let other = if meets { None } else { fine().map(|p| self.grow(Some(p), || form_bricks(p))) };
        let (cut, _, skipped) = match other {
            Some(other) if total_mass(&other.0) < total_mass(&from_root.0) => other,
            _ => from_root,
        };
        (cut, skipped)
    }

    /// The selection of `bricks`: its bytes, its largest weighted error (a
    /// warning when above the tolerance, unless `warning` is set already) and
    /// its [`estimated_error`] and [`seen_rms_error`] (behind the view's transmittance).
    fn selection(&self, bricks: Vec<Brick>, skipped: usize, mut warning: Option<String>) -> Selection {
        let max_error = bricks.iter().map(Self::weighted).fold(0.0, f64::max);
        if warning.is_none() && max_error > self.options.tolerance {
            warning = Some(format!(
                "the budget of {} bytes reaches a largest error of {:.4} of the data range, above the tolerance {}: \
                 raise the budget to reach it",
                self.options.budget_bytes, max_error, self.options.tolerance
            ));
        }
        let texture_bytes = bricks.iter().map(|b| b.bytes).sum();
        let point_bytes = bricks.iter().map(|b| b.point_bytes).sum();
        let estimated_error = estimated_error(self.octree, &bricks, self.visible);
        let estimated_rms_error = seen_rms_error(
            self.octree,
            bricks.iter().map(|b| Seen::at_stride(b, self.transmittance(b.node))),
            self.visible,
        );
        Selection {
            bricks,
            texture_bytes,
            point_bytes,
            budget_bytes: self.options.budget_bytes,
            max_error,
            estimated_error,
            estimated_rms_error,
            skipped,
            warning,
        }
    }
}

/// Every brick of `selection` whose stride is the points' factor takes all
/// its points (what drawing a uniform stride with its points costs; the
/// budget is not consulted). [`crate::plan::point_slabs::add_points`] draws points only
/// in bricks that took them.
pub fn take_all_points(selection: &mut Selection, points: &PointMass) {
    for b in &mut selection.bricks {
        if b.stride == points.factor {
            let (count, _, _) = points.in_box(b.lo, b.hi);
            b.point_count = count;
            b.point_bytes = count * points.point_bytes;
        }
    }
    selection.point_bytes = selection.bricks.iter().map(|b| b.point_bytes).sum();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{uniform, Roi};

    fn octree(size: usize) -> VolumeOctree {
        octree_of(Dataset::SheppLogan, size)
    }

    fn octree_of(dataset: Dataset, size: usize) -> VolumeOctree {
        let v = generate(dataset, size, ScalarType::F32);
        VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap()
    }

    /// Every grid cell lies in exactly one brick.
    fn assert_tiles(o: &VolumeOctree, s: &Selection) {
        let d = o.layout().dims;
        let mut count = vec![0u8; (d[0] - 1) * (d[1] - 1) * (d[2] - 1)];
        for b in &s.bricks {
            for z in b.lo[2]..b.hi[2] {
                for y in b.lo[1]..b.hi[1] {
                    for x in b.lo[0]..b.hi[0] {
                        count[x + (d[0] - 1) * (y + (d[1] - 1) * z)] += 1;
                    }
                }
            }
        }
        assert!(count.iter().all(|&c| c == 1), "the cut does not tile the grid once");
    }

    #[test]
    fn budget_is_respected_and_more_budget_buys_less_error() {
        let o = octree(65);
        let mut last = f64::INFINITY;
        for budget in [4_000, 40_000, 400_000, 4_000_000] {
            let s = select(&o, &SelectOptions::new(budget, 0.0), |_, _| true).unwrap();
            assert!(s.texture_bytes <= budget, "{} > {budget}", s.texture_bytes);
            assert_eq!(s.texture_bytes, s.bricks.iter().map(|b| b.bytes).sum::<usize>());
            assert_tiles(&o, &s);
            assert!(s.max_error <= last);
            last = s.max_error;
        }
    }

    #[test]
    fn zero_budget_is_an_error_and_a_tiny_one_a_warning() {
        let o = octree(33);
        let e = select(&o, &SelectOptions::new(0, 0.0), |_, _| true).unwrap_err().to_string();
        assert!(e.contains("budget is 0 bytes"), "{e}");
        let e = select(&o, &SelectOptions::new(1000, f64::NAN), |_, _| true).unwrap_err().to_string();
        assert!(e.contains("tolerance"), "{e}");
        let roi = Some(Roi { center: [1.0; 3], radius: 0.0 });
        let e =
            select(&o, &SelectOptions { roi, ..SelectOptions::new(1000, 0.0) }, |_, _| true).unwrap_err().to_string();
        assert!(e.contains("radius > 0"), "{e}");
        let e = select(&o, &SelectOptions { bytes_per_texel: 0, ..SelectOptions::new(1000, 0.0) }, |_, _| true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bytes per texel"), "{e}");
        let s = select(&o, &SelectOptions::new(1, 0.0), |_, _| true).unwrap();
        assert_eq!(s.bricks.len(), 1);
        assert!(s.warning.as_deref().unwrap_or("").contains("below the coarsest"));
    }

    #[test]
    fn tolerance_stops_refinement_and_transparent_nodes_cost_nothing() {
        // Smooth data: coarse levels already meet a loose tolerance (the
        // phantom's sharp edges keep a large error at every level but the finest).
        let o = octree_of(Dataset::MarschnerLobb, 65);
        let loose = select(&o, &SelectOptions::new(100_000_000, 0.3), |_, _| true).unwrap();
        let tight = select(&o, &SelectOptions::new(100_000_000, 0.0), |_, _| true).unwrap();
        assert!(
            loose.texture_bytes < tight.texture_bytes,
            "{} {} {} {}",
            loose.texture_bytes,
            tight.texture_bytes,
            loose.max_error,
            tight.max_error
        );
        assert!(loose.max_error <= 0.3 && tight.max_error == 0.0);
        assert!(loose.warning.is_none() && tight.warning.is_none());
        // Only nodes reaching above 0.8 are visible: the rest are skipped.
        let some = select(&o, &SelectOptions::new(100_000_000, 0.0), |_, max| max > 0.8).unwrap();
        assert!(some.skipped > 0 && some.texture_bytes < tight.texture_bytes);
    }

    /// A node whose only error lies on a far face (a face sample its
    /// half-open box leaves to the neighbour) has `Q_0 = 0` but draws that
    /// error in the cells beside the face: a budget with room refines it,
    /// and the estimate reaches 0.
    #[test]
    fn an_error_on_a_far_face_is_refined_when_the_budget_has_room() {
        let n = 33;
        let mut data = vec![0.0f32; n * n * n];
        data[16 + n * (8 + n * 8)] = 1.0; // on the face x = 16 between the leaves [0, 16] and [16, 32]
        let grid = crate::data::grid::Grid::scalar(crate::data::grid::Samples::F32(&data), [n; 3]).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 16 }).unwrap();
        let left = o.layout().id(1, [0, 0, 0]);
        let node = o.node(left);
        assert_eq!((node.squared_error(0), node.error(0)), (0.0, 1.0), "Q_0 = 0 but E_0 = 1");
        let s = select(&o, &SelectOptions::new(10_000_000, 0.0), |_, _| true).unwrap();
        assert_eq!((s.max_error, s.estimated_error), (0.0, 0.0), "{:?}", s.bricks);
        assert!(s.bricks.iter().all(|b| b.error == 0.0));
    }

    /// When the bytes left are too few for a brick's best step, a smaller
    /// one is taken: no brick of the cut could still be raised one level
    /// within the budget (gradient borders make the finest start's raise
    /// too large for what is left, where its split would fit).
    #[test]
    fn a_step_too_large_leaves_room_for_a_smaller_one() {
        let v = generate(Dataset::SheppLogan, 64, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 16 }).unwrap();
        let l = o.layout().root_log2 as usize;
        for budget in [150_000, 300_000, 600_000, 1_000_000] {
            let options = SelectOptions { gradient_border: true, ..SelectOptions::new(budget, 0.0) };
            let s = select(&o, &options, |_, _| true).unwrap();
            assert!(s.texture_bytes <= budget);
            let left = budget - s.texture_bytes;
            for b in &s.bricks {
                let n = o.node(b.node);
                if b.p + 1 > (l - n.level).min(options.max_brick_log2 as usize)
                    || error_mass(&n, b.p + 1, 0.0, None) >= error_mass(&n, b.p, 0.0, None)
                {
                    continue;
                }
                let up = make_brick(&o, &n, b.p + 1, 1.0, 4, true).bytes;
                assert!(up - b.bytes > left, "budget {budget}: {b:?} could be raised ({} bytes, {left} left)", up);
            }
            if budget >= 600_000 {
                assert!(s.bricks.len() > 1, "budget {budget}: {} bytes in one brick", s.texture_bytes);
            }
        }
    }

    #[test]
    fn roi_refines_near_its_centre_first() {
        let o = octree(65);
        let roi = Roi { center: [8.0, 8.0, 32.0], radius: 8.0 };
        let s = select(&o, &SelectOptions { roi: Some(roi), ..SelectOptions::new(60_000, 0.0) }, |_, _| true).unwrap();
        let near = s.bricks.iter().filter(|b| b.importance == 1.0).map(|b| b.stride).min().unwrap();
        let far = s.bricks.iter().filter(|b| b.importance < 0.3).map(|b| b.stride).min().unwrap_or(usize::MAX);
        assert!(near < far, "near stride {near}, far {far}");
    }

    fn total_mass(o: &VolumeOctree, s: &Selection) -> f64 {
        s.bricks.iter().map(|b| b.importance * o.node(b.node).squared_error(b.p) as f64).sum()
    }

    /// At the bytes of uniform downsampling, the selection's squared error
    /// is never above the uniform one's, on data with detail in places
    /// (the phantom) and everywhere (Marschner-Lobb), and the phantom's
    /// empty and constant parts buy it a much smaller one.
    #[test]
    fn never_worse_than_uniform_at_its_bytes() {
        for dataset in [Dataset::SheppLogan, Dataset::MarschnerLobb] {
            let o = octree_of(dataset, 65);
            for stride in [2, 4, 8] {
                let better = if dataset == Dataset::SheppLogan && stride == 2 { 0.9 } else { 1.0 };
                let u = uniform(&o, stride, 4).unwrap();
                let s = select(&o, &SelectOptions::new(u.texture_bytes, 0.0), |_, _| true).unwrap();
                assert!(s.texture_bytes <= u.texture_bytes);
                let (ms, mu) = (total_mass(&o, &s), total_mass(&o, &u));
                assert!(ms <= mu * better + 1e-12, "{dataset:?} stride {stride}: {ms} vs uniform {mu}");
            }
        }
    }

    /// A node's cheapest form adds no squared error and no bytes, and drops
    /// transparent children.
    #[test]
    fn cheapest_form_loses_nothing() {
        let o = octree(65);
        let l = o.layout().root_log2 as usize;
        let options = SelectOptions::new(1 << 30, 0.0);
        let brick_of = |id: NodeId, p: usize| make_brick(&o, &o.node(id), p, 1.0, 4, false);
        let root = o.node(o.root());
        for p in 1..=l {
            let own = brick_of(root.id, p);
            for shows in [&(|_: &NodeRef<'_>| true) as &dyn Fn(&NodeRef<'_>) -> bool, &|n| n.max > 0.5] {
                let caches = Caches::default();
                let refiner = Refiner {
                    octree: &o,
                    options: &options,
                    visible: &|_, _| true,
                    shows,
                    points: None,
                    view: None,
                    root_log2: l,
                    slots: o.layout().node_slots(),
                    caches: &caches,
                };
                let form = refiner.cheapest(&root, p);
                let mut bricks = Vec::new();
                refiner.form_bricks(form, &mut bricks);
                let mass_of_form = refiner.form_mass(form);
                let bytes: usize = bricks.iter().map(|b| b.bytes).sum();
                let mass: f64 = bricks.iter().map(|b| o.node(b.node).squared_error(b.p) as f64).sum();
                // The form's own sums are its bricks'.
                let masses: f64 = bricks.iter().map(|b| error_mass(&o.node(b.node), b.p, 0.0, None)).sum();
                assert_eq!(refiner.form_size(form).0, bytes);
                assert!((mass_of_form - masses).abs() <= 1e-9 * masses.max(1e-30), "p {p}: {mass_of_form} vs {masses}");
                assert!(bytes <= own.bytes, "p {p}: {bytes} > {}", own.bytes);
                assert!(mass <= root.squared_error(p) as f64 * (1.0 + 1e-5) + 1e-9, "p {p}");
            }
        }
    }

    /// Nodes whose box the kept region removes cost no texture and are
    /// counted as skipped; the bricks left cover exactly the kept part.
    #[test]
    fn removed_nodes_are_not_selected() {
        use crate::plan::crop::{ClippingPlane, Cropping, KeptRegion};
        let o = octree(65);
        let all = select(&o, &SelectOptions::new(1 << 30, 0.0), |_, _| true).unwrap();
        let half =
            KeptRegion::new(None, &[ClippingPlane { origin: [40.0, 0.0, 0.0], normal: [1.0, 0.0, 0.0] }]).unwrap();
        let options = SelectOptions { region: Some(half), ..SelectOptions::new(1 << 30, 0.0) };
        let clipped = select(&o, &options, |_, _| true).unwrap();
        // The half at x < 32 is left out (the bricks across x = 40 are drawn whole).
        assert!(clipped.skipped > all.skipped && 2 * clipped.texture_bytes <= all.texture_bytes);
        assert!(clipped.bricks.iter().all(|b| b.hi[0] >= 40), "a brick entirely at x < 40 was selected");
        // Every kept sample is still in a brick.
        let covered = |x: usize| clipped.bricks.iter().any(|b| b.lo[0] <= x && x <= b.hi[0]);
        assert!((40..65).all(covered));
        let corner = Cropping::subvolume([0.0, 10.0, 0.0, 10.0, 0.0, 10.0]);
        let options = SelectOptions {
            region: Some(KeptRegion::new(Some(corner), &[]).unwrap()),
            ..SelectOptions::new(1 << 30, 0.0)
        };
        let cropped = select(&o, &options, |_, _| true).unwrap();
        assert!(cropped.bricks.iter().all(|b| b.lo.iter().all(|&v| v <= 10)));
        assert!(cropped.texture_bytes * 20 < all.texture_bytes, "{} vs {}", cropped.texture_bytes, all.texture_bytes);
        // A region removing everything selects nothing.
        let none =
            KeptRegion::new(None, &[ClippingPlane { origin: [70.0, 0.0, 0.0], normal: [1.0, 0.0, 0.0] }]).unwrap();
        let options = SelectOptions { region: Some(none), ..SelectOptions::new(1 << 30, 0.0) };
        let empty = select(&o, &options, |_, _| true).unwrap();
        assert!(empty.bricks.is_empty() && empty.skipped == 1);
    }

    #[test]
    fn uniform_is_one_texture_of_the_whole_grid() {
        let o = octree(65);
        let u = uniform(&o, 2, 4).unwrap();
        assert_tiles(&o, &u);
        assert_eq!(u.bricks.len(), 1);
        assert_eq!((u.bricks[0].stride, u.bricks[0].texels), (2, [33, 33, 33]));
        assert_eq!(u.texture_bytes, 33 * 33 * 33 * 4);
        assert_eq!(u.max_error, o.node(o.root()).error(u.bricks[0].p) as f64);
        assert!(uniform(&o, 3, 4).is_err() && uniform(&o, 128, 4).is_err());
    }
}
