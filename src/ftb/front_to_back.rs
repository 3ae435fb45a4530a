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
    match view.axes.len() {
        3 => run::<3>(octree, view, size),
        2 => run::<2>(octree, view, size),
        _ => run::<1>(octree, view, size),
    }
}

/// The display with `N` used axes (the view case's bitmaps), so the per-axis
/// loops are unrolled.
fn run<const N: usize>(octree: &BinaryOctree, view: &View, size: usize) -> (Display, usize) {
    let started = Instant::now();
    let axes: [usize; N] = std::array::from_fn(|ii| view.axes[ii]);
    let mut run = Run::<N> {
        octree,
        view,
        axes,
        quad: std::array::from_fn(|oct| std::array::from_fn(|ii| QUAD_TAB[oct][axes[ii]] as usize)),
        projector: Projector::new(view, octree.side(), size),
        bitmaps: BlockingBitmaps::new(N, octree.n),
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
        Colour::Gray => run.gray(root, 0, [0; N], [0; 3], octree.side()),
    }
    let bytes = run.bitmaps.bytes();
    let ms = started.elapsed().as_secs_f64() * 1e3;
    (Display { image: run.projector.image, counters: run.projector.counters, ms }, bytes)
}

struct Run<'a, const N: usize> {
    octree: &'a BinaryOctree,
    view: &'a View,
    /// The used axes (`axis` of the paper), in X, Y, Z order.
    axes: [usize; N],
    /// `quad_tab[oct][axes[ii]]`: Table I restricted to the used axes.
    quad: [[usize; N]; 8],
    projector: Projector,
    /// One bitmap per used axis, in the order of `axes`.
    bitmaps: BlockingBitmaps,
}

impl<const N: usize> Run<'_, N> {
    /// `ind_num` per used axis (as global bitmap indices): formula (1).
    #[inline]
    fn ind_num(&self, depth: u32, card: &[usize; N]) -> [usize; N] {
        std::array::from_fn(|ii| self.bitmaps.node(ii, depth, card[ii]))
    }

    /// Procedure "Process a G Octant".
    fn gray(&mut self, node: Node, depth: u32, card: [usize; N], origin: [usize; 3], size: usize) {
        self.projector.counters.gray_visited += 1;
        let ind = self.ind_num(depth, &card);
        if ind.iter().all(|&g| self.bitmaps.get_at(g) == BLACK) {
            return; // blocked: discarded with its subtree
        }
        // ind_num_son[i][0] = ind_tab[depth + 1] + 4 card_num[i]: formula (3).
        let son: [usize; N] = std::array::from_fn(|ii| self.bitmaps.node(ii, depth + 1, 4 * card[ii]));
        for ii in 0..N {
            self.bitmaps.refine_at(ind[ii], son[ii]);
        }
        let half = size / 2;
        for k in 0..8 {
            let oct = self.view.ftb_order[k];
            // card_num_son[i] = 4 card_num[i] + quad_tab[oct][i]: formula (4).
            let card_son: [usize; N] = std::array::from_fn(|ii| 4 * card[ii] + self.quad[oct][ii]);
            let o = [origin[0] + half * (oct & 1), origin[1] + half * ((oct >> 1) & 1), origin[2] + half * (oct >> 2)];
            let child = self.octree.child(node, oct);
            if child.colour == Colour::Gray {
                self.gray(child, depth + 1, card_son, o, half);
            } else {
                self.white_or_black(child.colour, depth + 1, card_son, o, half);
            }
        }
        for ii in 0..N {
            self.bitmaps.compact_at(ind[ii], son[ii]);
        }
    }

    /// Procedure "Process a W or B Octant".
    fn white_or_black(&mut self, colour: Colour, depth: u32, card: [usize; N], origin: [usize; 3], size: usize) {
        if colour == Colour::Black {
            self.projector.counters.black_visited += 1;
        } else {
            self.projector.counters.white_visited += 1;
        }
        let ind = self.ind_num(depth, &card);
        if ind.iter().all(|&g| self.bitmaps.get_at(g) == BLACK) {
            return; // blocked
        }
        let value = if colour == Colour::Black { BLACK } else { WHITE };
        for (&g, &axis) in ind.iter().zip(&self.axes) {
            if colour == Colour::Black && self.bitmaps.get_at(g) != BLACK {
                self.projector.face(origin, size, axis, self.view.high_face[axis], Paint::Unpainted);
            }
            self.bitmaps.set_at(g, value);
        }
    }
}
