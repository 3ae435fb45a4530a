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
//!
//! Stand-ins merge up the octree ([`merged_stand_ins`]): where every brick
//! of the cut inside a node `A` is loading (or at `p = 0`, read at once),
//! one brick of `A` at the finest of their strides takes their place,
//!
//! ```text
//! s_A = min s'(b),   p_A = log2(2^(L - k_A) / s_A)
//! kept only while  p_A <= p_max  and  bytes(A, p_A) <= 2 sum bytes(s'(b))
//! ```
//!
//! (the sum over the stand-ins first replaced, so the stand-ins' bytes at
//! most double however far they merge), and so on up. Since the strides
//! are exact powers of two from node corners, a coarser stand-in's lattice
//! is a subset of `A`'s: no part is drawn coarser than its own stand-in.
//! Parts of `A` the cut leaves out are transparent under the transfer
//! function (their samples show nothing) or removed by cropping and
//! clipping (which the DrawList applies to every brick), so drawing them
//! costs fragments, not a change in the picture beyond interpolation at
//! their faces. A first frame of a store has every brick loading, and
//! drawing each of tens of thousands of stand-ins costs more than reading
//! them: merged, they are far fewer draws and textures.

use super::brick::{brick_bytes, make_brick, texels, Brick, Selection};
use crate::octree::{NodeId, VolumeOctree};
use std::collections::{BTreeMap, HashSet};

/// `brick` drawn `coarser` levels coarser (see the module documentation);
/// the brick itself at `p = 0`. `bytes_per_texel`: the selection's.
pub fn stand_in(octree: &VolumeOctree, brick: &Brick, coarser: usize, bytes_per_texel: usize) -> Brick {
    let p = brick.p.saturating_sub(coarser);
    if p == brick.p {
        return *brick;
    }
    let stride = brick.stride << (brick.p - p);
    let coarse = texels(brick.lo, brick.hi, stride);
    let border = has_gradient_border(brick, bytes_per_texel);
    Brick {
        p,
        stride,
        texels: coarse,
        bytes: brick_bytes(coarse, bytes_per_texel, border),
        error: octree.node(brick.node).error(p),
        ..*brick
    }
}

/// Whether the selection counted `brick`'s texels with their gradient
/// border (or without).
fn has_gradient_border(brick: &Brick, bytes_per_texel: usize) -> bool {
    brick.bytes == brick_bytes(brick.texels, bytes_per_texel, true)
}

/// `selection` with the bricks at `standing` replaced by their
/// [`stand_in`]s, merged up the octree into bricks of at most `2^max_p + 1`
/// texels a side (see the module documentation); the bricks in node order,
/// its texture bytes summed again.
pub fn merged_stand_ins(
    octree: &VolumeOctree,
    selection: &Selection,
    standing: &[usize],
    coarser: usize,
    bytes_per_texel: usize,
    max_p: usize,
) -> Selection {
    if standing.is_empty() {
        return selection.clone();
    }
    let layout = octree.layout();
    let mut is_standing = vec![false; selection.bricks.len()];
    for &i in standing {
        if let Some(s) = is_standing.get_mut(i) {
            *s = true;
        }
    }
    // Bricks at p = 0 (their own stand-ins: two texels a side, read at once)
    // merge too: a parent at their stride samples their lattice.
    let merges = |(b, s): &(&Brick, &bool)| **s || b.p == 0;
    let mut drawn: Vec<Brick> =
        selection.bricks.iter().zip(&is_standing).filter(|x| !merges(x)).map(|(b, _)| *b).collect();
    // A node with a drawn brick inside never merges: the ancestors of
    // every brick drawn as it is.
    let mut blocked = HashSet::new();
    let block = |blocked: &mut HashSet<NodeId>, id: NodeId| {
        let mut up = layout.parent(id);
        while let Some(a) = up.filter(|&a| blocked.insert(a)) {
            up = layout.parent(a);
        }
    };
    for b in &drawn {
        block(&mut blocked, b.node);
    }
    // The stand-ins by level, each with the bytes of the stand-ins it
    // replaces, each level's by parent: merged into the parent (one level
    // up) where nothing else is drawn inside it, drawn as they are
    // otherwise.
    let mut by_level: BTreeMap<usize, Vec<(Brick, usize)>> = BTreeMap::new();
    for (b, _) in selection.bricks.iter().zip(&is_standing).filter(merges) {
        let s = stand_in(octree, b, coarser, bytes_per_texel);
        by_level.entry(b.level).or_default().push((s, s.bytes));
    }
    while let Some((level, mut bricks)) = by_level.pop_last() {
        if level == 0 {
            drawn.extend(bricks.iter().map(|(b, _)| *b));
            continue;
        }
        // Bricks below the root (level > 0) have a parent.
        let parent_of = |b: &Brick| layout.parent(b.node).unwrap_or(b.node);
        bricks.sort_by_key(|(b, _)| (parent_of(b), b.node));
        for group in bricks.chunk_by(|(a, _), (b, _)| parent_of(a) == parent_of(b)) {
            let parent = parent_of(&group[0].0);
            let m = (!blocked.contains(&parent))
                .then(|| merged(octree, parent, level - 1, group, bytes_per_texel, max_p))
                .flatten();
            match m {
                Some(m) => by_level.entry(level - 1).or_default().push(m),
                None => {
                    drawn.extend(group.iter().map(|(b, _)| *b));
                    block(&mut blocked, group[0].0.node);
                }
            }
        }
    }
    drawn.sort_by_key(|b| b.node);
    let mut out = Selection { bricks: drawn, ..selection.clone() };
    out.texture_bytes = out.bricks.iter().map(|b| b.bytes).sum();
    out
}

/// Node `parent` (of `level`) at the finest stride of `group`, its
/// children's stand-ins (each with the bytes of the stand-ins it
/// replaces), if it has at most `2^max_p + 1` texels a side and at most
/// twice their bytes; with the bytes it replaces.
fn merged(
    octree: &VolumeOctree,
    parent: NodeId,
    level: usize,
    group: &[(Brick, usize)],
    bytes_per_texel: usize,
    max_p: usize,
) -> Option<(Brick, usize)> {
    let stride = group.iter().map(|(b, _)| b.stride).min()?;
    let size = octree.layout().node_size(level);
    if stride > size {
        return None;
    }
    let p = (size / stride).trailing_zeros() as usize;
    if p > max_p {
        return None;
    }
    let border = has_gradient_border(&group[0].0, bytes_per_texel);
    let importance = group.iter().map(|(b, _)| b.importance).fold(0.0, f64::max);
    let replaced: usize = group.iter().map(|(_, r)| r).sum();
    let m = make_brick(octree, &octree.node(parent), p, importance, bytes_per_texel, border);
    (m.bytes <= 2 * replaced).then_some((m, replaced))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, SelectOptions};

    /// `selection` with the bricks at `standing` (indices into its bricks)
    /// replaced by their own [`stand_in`]s, unmerged: the reference the
    /// merged ones are compared with.
    fn with_stand_ins(
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

    /// Merged stand-ins tile what the loading bricks tile, each no coarser
    /// than the stand-ins it replaces, at most `2^max_p + 1` texels a side
    /// and twice their bytes, in fewer bricks; a brick not loading keeps
    /// every ancestor from merging over it.
    #[test]
    fn merged_stand_ins_tile_the_loading_bricks_in_fewer_draws() {
        let v = generate(Dataset::SheppLogan, 64, ScalarType::U8);
        let octree = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 8 }).unwrap();
        let d = octree.layout().dims;
        let cover = |bricks: &[Brick]| {
            let mut count = vec![0u8; (d[0] - 1) * (d[1] - 1) * (d[2] - 1)];
            for b in bricks {
                for z in b.lo[2]..b.hi[2] {
                    for y in b.lo[1]..b.hi[1] {
                        for x in b.lo[0]..b.hi[0] {
                            count[x + (d[0] - 1) * (y + (d[1] - 1) * z)] += 1;
                        }
                    }
                }
            }
            count
        };
        for gradient_border in [false, true] {
            let options = SelectOptions { bytes_per_texel: 1, gradient_border, ..SelectOptions::new(200_000, 0.0) };
            let selection = select(&octree, &options, |_, _| true).unwrap();
            let loading: Vec<usize> = (0..selection.bricks.len()).filter(|&i| selection.bricks[i].p > 0).collect();
            assert!(loading.len() > 20, "{} bricks loading", loading.len());
            let single = with_stand_ins(&octree, &selection, &loading, 2, 1);
            let merged = merged_stand_ins(&octree, &selection, &loading, 2, 1, 5);
            assert_eq!(cover(&merged.bricks), cover(&selection.bricks), "the same cells, once each");
            assert!(
                merged.bricks.len() * 4 < single.bricks.len(),
                "{} of {}",
                merged.bricks.len(),
                single.bricks.len()
            );
            assert!(merged.bricks.windows(2).all(|w| w[0].node < w[1].node), "node order");
            assert_eq!(merged.texture_bytes, merged.bricks.iter().map(|b| b.bytes).sum::<usize>());
            assert!(
                merged.texture_bytes <= 2 * single.texture_bytes,
                "{} of {}",
                merged.texture_bytes,
                single.texture_bytes
            );
            for m in &merged.bricks {
                assert!(m.texels.iter().all(|&t| t <= 33) || single.bricks.contains(m), "{m:?}");
                assert_eq!(m.bytes, brick_bytes(m.texels, 1, gradient_border));
                // No coarser than any stand-in it covers.
                for s in single.bricks.iter().filter(|s| (0..3).all(|a| m.lo[a] <= s.lo[a] && s.hi[a] <= m.hi[a])) {
                    assert!(m.stride <= s.stride, "{m:?} over {s:?}");
                }
            }
            // One brick read: it is drawn itself, and no stand-in covers it.
            let kept = loading[loading.len() / 2];
            let fewer: Vec<usize> = loading.iter().copied().filter(|&i| i != kept).collect();
            let partly = merged_stand_ins(&octree, &selection, &fewer, 2, 1, 5);
            let own = selection.bricks[kept];
            assert!(partly.bricks.contains(&own));
            assert_eq!(cover(&partly.bricks), cover(&selection.bricks));
            // Nothing loading: the selection itself.
            assert_eq!(merged_stand_ins(&octree, &selection, &[], 2, 1, 5).bricks, selection.bricks);
        }
    }
}
