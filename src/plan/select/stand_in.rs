//! Stand-ins: a selected brick drawn coarser while its own texels load.
//!
//! A brick of node `n` at level `p` (stride `s = 2^(L - k - p)`) whose
//! texels are not in memory yet is drawn as the same node `c` levels
//! coarser,
//!
//! ```text
//! p' = max(p - c, 0),   s' = 2^(L - k - p') = s 2^(p - p')
//! ```
//!
//! its own box and place in the cut, so the frame's bricks still tile the
//! grid once (never a hole) and are composited in the same order, from
//! about `2^-3c` of its texels (1/64 at `c = 2`). Its error is `e_p'(n)`,
//! its bytes those of its texels at the selection's bytes per texel and
//! border. A brick at `p = 0` (two texels a side) has no coarser form.

use super::brick::{brick_bytes, texels, Brick, Selection};
use crate::octree::VolumeOctree;

/// `brick` drawn `coarser` levels coarser (see the module documentation);
/// the brick itself at `p = 0`. `bytes_per_texel`: the selection's.
pub fn stand_in(octree: &VolumeOctree, brick: &Brick, coarser: usize, bytes_per_texel: usize) -> Brick {
    let p = brick.p.saturating_sub(coarser);
    if p == brick.p {
        return *brick;
    }
    let stride = brick.stride << (brick.p - p);
    let coarse = texels(brick.lo, brick.hi, stride);
    // The selection counted the texels with their gradient border, or without.
    let border = brick.bytes == brick_bytes(brick.texels, bytes_per_texel, true);
    Brick {
        p,
        stride,
        texels: coarse,
        bytes: brick_bytes(coarse, bytes_per_texel, border),
        error: octree.node(brick.node).error(p),
        ..*brick
    }
}

/// `selection` with the bricks at `standing` (indices into its bricks)
/// replaced by their [`stand_in`]s; its texture bytes summed again.
pub fn with_stand_ins(
    octree: &VolumeOctree,
    selection: &Selection,
    standing: &[usize],
    coarser: usize,
    bytes_per_texel: usize,
) -> Selection {
    let mut out = selection.clone();
    for &i in standing {
        if let Some(b) = out.bricks.get_mut(i) {
            *b = stand_in(octree, b, coarser, bytes_per_texel);
        }
    }
    out.texture_bytes = out.bricks.iter().map(|b| b.bytes).sum();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, SelectOptions};

    #[test]
    fn a_stand_in_is_its_node_coarser_at_the_selections_bytes() {
        let v = generate(Dataset::SheppLogan, 45, ScalarType::U8);
        let grid = v.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        let root = octree.layout().root_log2 as usize;
        for (bytes_per_texel, gradient_border) in [(4, false), (1, true), (2, false), (2, true)] {
            let options = SelectOptions { bytes_per_texel, gradient_border, ..SelectOptions::new(1 << 30, 0.0) };
            let selection = select(&octree, &options, |_, _| true).unwrap();
            for coarser in [1, 2, 5] {
                let all: Vec<usize> = (0..selection.bricks.len()).collect();
                let stood = with_stand_ins(&octree, &selection, &all, coarser, bytes_per_texel);
                for (b, s) in selection.bricks.iter().zip(&stood.bricks) {
                    assert_eq!((s.node, s.level, s.lo, s.hi), (b.node, b.level, b.lo, b.hi));
                    assert_eq!(s.p, b.p.saturating_sub(coarser));
                    assert_eq!(s.stride, 1 << (root - s.level - s.p), "stride = 2^(L - k - p')");
                    assert_eq!(s.texels, texels(b.lo, b.hi, s.stride));
                    assert_eq!(s.bytes, brick_bytes(s.texels, bytes_per_texel, gradient_border));
                    assert_eq!(s.error, octree.node(b.node).error(s.p));
                }
                assert_eq!(stood.texture_bytes, stood.bricks.iter().map(|b| b.bytes).sum::<usize>());
                assert!(stood.texture_bytes < selection.texture_bytes, "{coarser} levels coarser");
            }
            // Only the bricks named stand in; a brick at p = 0 is itself.
            let i = selection.bricks.iter().position(|b| b.p > 0).unwrap();
            let one = with_stand_ins(&octree, &selection, &[i], 8, bytes_per_texel);
            assert_eq!((one.bricks[i].p, one.bricks[i].texels), (0, [2, 2, 2]), "two texels a side");
            assert!((0..one.bricks.len()).all(|j| j == i || one.bricks[j] == selection.bricks[j]));
            assert_eq!(stand_in(&octree, &one.bricks[i], 2, bytes_per_texel), one.bricks[i]);
        }
    }
}
