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
//!
//! The procedures here take `ind_num` itself rather than `card_num`: a
//! suboctant's `ind_num` is `ind_num_son[i][0] + quad_tab[oct][i]` (formulas
//! (3) and (4) added), so no octant looks `ind_tab` up.

use super::binary_octree::{BinaryOctree, Colour, GrayOctant, Node};
use super::bitmap::{BlockingBitmaps, BLACK, QUAD_TAB, WHITE};
use super::display::Display;
use super::raster::{DepthImage, Paint, Projector};
use super::view::View;
use std::time::Instant;

/// The depth image of `octree` seen along `view` on a `size x size` image,
/// and the bytes of the blocking bitmaps it used.
pub fn display(octree: &BinaryOctree, view: &View, size: usize) -> (Display, usize) {
    display_into(octree, view, DepthImage::new(size))
}

/// [`display`] into `image` (cleared first; its size is the image size).
/// The time covers clearing, the bitmaps, traversal and scan conversion.
pub fn display_into(octree: &BinaryOctree, view: &View, image: DepthImage) -> (Display, usize) {
    match view.axes.len() {
        3 => run::<3>(octree, view, image),
        2 => run::<2>(octree, view, image),
        _ => run::<1>(octree, view, image),
    }
}

/// The display with `N` used axes (the view case's bitmaps), so the per-axis
/// loops are unrolled.
fn run<const N: usize>(octree: &BinaryOctree, view: &View, image: DepthImage) -> (Display, usize) {
    let started = Instant::now();
    let axes: [usize; N] = std::array::from_fn(|ii| view.axes[ii]);
    let mut run = Run::<N> {
        octree,
        view,
        axes,
        order: view.ftb_order,
        quad: std::array::from_fn(|k| std::array::from_fn(|ii| QUAD_TAB[view.ftb_order[k]][axes[ii]] as usize)),
        projector: Projector::reusing(view, octree.side(), image),
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
        Colour::Gray => {
            let ind: [usize; N] = std::array::from_fn(|ii| run.bitmaps.node(ii, 0, 0));
            run.gray(root, ind, [0; 3], octree.side())
        }
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
    /// The suboctant labels in FTB order.
    order: [usize; 8],
    /// `quad[k][ii] = quad_tab[order[k]][axes[ii]]`: Table I restricted to
    /// the used axes, in FTB order.
    quad: [[usize; N]; 8],
    projector: Projector,
    /// One bitmap per used axis, in the order of `axes`.
    bitmaps: BlockingBitmaps,
}

impl<const N: usize> Run<'_, N> {
    /// Procedure "Process a G Octant", given the octant's `ind_num` (global
    /// bitmap indices of its face nodes, one per used axis).
    fn gray(&mut self, node: Node, ind: [usize; N], origin: [usize; 3], size: usize) {
        self.projector.counters.gray_visited += 1;
        if ind.iter().all(|&g| self.bitmaps.get_at(g) == BLACK) {
            return; // blocked: discarded with its subtree
        }
        // ind_num_son[i][0] = ind_tab[depth + 1] + 4 card_num[i]: formula (3).
        let son: [usize; N] = std::array::from_fn(|ii| self.bitmaps.first_son_at(ii, ind[ii]));
        for ii in 0..N {
            self.bitmaps.refine_at(ind[ii], son[ii]);
        }
        let half = size / 2;
        let octant = self.octree.gray_octant(node);
        if half == 1 && (octant.child_colours >> 1) & 0x5555 == 0 {
            self.voxels(octant, ind, son, origin);
            return;
        }
        for k in 0..8 {
            let oct = self.order[k];
            // card_num_son[i] = 4 card_num[i] + quad_tab[oct][i]: formula (4).
            let ind_son: [usize; N] = std::array::from_fn(|ii| son[ii] + self.quad[k][ii]);
            let o = [origin[0] + half * (oct & 1), origin[1] + half * ((oct >> 1) & 1), origin[2] + half * (oct >> 2)];
            let child = BinaryOctree::suboctant(octant, oct);
            if child.colour == Colour::Gray {
                self.gray(child, ind_son, o, half);
            } else {
                self.white_or_black(child.colour, ind_son, o, half);
            }
        }
        for ii in 0..N {
            self.bitmaps.compact_at(ind[ii], son[ii]);
        }
    }

    /// The eight voxels of a gray octant of size 2 (all W or B), each by
    /// procedure "Process a W or B Octant", then the compaction of step 5.
    /// Their face nodes are the four sons of the octant's nodes (`quad_tab`
    /// picks one per voxel and axis), so each axis' sons are read into one
    /// byte, processed there, and written back once: the same reads and
    /// writes as the general path, in a register instead of the bitmap.
    fn voxels(&mut self, octant: GrayOctant, ind: [usize; N], son: [usize; N], origin: [usize; 3]) {
        let mut sons: [u8; N] = std::array::from_fn(|ii| self.bitmaps.sons_at(son[ii]));
        for k in 0..8 {
            let oct = self.order[k];
            let black = octant.child_colour(oct) == Colour::Black;
            self.projector.counters.black_visited += usize::from(black);
            self.projector.counters.white_visited += usize::from(!black);
            let shift: [usize; N] = std::array::from_fn(|ii| 2 * self.quad[k][ii]);
            let nodes: [u8; N] = std::array::from_fn(|ii| (sons[ii] >> shift[ii]) & 3);
            if nodes.iter().all(|&c| c == BLACK) {
                continue; // blocked
            }
            let value = if black { BLACK } else { WHITE };
            for ii in 0..N {
                if black && nodes[ii] != BLACK {
                    let axis = self.axes[ii];
                    let o = [origin[0] + (oct & 1), origin[1] + ((oct >> 1) & 1), origin[2] + (oct >> 2)];
                    self.projector.face(o, 1, axis, self.view.high_face[axis], Paint::Unpainted);
                }
                sons[ii] = (sons[ii] & !(3 << shift[ii])) | (value << shift[ii]);
            }
        }
        for ii in 0..N {
            self.bitmaps.set_sons_at(son[ii], sons[ii]);
            if sons[ii] == BLACK * 0b0101_0101 {
                self.bitmaps.set_at(ind[ii], BLACK);
            }
        }
    }

    /// Procedure "Process a W or B Octant", given its `ind_num`.
    fn white_or_black(&mut self, colour: Colour, ind: [usize; N], origin: [usize; 3], size: usize) {
        let black = colour == Colour::Black;
        self.projector.counters.black_visited += usize::from(black);
        self.projector.counters.white_visited += usize::from(!black);
        let nodes: [u8; N] = std::array::from_fn(|ii| self.bitmaps.get_at(ind[ii]));
        if nodes.iter().all(|&c| c == BLACK) {
            return; // blocked
        }
        if black {
            for ii in 0..N {
                if nodes[ii] != BLACK {
                    let axis = self.axes[ii];
                    self.projector.face(origin, size, axis, self.view.high_face[axis], Paint::Unpainted);
                    self.bitmaps.set_at(ind[ii], BLACK);
                }
            }
        } else {
            for g in ind {
                self.bitmaps.set_at(g, WHITE);
            }
        }
    }
}
