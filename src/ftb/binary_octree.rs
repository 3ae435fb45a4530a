//! The binary octree (paper 2, section 2): the octree space is the cube of
//! `N = 2^n` voxels per axis enclosing the grid (one voxel per sample; the
//! padding outside the grid is white), recursively divided into eight
//! octants. An octant is black (B) when all its voxels are inside the
//! object, white (W) when none is, gray (G) otherwise, with eight suboctants.
//!
//! Octant labels: suboctant `oct` of a cell at `(x, y, z)` of size `s` lies at
//! `(x + s/2 * (oct & 1), y + s/2 * ((oct >> 1) & 1), z + s/2 * (oct >> 2))`
//! (bit 0 x, bit 1 y, bit 2 z, as in the paper's Table I).

use crate::base::error::{Error, Result};
use crate::data::grid::Grid;
use rayon::prelude::*;
use serde::Serialize;

/// The colour of an octant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[repr(u8)]
pub enum Colour {
    /// No voxel inside the object.
    White = 0,
    /// Every voxel inside the object.
    Black = 1,
    /// Mixed: eight suboctants.
    Gray = 2,
}

impl Colour {
    /// The colour of 2-bit code `code & 3` (0 W, 1 B, otherwise G).
    #[inline]
    fn from_code(code: u16) -> Colour {
        match code & 3 {
            0 => Colour::White,
            1 => Colour::Black,
            _ => Colour::Gray,
        }
    }
}

/// Which voxels are inside the object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Inside {
    /// Value at or above the isovalue.
    AtOrAbove(f64),
    /// Value equal to this label (label volumes, segmentations).
    Label(f64),
}

impl Inside {
    /// Whether a sample of value `v` is inside (NaN never is).
    pub fn contains(self, v: f64) -> bool {
        match self {
            Inside::AtOrAbove(iso) => v >= iso,
            Inside::Label(label) => v == label,
        }
    }
}

/// A gray octant as stored: the colours of its eight suboctants and where
/// its gray suboctants are. White and black octants are not stored: their
/// parent's `child_colours` says all there is to know about them, so a
/// display reads memory only for gray octants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GrayOctant {
    /// Colour of suboctant `oct` in bits `2 oct .. 2 oct + 2` (0 W, 1 B, 2 G).
    pub child_colours: u16,
    /// Index in [`BinaryOctree::gray`] of the first gray suboctant; the gray
    /// suboctants follow one another in label order.
    pub first_gray: u32,
}

impl GrayOctant {
    /// Colour of suboctant `oct`.
    #[inline]
    pub fn child_colour(self, oct: usize) -> Colour {
        Colour::from_code(self.child_colours >> (2 * oct))
    }

    /// Gray suboctants with a label below `oct` (bit `2 j` set for each gray `j`, counted).
    #[inline]
    fn gray_below(self, oct: usize) -> u32 {
        let grays = (self.child_colours >> 1) & 0x5555;
        (grays & ((1u16 << (2 * oct)) - 1)).count_ones()
    }
}

/// One octant met in a traversal: its colour and, for a gray one, its index
/// in [`BinaryOctree::gray`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Node {
    /// W, B or G.
    pub colour: Colour,
    /// Index in [`BinaryOctree::gray`]; 0 unless gray.
    pub gray: u32,
}

/// Octants of each colour.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct OctantCounts {
    /// White octants.
    pub white: usize,
    /// Black octants.
    pub black: usize,
    /// Gray octants.
    pub gray: usize,
}

/// A binary octree of resolution `n` (`2^n` voxels per axis).
#[derive(Debug, Clone, PartialEq)]
pub struct BinaryOctree {
    /// Resolution: the octree space is `2^n` voxels per axis.
    pub n: u32,
    /// Colour of the root octant.
    pub root_colour: Colour,
    /// The gray octants, the root first when it is gray, depth first: a gray
    /// octant's gray suboctants are appended together, and the subtree of
    /// each follows before its next gray sibling's, so a display walks this
    /// array forwards.
    pub gray: Vec<GrayOctant>,
    /// Samples per axis of the grid the octree was built from.
    pub dims: [usize; 3],
}

impl BinaryOctree {
    /// The octree of the voxels of `grid` that are `inside`.
    pub fn from_grid(grid: &Grid<'_>, inside: Inside) -> Result<BinaryOctree> {
        let (Inside::AtOrAbove(v) | Inside::Label(v)) = inside;
        if !v.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "the isovalue or label {v} is not a finite number: give a value within the data range"
            )));
        }
        Ok(BinaryOctree::from_fn(grid.dims(), |i, j, k| inside.contains(grid.value(i, j, k))))
    }

    /// The octree of the voxels `inside[i + dims[0] * (j + dims[1] * k)]`.
    pub fn from_voxels(dims: [usize; 3], inside: &[bool]) -> BinaryOctree {
        assert_eq!(inside.len(), dims[0] * dims[1] * dims[2], "one flag per voxel");
        BinaryOctree::from_fn(dims, |i, j, k| inside[i + dims[0] * (j + dims[1] * k)])
    }

    /// The octree of the voxels `(i, j, k)` of a `dims` grid for which
    /// `inside(i, j, k)` holds (read once each, in parallel by z slices).
    fn from_fn(dims: [usize; 3], inside: impl Fn(usize, usize, usize) -> bool + Sync) -> BinaryOctree {
        let largest = dims.iter().copied().max().unwrap_or(1).max(1);
        let n = largest.next_power_of_two().trailing_zeros();
        let pyramid = Pyramid::new(n, dims, inside);
        let root_colour = pyramid.colour(0, [0; 3]);
        let mut gray = Vec::new();
        let mut stack = Vec::new();
        if root_colour == Colour::Gray {
            gray.push(GrayOctant { child_colours: 0, first_gray: 0 });
            stack.push((0usize, 0u32, [0usize; 3]));
        }
        while let Some((index, level, cell)) = stack.pop() {
            let first_gray = gray.len();
            let mut child_colours = 0u16;
            let mut gray_cells = [(0usize, [0usize; 3]); 8];
            let mut grays = 0;
            for oct in 0..8 {
                let child = [2 * cell[0] + (oct & 1), 2 * cell[1] + ((oct >> 1) & 1), 2 * cell[2] + (oct >> 2)];
                let colour = pyramid.colour(level + 1, child);
                child_colours |= (colour as u16) << (2 * oct);
                if colour == Colour::Gray {
                    gray_cells[grays] = (gray.len(), child);
                    gray.push(GrayOctant { child_colours: 0, first_gray: 0 });
                    grays += 1;
                }
            }
            let first_gray = u32::try_from(first_gray).expect("fewer than 2^32 gray octants");
            gray[index] = GrayOctant { child_colours, first_gray };
            // Pushed last to first so the first gray suboctant's subtree is laid out first.
            for &(child_index, child) in gray_cells[..grays].iter().rev() {
                stack.push((child_index, level + 1, child));
            }
        }
        BinaryOctree { n, root_colour, gray, dims }
    }

    /// Voxels per axis of the octree space.
    pub fn side(&self) -> usize {
        1 << self.n
    }

    /// The root octant.
    pub fn root(&self) -> Node {
        Node { colour: self.root_colour, gray: 0 }
    }

    /// The stored gray octant `node`.
    #[inline]
    pub fn gray_octant(&self, node: Node) -> GrayOctant {
        self.gray[node.gray as usize]
    }

    /// Suboctant `oct` of gray octant `parent`: its colour, and its index
    /// when it is gray (`first_gray` plus the gray suboctants before it).
    #[inline]
    pub fn suboctant(parent: GrayOctant, oct: usize) -> Node {
        match parent.child_colour(oct) {
            Colour::Gray => Node { colour: Colour::Gray, gray: parent.first_gray + parent.gray_below(oct) },
            leaf => Node { colour: leaf, gray: 0 },
        }
    }

    /// Suboctant `oct` of gray node `node`.
    pub fn child(&self, node: Node, oct: usize) -> Node {
        BinaryOctree::suboctant(self.gray_octant(node), oct)
    }

    /// Octants of each colour.
    pub fn counts(&self) -> OctantCounts {
        let mut c = OctantCounts::default();
        let mut add = |colour| match colour {
            Colour::White => c.white += 1,
            Colour::Black => c.black += 1,
            Colour::Gray => c.gray += 1,
        };
        add(self.root_colour);
        for g in &self.gray {
            (0..8).for_each(|oct| add(g.child_colour(oct)));
        }
        c
    }

    /// Bytes the octree takes (its gray octants).
    pub fn bytes(&self) -> usize {
        self.gray.len() * std::mem::size_of::<GrayOctant>()
    }

    /// Checks the structure: every gray octant has eight suboctants, not all
    /// white and not all black (the octree is condensed), none below voxel
    /// level, every node reached exactly once, white and black octants have no
    /// children.
    pub fn validate(&self) -> Result<()> {
        let fail = |m: String| Err(Error::Internal(format!("invalid binary octree: {m}")));
        if (self.root_colour == Colour::Gray) == self.gray.is_empty() {
            return fail(format!("a {:?} root with {} gray octants", self.root_colour, self.gray.len()));
        }
        let mut reached = vec![false; self.gray.len()];
        let mut stack = if self.gray.is_empty() { vec![] } else { vec![(0usize, 0u32)] };
        if let Some(root) = reached.first_mut() {
            *root = true;
        }
        while let Some((index, depth)) = stack.pop() {
            let octant = self.gray[index];
            if depth >= self.n {
                return fail(format!("gray octant {index} at voxel depth {depth}"));
            }
            let colours: Vec<u16> = (0..8).map(|oct| (octant.child_colours >> (2 * oct)) & 3).collect();
            if colours.contains(&3) {
                return fail(format!("gray octant {index} has a suboctant of no colour"));
            }
            if colours.iter().all(|&c| c == 0) || colours.iter().all(|&c| c == 1) {
                return fail(format!("gray octant {index} has eight suboctants of one colour"));
            }
            let grays = colours.iter().filter(|&&c| c == 2).count();
            let first = octant.first_gray as usize;
            if grays > 0 && (first + grays > self.gray.len() || first <= index) {
                return fail(format!("gray octant {index} has gray suboctants out of range at {first}"));
            }
            for (k, seen) in reached.iter_mut().enumerate().skip(first).take(grays) {
                if std::mem::replace(seen, true) {
                    return fail(format!("gray octant {k} is the child of two octants"));
                }
                stack.push((k, depth + 1));
            }
        }
        if let Some(orphan) = reached.iter().position(|r| !r) {
            return fail(format!("gray octant {orphan} is not reached from the root"));
        }
        Ok(())
    }

    /// Whether voxel `(i, j, k)` of the octree space is black.
    pub fn is_black(&self, voxel: [usize; 3]) -> bool {
        let mut node = self.root();
        let mut size = self.side();
        let mut origin = [0usize; 3];
        while node.colour == Colour::Gray {
            size /= 2;
            let mut oct = 0;
            for a in 0..3 {
                if voxel[a] >= origin[a] + size {
                    oct |= 1 << a;
                    origin[a] += size;
                }
            }
            node = self.child(node, oct);
        }
        node.colour == Colour::Black
    }
}

/// Octant colours level by level (level `n`: voxels), from which the tree is read.
struct Pyramid {
    /// `levels[d]`: `(2^d)^3` colours, x fastest.
    levels: Vec<Vec<Colour>>,
}

impl Pyramid {
    fn new(n: u32, dims: [usize; 3], inside: impl Fn(usize, usize, usize) -> bool + Sync) -> Pyramid {
        let side = 1usize << n;
        let mut finest = vec![Colour::White; side * side * side];
        finest.par_chunks_mut(side * side).enumerate().for_each(|(k, slice)| {
            if k < dims[2] {
                for j in 0..dims[1] {
                    for i in 0..dims[0] {
                        if inside(i, j, k) {
                            slice[i + side * j] = Colour::Black;
                        }
                    }
                }
            }
        });
        let mut levels = vec![finest];
        for d in (0..n).rev() {
            let s = 1usize << d;
            let fine = levels.last().expect("a finer level");
            let mut coarse = vec![Colour::White; s * s * s];
            coarse.par_chunks_mut(s * s).enumerate().for_each(|(z, slice)| {
                for y in 0..s {
                    for x in 0..s {
                        let mut black = 0;
                        let mut white = 0;
                        for oct in 0..8 {
                            let c = [2 * x + (oct & 1), 2 * y + ((oct >> 1) & 1), 2 * z + (oct >> 2)];
                            match fine[c[0] + 2 * s * (c[1] + 2 * s * c[2])] {
                                Colour::Black => black += 1,
                                Colour::White => white += 1,
                                Colour::Gray => {}
                            }
                        }
                        slice[x + s * y] = match (black, white) {
                            (8, _) => Colour::Black,
                            (_, 8) => Colour::White,
                            _ => Colour::Gray,
                        };
                    }
                }
            });
            levels.push(coarse);
        }
        levels.reverse();
        Pyramid { levels }
    }

    fn colour(&self, level: u32, cell: [usize; 3]) -> Colour {
        let s = 1usize << level;
        self.levels[level as usize][cell[0] + s * (cell[1] + s * cell[2])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_voxel_in_a_padded_grid() {
        let dims = [3, 2, 2];
        let mut inside = vec![false; 12];
        inside[2 + 3 * (1 + 2)] = true; // voxel (2, 1, 1)
        let t = BinaryOctree::from_voxels(dims, &inside);
        assert_eq!(t.n, 2);
        t.validate().unwrap();
        for k in 0..4 {
            for j in 0..4 {
                for i in 0..4 {
                    assert_eq!(t.is_black([i, j, k]), [i, j, k] == [2, 1, 1], "voxel {i} {j} {k}");
                }
            }
        }
        assert_eq!(t.counts(), OctantCounts { white: 14, black: 1, gray: 2 });
    }

    #[test]
    fn uniform_volumes_are_one_octant() {
        assert!(BinaryOctree::from_voxels([4, 4, 4], &[true; 64]).gray.is_empty());
        assert_eq!(BinaryOctree::from_voxels([4, 4, 4], &[false; 64]).root().colour, Colour::White);
        // A 3^3 block inside a 4^3 space is not uniform: the padding is white.
        let t = BinaryOctree::from_voxels([3, 3, 3], &[true; 27]);
        assert_eq!(t.root().colour, Colour::Gray);
        t.validate().unwrap();
    }

    #[test]
    fn inside_tests() {
        assert!(Inside::AtOrAbove(2.0).contains(2.0));
        assert!(!Inside::AtOrAbove(2.0).contains(f64::NAN));
        assert!(Inside::Label(3.0).contains(3.0) && !Inside::Label(3.0).contains(4.0));
    }
}
