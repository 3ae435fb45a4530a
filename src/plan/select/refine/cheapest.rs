//! The cheapest form of a node at a stride, the children a brick splits
//! into, and a form's weighted mass (see the module documentation of
//! [`super::super`]), kept in the selection's [`Forms`].

use super::super::forms::{Form, Forms, Split, NONE};
use super::super::mass::error_mass;
use super::{Brick, NodeId, NodeRef, Refiner};

impl Refiner<'_> {
    /// The entries per node of level `level` in [`Forms`]: `p = 0 ..= L - k`.
    fn width(&self, level: usize) -> usize {
        self.root_log2 - level + 1
    }

    /// The cheapest form of node `n` drawn at the stride of level `p`
    /// without adding error: either `n` itself at the coarsest level
    /// `q <= p` whose error mass ([`error_mass`]) is no larger, or its
    /// visible children, each in its own cheapest form at `p - 1` (the same
    /// stride; transparent children cost nothing), whichever needs fewer
    /// bytes:
    ///
    /// ```text
    /// q(n, p)     = min { q <= p : mass(n, q) <= mass(n, p) }
    /// form(n, p)  = children's forms at p - 1   when their bytes < bytes(n, q(n, p))
    ///             = n at q(n, p)                otherwise (and when n is terminal or p = 0)
    /// ```
    ///
    /// A constant or smooth part of a node drops to a few texels and a
    /// transparent one to none, so the bytes go where the error is.
    /// Returns the form's index in [`Forms::forms`], computed once per
    /// (node, p).
    ///
    /// A form does not depend on the importance `Imp(n)` (the region of
    /// interest, the view weight): which bricks it holds is decided by
    /// their unweighted error mass and their bytes, and its bricks carry an
    /// importance of 1. Its weighted mass is summed when asked for
    /// ([`Refiner::form_mass`]), so one form serves every region of
    /// interest and every view that leaves `max_p` alone.
    pub(in super::super) fn cheapest(&self, n: &NodeRef<'_>, p: usize) -> u32 {
        if let Some(e) = self.caches.forms.borrow().get(n.id, p).filter(|e| e.form != NONE) {
            return e.form;
        }
        let pooled = self.pooled();
        let at_p = error_mass(n, p, 0.0, pooled);
        let q = (0..p).find(|&q| error_mass(n, q, 0.0, pooled) <= at_p).unwrap_or(p);
        let own_bytes = self.bytes_at(n, q);
        let mut kids = None;
        if !(n.is_terminal() || p == 0) {
            let (forms, count, hidden, bytes) = self.children_forms(n, p, own_bytes);
            if bytes < own_bytes {
                kids = Some((forms, count, hidden, bytes));
            }
        }
        let mut store = self.caches.forms.borrow_mut();
        let form = match kids {
            Some((forms, count, hidden, bytes)) => {
                let mut form = Form::children(n.id, hidden, bytes);
                form.kids = store.push_kids(&forms[..count]);
                form
            }
            None => Form::own(n.id, q, own_bytes, error_mass(n, q, 0.0, pooled)),
        };
        let index = store.forms.len() as u32;
        store.forms.push(form);
        store.entry(n.id, p, self.width(n.level), self.slots).form = index;
        index
    }

    /// The children of `n` that show (`n` not terminal, `p >= 1`), each in
    /// its cheapest form at `p - 1` (the stride of `n` at `p`): their forms
    /// (the first `count` of the array), the nodes left out (transparent or
    /// removed: `shows` is false) and their bytes. Stops early once the
    /// bytes reach `enough`.
    fn children_forms(&self, n: &NodeRef<'_>, p: usize, enough: usize) -> ([u32; 8], usize, usize, usize) {
        let (mut forms, mut count, mut hidden, mut bytes) = ([0u32; 8], 0, 0, 0);
        for (level, c) in self.octree.layout().children(n.level, n.coords) {
            let Some(form) = self.child_form(level, c, p) else {
                hidden += 1;
                continue;
            };
            let store = self.caches.forms.borrow();
            let f = &store.forms[form as usize];
            bytes += f.bytes;
            hidden += f.hidden;
            forms[count] = form;
            count += 1;
            if bytes >= enough {
                break;
            }
        }
        (forms, count, hidden, bytes)
    }

    /// The child at `level` and `c` of a node at `p >= 1`, in its cheapest
    /// form at `p - 1`; none when it does not show. A child asked for
    /// again answers from the kept forms and whether it shows, without
    /// making its node.
    fn child_form(&self, level: usize, c: [usize; 3], p: usize) -> Option<u32> {
        let id = self.octree.layout().id(level, c);
        let shows = self.caches.forms.borrow().shows(id);
        if shows == Some(false) {
            return None;
        }
        if let (Some(true), Some(coarsest)) = (shows, self.seen_levels(id)) {
            let q = (p - 1).min(self.max_p_at(level, coarsest));
            if let Some(e) = self.caches.forms.borrow().get(id, q).filter(|e| e.form != NONE) {
                return Some(e.form);
            }
        }
        let cn = self.octree.node_at(id, level, c);
        if shows.is_none() {
            let shows = (self.shows)(&cn);
            self.caches.forms.borrow_mut().set_shows(id, shows, self.slots);
            if !shows {
                return None;
            }
        }
        Some(self.cheapest(&cn, (p - 1).min(self.max_p(&cn))))
    }

    /// The split of a brick of node `n` at level `p` (`n` not terminal,
    /// `p >= 1`): all its children that show, each in its cheapest form at
    /// `p - 1`. Returns its index in [`Forms::splits`], computed once per
    /// (node, p).
    pub(in super::super) fn split_of(&self, n: &NodeRef<'_>, p: usize) -> u32 {
        if let Some(e) = self.caches.forms.borrow().get(n.id, p).filter(|e| e.split != NONE) {
            return e.split;
        }
        let (forms, count, hidden, bytes) = self.children_forms(n, p, usize::MAX);
        let mut store = self.caches.forms.borrow_mut();
        let kids = store.push_kids(&forms[..count]);
        let index = store.splits.len() as u32;
        store.splits.push(Split { kids, hidden, bytes });
        store.entry(n.id, p, self.width(n.level), self.slots).split = index;
        index
    }

    /// The weighted error mass of form `form` under this selection's
    /// importance `Imp` (by node id):
    ///
    /// ```text
    /// M(form) = Imp(n) mass(n, p_n)           its node's own brick
    ///         = sum over children c of M(c)   (in octree order)
    /// ```
    ///
    /// Kept with the caches' epoch (their count of importance changes):
    /// asked again under the same epoch, the form answers without a walk.
    pub(in super::super) fn form_mass(&self, form: u32) -> f64 {
        let store = self.caches.forms.borrow();
        self.weighted_mass(&store, form)
    }

    fn weighted_mass(&self, store: &Forms, form: u32) -> f64 {
        let f = &store.forms[form as usize];
        let (epoch, kept) = f.weighted.get();
        if epoch == self.caches.epoch {
            return kept;
        }
        let mass = if f.own.is_some() {
            self.importance_of(f.node) * f.own_mass
        } else {
            let mut sum = 0.0;
            for &k in store.kids_of(f.kids) {
                sum += self.weighted_mass(store, k);
            }
            sum
        };
        f.weighted.set((self.caches.epoch, mass));
        mass
    }

    /// The bytes and transparent nodes of form `form`.
    pub(in super::super) fn form_size(&self, form: u32) -> (usize, usize) {
        let store = self.caches.forms.borrow();
        let f = &store.forms[form as usize];
        (f.bytes, f.hidden)
    }

    /// The own bricks of form `form` (importance 1, no points), in order
    /// (children in octree order), appended to `out`.
    pub(in super::super) fn form_bricks(&self, form: u32, out: &mut Vec<Brick>) {
        let mut own = Vec::new();
        self.caches.forms.borrow().each_own(form, &mut |node, q, _, _| own.push((node, q)));
        out.extend(own.into_iter().map(|(node, q): (NodeId, usize)| self.form_brick(node, q)));
    }
}
