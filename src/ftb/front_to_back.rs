//! Front-to-back display with blocking quadtrees (paper 2, section 4).
//!
//! Algorithm "FTB Display of an Octree": a white root draws nothing; a black
//! root has its visible faces scan-converted; otherwise the blocking bitmaps
//! start white and the root is processed as a gray octant.
//!
//! "Process a G Octant" (depth, card_num): locate its face nodes
//! `ind_num[i] = ind_tab[depth] + card_num[i]`; if all are B the octant is
//! blocked and discarded with its subtree; else refine the bitmaps, process
//! the eight suboctants front to back with `card_num_son[i] = 4 card_num[i] +
//! quad_tab[oct][i]`, and compact.
//!
//! "Process a W or B Octant": if all its face nodes are B it is blocked;
//! else a black octant scan-converts the faces whose nodes are not B (only
//! into pixels not painted yet), and every face node takes the octant's colour.
//!
//! Only the axes whose faces the view can see are used (the view case), so
//! the XY, X, ... cases touch two or one bitmap.

use super::binary_octree::{BinaryOctree, Colour, Node};
use super::bitmap::{BlockingBitmaps, BLACK, QUAD_TAB, WHITE};
use super::raster::{Paint, Projector};
use super::view::View;
use super::Display;
use std::time::Instant;

/// The depth image of `octree` seen along `view` on a `size x size` image,
/// and the bytes of the blocking bitmaps it used.
pub fn display(octree: &BinaryOctree, view: &View, size: usize) -> (Display, usize) {
    let started = Instant::now();
    let mut run = Run {
        octree,
        view,
        projector: Projector::new(view, octree.side(), size),
        bitmaps: BlockingBitmaps::new(view.axes.len(), octree.n),
    };
    let root = octree.root();
    match root.colour {
        Colour::White => {}
        Colour::Black => {
            run.projector.counters.black_visited += 1;
            for &axis in &view.axes {
                run.projector.face([0; 3], octree.side(), axis, view.high_face[axis], Paint::Unpainted);
            }
        }
        Colour::Gray => run.gray(root, 0, [0; 3], [0; 3], octree.side()),
    }
    let bytes = run.bitmaps.bytes();
    let ms = started.elapsed().as_secs_f64() * 1e3;
    (Display { image: run.projector.image, counters: run.projector.counters, ms }, bytes)
}

struct Run<'a> {
    octree: &'a BinaryOctree,
    view: &'a View,
    projector: Projector,
    /// One bitmap per used axis, in the order of `view.axes`.
    bitmaps: BlockingBitmaps,
}

impl Run<'_> {
    /// Whether every face node of the octant (`card` per used axis) is B.
    fn blocked(&self, depth: u32, card: &[usize; 3]) -> bool {
        let b = &self.bitmaps;
        (0..self.view.axes.len()).all(|ii| b.get(ii, b.index(depth, card[ii])) == BLACK)
    }

    /// Procedure "Process a G Octant".
    fn gray(&mut self, node: Node, depth: u32, card: [usize; 3], origin: [usize; 3], size: usize) {
        self.projector.counters.gray_visited += 1;
        if self.blocked(depth, &card) {
            return;
        }
        for (ii, &c) in card.iter().enumerate().take(self.view.axes.len()) {
            self.bitmaps.refine(ii, depth, c);
        }
        let half = size / 2;
        for k in 0..8 {
            let oct = self.view.ftb_order[k];
            let mut card_son = [0usize; 3];
            for (ii, &axis) in self.view.axes.iter().enumerate() {
                card_son[ii] = 4 * card[ii] + QUAD_TAB[oct][axis] as usize;
            }
            let o = [origin[0] + half * (oct & 1), origin[1] + half * ((oct >> 1) & 1), origin[2] + half * (oct >> 2)];
            let child = self.octree.child(node, oct);
            if child.colour == Colour::Gray {
                self.gray(child, depth + 1, card_son, o, half);
            } else {
                self.white_or_black(child.colour, depth + 1, card_son, o, half);
            }
        }
        for (ii, &c) in card.iter().enumerate().take(self.view.axes.len()) {
            self.bitmaps.compact(ii, depth, c);
        }
    }

    /// Procedure "Process a W or B Octant".
    fn white_or_black(&mut self, colour: Colour, depth: u32, card: [usize; 3], origin: [usize; 3], size: usize) {
        if colour == Colour::Black {
            self.projector.counters.black_visited += 1;
        } else {
            self.projector.counters.white_visited += 1;
        }
        if self.blocked(depth, &card) {
            return;
        }
        let value = if colour == Colour::Black { BLACK } else { WHITE };
        for (ii, &c) in card.iter().enumerate().take(self.view.axes.len()) {
            let index = self.bitmaps.index(depth, c);
            if colour == Colour::Black && self.bitmaps.get(ii, index) != BLACK {
                let axis = self.view.axes[ii];
                self.projector.face(origin, size, axis, self.view.high_face[axis], Paint::Unpainted);
            }
            self.bitmaps.set(ii, index, value);
        }
    }
}
