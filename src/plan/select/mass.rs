//! The error mass a node removes per byte, and the cheapest form of a node
//! at a stride (see the module documentation of [`super`]).

use super::brick::Brick;
use super::cache::NodeMap;
use crate::octree::{NodeId, NodeRef, VolumeOctree};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Arc, OnceLock};

/// The error mass of node `n` drawn at level `p`, `removed` of its squared
/// error corrected by points:
///
/// ```text
/// mass(n, p) = max(Q_p(n) - removed, E_p(n)^2)
/// ```
///
/// `Q_p` sums the node's half-open box (each sample counted once across
/// nodes), but the node draws its closed box: the cells along its far faces
/// interpolate towards face samples that `Q_p` leaves to the neighbours. A
/// node whose only error lies on a far face has `Q_p = 0` and still draws
/// that error; `E_p` (the closed box's largest error) keeps its mass above
/// 0, so that a budget with room left refines it to full resolution, and
/// keeps a coarser level from passing for one of no more error
/// ([`cheapest`]): a node at full resolution has mass 0, and only an exact
/// coarse form (`E_q = 0`) matches it.
///
/// Maximum and minimum intensity draw a coarse brick from peak-keeping
/// texels ([`crate::render::texture`]'s `pool`): they are exact only for a
/// constant node, elsewhere they may show any value of the node's range a
/// stride away. With `pooled = Some(1 / range)` (the data range) a node
/// drawn coarser than its full resolution (`p < L - level`) keeps at least
/// that error,
///
/// ```text
/// E_pool(n) = (max(n) - min(n)) / range,   mass(n, p) >= E_pool(n)^2   (p < L - level)
/// ```
///
/// (normalised like `E_p`), so that only a constant node passes for exact
/// at a coarse level and a peak's node is refined first.
pub(super) fn error_mass(n: &NodeRef<'_>, p: usize, removed: f64, pooled: Option<f64>) -> f64 {
    let e = n.error(p) as f64;
    let e_pool = match pooled {
        Some(inv_range) if p < n.errors.len() => (n.max - n.min) * inv_range,
        _ => 0.0,
    };
    (n.squared_error(p) as f64 - removed).max(e * e).max(e_pool * e_pool)
}

/// What a step buys: error mass removed per byte added, and a step that
/// frees bytes without adding error before any step that costs bytes.
/// A step that changes neither (the same bricks again) buys nothing: 0.
pub(super) fn gain(removed: f64, added_bytes: f64) -> f64 {
    if added_bytes == 0.0 && removed == 0.0 {
        0.0
    } else if added_bytes <= 0.0 && removed >= 0.0 {
        f64::INFINITY
    } else {
        removed / added_bytes.max(1.0)
    }
}

/// The cheapest form of node `n` drawn at the stride of level `p` without
/// adding error: either `n` itself at the coarsest level `q <= p` whose
/// error mass ([`error_mass`]) is no larger, or its visible children,
/// each in its own cheapest form at `p - 1` (the same stride; transparent
/// children cost nothing), whichever needs fewer bytes. A constant or smooth
/// part of a node drops to a few texels and a transparent one to none, so
/// the bytes go where the error is. Returns the bricks and how many
/// transparent nodes were left out ([`Form`]). Results are kept in `memo`
/// by (node, p): they depend on nothing else within one selection, and are
/// shared, not copied (a fine form of a large node holds many bricks).
///
/// A form does not depend on the importance `Imp(n)` (the region of
/// interest, the view weight): which bricks it holds is decided by their
/// unweighted error mass and their bytes, and its bricks carry an
/// importance of 1. Its weighted mass is summed when asked for
/// ([`Form::weighted_mass`]), so one form serves every region of interest
/// and every view that leaves `max_p` alone.
#[allow(clippy::too_many_arguments)]
pub(super) fn cheapest(
    octree: &VolumeOctree,
    n: &NodeRef<'_>,
    p: usize,
    brick_of: &dyn Fn(NodeId, usize) -> Brick,
    max_p: &dyn Fn(&NodeRef<'_>) -> usize,
    shows: &dyn Fn(&NodeRef<'_>) -> bool,
    memo: &Memo,
    pooled: Option<f64>,
) -> Arc<Form> {
    if let Some(known) = memo.borrow().get(&(n.id, p)) {
        return Arc::clone(known);
    }
    let q = (0..p).find(|&q| error_mass(n, q, 0.0, pooled) <= error_mass(n, p, 0.0, pooled)).unwrap_or(p);
    let own = brick_of(n.id, q);
    let mut form = Form::new(n.id, Some(own), Vec::new(), 0, own.bytes, error_mass(n, q, 0.0, pooled));
    if !(n.is_terminal() || p == 0) {
        let (children, hidden, bytes) = children_forms(octree, n, p, own.bytes, brick_of, max_p, shows, memo, pooled);
        if bytes < own.bytes {
            form = Form::new(n.id, None, children, hidden, bytes, 0.0);
        }
    }
    let form = Arc::new(form);
    memo.borrow_mut().insert((n.id, p), Arc::clone(&form));
    form
}

/// A node's [`cheapest`] form: the node's own brick, or its children's
/// forms (shared, so a form costs its children count, not its bricks);
/// the transparent nodes it leaves out and its bytes. Its bricks carry no
/// points and an importance of 1.
#[derive(Debug)]
pub(super) struct Form {
    node: NodeId,
    own: Option<Brick>,
    children: Vec<Arc<Form>>,
    pub hidden: usize,
    pub bytes: usize,
    /// Of a form that is its node's own brick `b`: `mass(n, p_b)`
    /// ([`error_mass`], unweighted); 0 otherwise.
    pub own_mass: f64,
    /// The weighted mass of the last [`Form::weighted_mass`]: `(epoch, bits)`.
    weighted: (AtomicU64, AtomicU64),
    /// Of a form that is its node's own brick `b`: the node's cheapest
    /// forms at each level `q` above `b.p` up to its finest (what a split's
    /// lookahead weighs; made once, see [`Form::each_own`]).
    pub raises: OnceLock<Vec<Arc<Form>>>,
}

impl Form {
    fn new(
        node: NodeId,
        own: Option<Brick>,
        children: Vec<Arc<Form>>,
        hidden: usize,
        bytes: usize,
        own_mass: f64,
    ) -> Form {
        Form {
            node,
            own,
            children,
            hidden,
            bytes,
            own_mass,
            weighted: (AtomicU64::new(u64::MAX), AtomicU64::new(0)),
            raises: OnceLock::new(),
        }
    }

    /// The form's error mass under the importance `imp` (by node id):
    ///
    /// ```text
    /// M(form) = Imp(n) mass(n, p_n)        its node's own brick
    ///         = sum over children c of M(c)   (in octree order)
    /// ```
    ///
    /// Kept with `epoch`, the caller's count of importance changes: asked
    /// again under the same epoch, the form answers without a walk (the
    /// importance must be the same function of the node for one epoch).
    pub fn weighted_mass(&self, epoch: u64, imp: &dyn Fn(NodeId) -> f64) -> f64 {
        if self.weighted.0.load(Relaxed) == epoch {
            return f64::from_bits(self.weighted.1.load(Relaxed));
        }
        let mass = if self.own.is_some() {
            imp(self.node) * self.own_mass
        } else {
            let mut sum = 0.0;
            for c in &self.children {
                sum += c.weighted_mass(epoch, imp);
            }
            sum
        };
        self.weighted.1.store(mass.to_bits(), Relaxed);
        self.weighted.0.store(epoch, Relaxed);
        mass
    }

    /// Calls `f` on each brick of the form, in order (children in octree order).
    pub fn each(&self, f: &mut impl FnMut(&Brick)) {
        if let Some(b) = &self.own {
            f(b);
        }
        for c in &self.children {
            c.each(f);
        }
    }

    /// Calls `f` on each form of this one that is its node's own brick,
    /// with that brick, in the order of [`Form::each`].
    pub fn each_own(&self, f: &mut impl FnMut(&Form, &Brick)) {
        if let Some(b) = &self.own {
            f(self, b);
        }
        for c in &self.children {
            c.each_own(f);
        }
    }
}

/// The children of `n` that show (not terminal, `p >= 1`), each in its
/// [`cheapest`] form at `p - 1` (the stride of `n` at `p`): their forms, the
/// nodes left out (transparent or removed: `shows` is false) and their
/// bytes. Stops early once the bytes reach `enough`.
#[allow(clippy::too_many_arguments)]
pub(super) fn children_forms(
    octree: &VolumeOctree,
    n: &NodeRef<'_>,
    p: usize,
    enough: usize,
    brick_of: &dyn Fn(NodeId, usize) -> Brick,
    max_p: &dyn Fn(&NodeRef<'_>) -> usize,
    shows: &dyn Fn(&NodeRef<'_>) -> bool,
    memo: &Memo,
    pooled: Option<f64>,
) -> (Vec<Arc<Form>>, usize, usize) {
    let mut children = Vec::new();
    let (mut hidden, mut bytes) = (0, 0);
    for c in octree.children(n.id) {
        let cn = octree.node(c);
        if !shows(&cn) {
            hidden += 1;
            continue;
        }
        let form = cheapest(octree, &cn, (p - 1).min(max_p(&cn)), brick_of, max_p, shows, memo, pooled);
        bytes += form.bytes;
        hidden += form.hidden;
        children.push(form);
        if bytes >= enough {
            break;
        }
    }
    (children, hidden, bytes)
}

/// [`cheapest`]'s results: by (node, p).
pub(super) type Memo = NodeMap<(NodeId, usize), Arc<Form>>;
