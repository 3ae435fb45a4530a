//! The binary octree (paper 2, section 2): the octree space is the cube of
//! `N = 2^n` voxels per axis enclosing the grid (one voxel per sample; the
//! padding outside the grid is white), recursively divided into eight
//! octants. An octant is black (B) when all its voxels are inside the
//! object, white (W) when none is, gray (G) otherwise, with eight suboctants.
//!
//! Octant labels: suboctant `oct` of a cell at `(x, y, z)` of size `s` lies at
//! `(x + s/2 * (oct & 1), y + s/2 * ((oct >> 1) & 1), z + s/2 * (oct >> 2))`
//! (bit 0 x, bit 1 y, bit 2 z, as in the paper's Table I).

use crate::error::{Error, Result};
use crate::grid::Grid;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::VecDeque;

/// The colour of an octant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Colour {
    /// No voxel inside the object.
    White,
    /// Every voxel inside the object.
    Black,
    /// Mixed: eight suboctants.
    Gray,
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

/// One octant: its colour and, for a gray one, where its eight suboctants start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Node {
    /// W, B or G.
    pub colour: Colour,
    /// Index of suboctant 0 in [`BinaryOctree::nodes`] (suboctants `first .. first + 8`, by label); 0 unless gray.
    pub first_child: u32,
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
    /// Octants in breadth-first order; the root is node 0.
    pub nodes: Vec<Node>,
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
        // Breadth first: a gray octant's eight suboctants are appended together.
        let mut nodes = vec![Node { colour: pyramid.colour(0, [0; 3]), first_child: 0 }];
        let mut queue = VecDeque::new();
        if nodes[0].colour == Colour::Gray {
            queue.push_back((0usize, 0u32, [0usize; 3]));
        }
        while let Some((index, level, cell)) = queue.pop_front() {
            let first = nodes.len();
            nodes[index].first_child = u32::try_from(first).expect("fewer than 2^32 octants");
            for oct in 0..8 {
                let child = [2 * cell[0] + (oct & 1), 2 * cell[1] + ((oct >> 1) & 1), 2 * cell[2] + (oct >> 2)];
                let colour = pyramid.colour(level + 1, child);
                nodes.push(Node { colour, first_child: 0 });
                if colour == Colour::Gray {
                    queue.push_back((first + oct, level + 1, child));
                }
            }
        }
        BinaryOctree { n, nodes, dims }
    }

    /// Voxels per axis of the octree space.
    pub fn side(&self) -> usize {
        1 << self.n
    }

    /// The root octant.
    pub fn root(&self) -> Node {
        self.nodes[0]
    }

    /// Suboctant `oct` of gray node `node`.
    pub fn child(&self, node: Node, oct: usize) -> Node {
        self.nodes[node.first_child as usize + oct]
    }

    /// Octants of each colour.
    pub fn counts(&self) -> OctantCounts {
        let mut c = OctantCounts::default();
        for node in &self.nodes {
            match node.colour {
                Colour::White => c.white += 1,
                Colour::Black => c.black += 1,
                Colour::Gray => c.gray += 1,
            }
        }
        c
    }

    /// Bytes the octree takes (its node array).
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>()
    }

    /// Checks the structure: every gray octant has eight suboctants, not all
    /// white and not all black (the octree is condensed), none below voxel
    /// level, every node reached exactly once, white and black octants have no
    /// children.
    pub fn validate(&self) -> Result<()> {
        let fail = |m: String| Err(Error::Internal(format!("invalid binary octree: {m}")));
        if self.nodes.is_empty() {
            return fail("no root".into());
        }
        let mut reached = vec![false; self.nodes.len()];
        reached[0] = true;
        let mut stack = vec![(0usize, 0u32)];
        while let Some((index, depth)) = stack.pop() {
            let node = self.nodes[index];
            if node.colour != Colour::Gray {
                if node.first_child != 0 {
                    return fail(format!("leaf octant {index} has children"));
                }
                continue;
            }
            if depth >= self.n {
                return fail(format!("gray octant {index} at voxel depth {depth}"));
            }
            let first = node.first_child as usize;
            if first + 8 > self.nodes.len() || first <= index {
                return fail(format!("gray octant {index} has suboctants out of range at {first}"));
            }
            let children = &self.nodes[first..first + 8];
            if children.iter().all(|c| c.colour == Colour::White) || children.iter().all(|c| c.colour == Colour::Black)
            {
                return fail(format!("gray octant {index} has eight suboctants of one colour"));
            }
            for k in 0..8 {
                if std::mem::replace(&mut reached[first + k], true) {
                    return fail(format!("octant {} is the child of two octants", first + k));
                }
                stack.push((first + k, depth + 1));
            }
        }
        if let Some(orphan) = reached.iter().position(|r| !r) {
            return fail(format!("octant {orphan} is not reached from the root"));
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
        assert_eq!(BinaryOctree::from_voxels([4, 4, 4], &[true; 64]).nodes.len(), 1);
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
