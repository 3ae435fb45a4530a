//! Where one selection keeps what it computes once per node and level: the
//! [`cheapest`](super::refine) form of each (node, p), the children a
//! brick of it splits into, and its best next step. Node ids are dense, so
//! each node that is asked for gets one block of entries, `p = 0 ..= L - k`,
//! found by its id; the forms and their children live in flat arrays and
//! name each other by index. No form is allocated on its own, none is
//! hashed, and a [`Selector`](super::Selector) keeps them all by keeping
//! the arrays.

use crate::octree::NodeId;
use std::cell::Cell;

/// No entry (yet): an index never used.
pub(super) const NONE: u32 = u32::MAX;

/// A brick's step, computed: it has none.
pub(super) const NO_STEP: u32 = u32::MAX - 1;

/// The entries of one (node, p): its form, its split and the best next
/// step of its brick without points (indices, or [`NONE`] until computed;
/// a step may be [`NO_STEP`]).
#[derive(Clone, Copy)]
pub(super) struct Entry {
    pub(super) form: u32,
    pub(super) split: u32,
    pub(super) step: u32,
}

const EMPTY: Entry = Entry { form: NONE, split: NONE, step: NONE };

/// A node's [`cheapest`](super::refine) form at a level: the node's own
/// brick at level `q`, or its children's forms (`kids`, a range of
/// [`Forms::kids`]); the transparent nodes it leaves out and its bytes. Its
/// bricks carry no points and an importance of 1.
pub(super) struct Form {
    pub(super) node: NodeId,
    /// The level of the node's own brick; none: the form is its children's.
    pub(super) own: Option<u8>,
    pub(super) kids: (u32, u32),
    pub(super) hidden: usize,
    pub(super) bytes: usize,
    /// Of a form that is its node's own brick `b`: `mass(n, p_b)`
    /// (unweighted); 0 otherwise.
    pub(super) own_mass: f64,
    /// The weighted mass last summed and the epoch of the importance it
    /// was summed under (`u64::MAX`: never).
    pub(super) weighted: Cell<(u64, f64)>,
}

impl Form {
    /// The node's own brick at level `q`.
    pub(super) fn own(node: NodeId, q: usize, bytes: usize, own_mass: f64) -> Form {
        // Levels never exceed the octree's depth (< 64).
        let own = Some(q.min(63) as u8);
        Form { node, own, kids: (0, 0), hidden: 0, bytes, own_mass, weighted: Cell::new((u64::MAX, 0.0)) }
    }

    /// The node's children (`kids` set when stored).
    pub(super) fn children(node: NodeId, hidden: usize, bytes: usize) -> Form {
        Form { node, own: None, kids: (0, 0), hidden, bytes, own_mass: 0.0, weighted: Cell::new((u64::MAX, 0.0)) }
    }
}

/// The children a brick of (node, p) splits into, each in its cheapest
/// form at `p - 1` (a range of [`Forms::kids`]), the transparent nodes
/// they leave out and their bytes.
pub(super) struct Split {
    pub(super) kids: (u32, u32),
    pub(super) hidden: usize,
    pub(super) bytes: usize,
}

/// The entries, forms and splits of one selection (see the module
/// documentation).
#[derive(Default)]
pub(super) struct Forms {
    /// Per node id: where its block starts in `entries`, `usize::MAX` until asked for.
    block: Vec<usize>,
    entries: Vec<Entry>,
    pub(super) forms: Vec<Form>,
    /// Form indices: the children of children forms and of splits.
    pub(super) kids: Vec<u32>,
    pub(super) splits: Vec<Split>,
    /// Per node id: whether it shows (the selection's visibility test, its
    /// kept region and slice): 0 until asked, 1 it shows, 2 it does not.
    shows: Vec<u8>,
}

impl Forms {
    /// The entry of (node `id`, `p`), if its node has a block.
    pub(super) fn get(&self, id: NodeId, p: usize) -> Option<Entry> {
        let start = *self.block.get(id.0 as usize)?;
        (start != usize::MAX).then(|| self.entries[start + p])
    }

    /// The entry of (node `id`, `p`) to fill: its node's block (of
    /// `width` entries, `p < width`) is made on first use; `slots` is the
    /// octree's node count.
    pub(super) fn entry(&mut self, id: NodeId, p: usize, width: usize, slots: usize) -> &mut Entry {
        if self.block.is_empty() {
            self.block.resize(slots, usize::MAX);
        }
        let slot = &mut self.block[id.0 as usize];
        if *slot == usize::MAX {
            *slot = self.entries.len();
            self.entries.resize(self.entries.len() + width, EMPTY);
        }
        &mut self.entries[*slot + p]
    }

    /// Whether node `id` shows, if asked before.
    pub(super) fn shows(&self, id: NodeId) -> Option<bool> {
        match self.shows.get(id.0 as usize) {
            Some(1) => Some(true),
            Some(2) => Some(false),
            _ => None,
        }
    }

    /// Keeps whether node `id` shows; `slots` is the octree's node count.
    pub(super) fn set_shows(&mut self, id: NodeId, shows: bool, slots: usize) {
        if self.shows.is_empty() {
            self.shows.resize(slots, 0);
        }
        self.shows[id.0 as usize] = if shows { 1 } else { 2 };
    }

    /// Stores `kids` and returns their range.
    pub(super) fn push_kids(&mut self, kids: &[u32]) -> (u32, u32) {
        let start = self.kids.len() as u32;
        self.kids.extend_from_slice(kids);
        (start, self.kids.len() as u32)
    }

    /// The form indices in `range` (of [`Forms::kids`]).
    pub(super) fn kids_of(&self, range: (u32, u32)) -> &[u32] {
        &self.kids[range.0 as usize..range.1 as usize]
    }

    /// Calls `f` on each of form `form`'s own bricks, as (node, level q,
    /// own mass, bytes), children in octree order.
    pub(super) fn each_own(&self, form: u32, f: &mut impl FnMut(NodeId, usize, f64, usize)) {
        let x = &self.forms[form as usize];
        match x.own {
            Some(q) => f(x.node, usize::from(q), x.own_mass, x.bytes),
            None => {
                for &k in self.kids_of(x.kids) {
                    self.each_own(k, f);
                }
            }
        }
    }

    /// Forgets every brick's step (they depend on the tolerance and the
    /// importance), keeps the forms and splits.
    pub(super) fn forget_steps(&mut self) {
        for e in &mut self.entries {
            e.step = NONE;
        }
    }
}
