//! Slab integration (paper 1, section 4.1): surface triangles into the slabs
//! between the slices of each brick.
//!
//! A brick is drawn as view-aligned slices, back to front. A translucent
//! surface is composited correctly with it by drawing each triangle between
//! the two slices that bracket it: after the slices behind it and before the
//! slices in front of it. A triangle crossing slices is drawn in each slab it
//! crosses, clipped to that slab.
//!
//! # Conventions
//!
//! View depth is `depth(p) = (p - eye) . f` ([`Camera::depth`]), `f` the unit
//! view direction. The slices of a brick are the lattice planes
//! `depth = k * spacing` (`k` an integer) that cut its box, back to front:
//!
//! ```text
//! slices = [ k * spacing  :  d_min <= k * spacing < d_max ]   by decreasing k
//! d_min, d_max = min, max of depth(corner) over the 8 corners of the box
//! ```
//!
//! The lattice is shared: bricks with the same spacing slice on the same
//! planes, and a plane through a face two bricks share belongs to one of them
//! only (the interval is half-open).
//!
//! With `n = slices.len()` there are `n + 1` slabs, numbered back to front by
//! the number of slices behind them: slab `s` is drawn after slices
//! `0 .. s` and before slices `s .. n`. With `slices[-1] = +inf` and
//! `slices[n] = -inf`:
//!
//! ```text
//! slab s     =  { d : slices[s] <= d < slices[s-1] }          s = 0 ..= n
//! slab 0     =  { d : d >= slices[0] }                        behind the first (farthest) slice
//! slab n     =  { d : d < slices[n-1] }                       in front of the last (nearest) slice
//! slab(d)    =  #{ i : slices[i] > d }                        the slab of depth d
//! ```
//!
//! Intervals are half-open, `near <= d < far`, as [`Batch::clip`] says: a
//! point exactly on slice `i` lies in slab `i`, the slab just behind that
//! slice, drawn before it. Slab 0 and slab `n` are unbounded, so no triangle
//! is ever lost, wherever it lies; without slices everything is slab 0.
//!
//! # Per selection and per view
//!
//! The paper splits the work in two. Once per selection, the slab
//! integration phase builds the [`SlabPolygons`]: each selected brick's
//! polygons grouped by terminal surface node into batches, each with the
//! tight world box of its vertices (view independent). For every new view,
//! UpdatePosition ([`assign_batches`]) only places each batch, by the view
//! depths of its box's corners, `[d_lo, d_hi]` (widened by a few rounding
//! units `r`), into the slabs it covers:
//!
//! ```text
//! far  = slab(d_hi + r)
//! near = slab(d_lo - r)
//! ```
//!
//! If `far = near` the batch is drawn unclipped in that slab (`clip =
//! None`), else in every slab `far ..= near` with `clip = Some((near_s,
//! far_s))`, the slab's interval (infinite for the two outer slabs). As the
//! intervals are half-open and tile the depth axis, each point of each
//! triangle is drawn in exactly one slab: a flat triangle lying on a slice
//! plane once, in the slab behind that slice. The cost per view is
//! O(batches); no triangle is read or copied (a batch names its triangles by
//! a range of surface polygon ids).

use crate::data::grid::GridShape;
use crate::geometry::camera::Camera;
use crate::geometry::vec3::{dot, sub};
use crate::octree::{NodeId, VolumeOctree};
use crate::plan::select::Selection;
use crate::surface::Surface;
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::Range;

/// Triangles of the surface drawn between two slices of a brick.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Batch {
    /// Slab index within the brick: slab `s` lies between slices `s - 1` and
    /// `s` (slices back to front, see
    /// [`BrickDraw::slices`](crate::plan::BrickDraw::slices)); slab 0 is
    /// behind the first slice, slab `n` in front of the last (see the module
    /// documentation).
    pub slab: usize,
    /// Surface triangle ids (polygon ids of the surface, contiguous: the
    /// polygons of one or more terminal surface nodes, see
    /// [`SlabPolygons`]).
    pub triangles: std::ops::Range<u32>,
    /// `Some((near, far))`: clip to view depths `near <= depth < far`
    /// (batches whose triangles span more than this slab).
    pub clip: Option<(f64, f64)>,
}

/// View depths `k * spacing` of the view-aligned slice planes through the
/// box `[world_lo, world_hi]`, back to front (largest depth first): those
/// with `d_min <= k * spacing < d_max`, `d_min` and `d_max` the smallest and
/// largest view depth of the box's 8 corners (see the module documentation).
///
/// Empty when `spacing` is not a positive finite number, or the box is not
/// finite.
pub fn slice_depths(camera: &Camera, world_lo: [f64; 3], world_hi: [f64; 3], spacing: f64) -> Vec<f64> {
    if !(spacing > 0.0 && spacing.is_finite()) {
        return Vec::new();
    }
    let f = camera.forward();
    let (mut d_min, mut d_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for o in 0..8 {
        let corner = [0, 1, 2].map(|a| if o >> a & 1 == 1 { world_hi[a] } else { world_lo[a] });
        let d = dot(sub(corner, camera.position), f);
        d_min = d_min.min(d);
        d_max = d_max.max(d);
    }
    if !(d_min.is_finite() && d_max.is_finite()) {
        return Vec::new();
    }
    // One integer k to either side of the exact range, then the exact test on
    // the depth itself: rounding in d / spacing cannot add or drop a slice.
    let k_lo = (d_min / spacing).floor() - 1.0;
    let mut k = (d_max / spacing).ceil() + 1.0;
    let mut slices = Vec::with_capacity(((k - k_lo).max(0.0) as usize).min(1 << 16));
    while k >= k_lo {
        let d = k * spacing;
        if d_min <= d && d < d_max {
            slices.push(d);
        }
        k -= 1.0;
    }
    slices
}

/// The slab of view depth `depth`: `#{ i : slices[i] > depth }` (slices back
/// to front, see the module documentation). A depth exactly on slice `i`
/// gives `i`, the slab behind that slice.
pub fn slab_of(slices: &[f64], depth: f64) -> usize {
    slices.partition_point(|&s| s > depth)
}

/// The slabs a primitive of view depths `[d_lo, d_hi]` is drawn in, with
/// their clip intervals: the one rule of the CPU compositor (through
/// [`assign_batches`], per batch) and of the OpenGL mapper (per triangle,
/// [`crate::plan::draw_geometry::brick_geometry()`]):
///
/// ```text
/// far = slab(d_hi),  near = slab(d_lo)
/// far = near:  (far, None)                                   unclipped in its one slab
/// else:        (s, Some(slab_interval(s)))  for s = far ..= near   clipped to each slab it covers
/// ```
///
/// Nothing when `far > near` (a NaN range: `d_lo = +inf, d_hi = -inf` with slices).
pub fn slab_copies(slices: &[f64], d_lo: f64, d_hi: f64) -> impl Iterator<Item = (usize, Option<(f64, f64)>)> + '_ {
    let (far, near) = (slab_of(slices, d_hi), slab_of(slices, d_lo));
    let clipped = far != near;
    (far..=near).map(move |s| (s, clipped.then(|| slab_interval(slices, s))))
}

/// The depth interval `(near, far)` of slab `slab`: `near <= d < far` with
/// `near = slices[slab]` (`-inf` for `slab = n`) and `far = slices[slab - 1]`
/// (`+inf` for `slab = 0`). Panics if `slab > slices.len()`.
pub fn slab_interval(slices: &[f64], slab: usize) -> (f64, f64) {
    assert!(slab <= slices.len(), "slab {slab} of {} slices: there are only slices + 1 slabs", slices.len());
    let near = slices.get(slab).copied().unwrap_or(f64::NEG_INFINITY);
    let far = if slab == 0 { f64::INFINITY } else { slices[slab - 1] };
    (near, far)
}

/// One batch of [`SlabPolygons`]: the polygons of one terminal surface node
/// (surface polygon ids `triangles`, contiguous in the surface, see
/// `Surface::node_ranges`) and the tight world box of their vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonBatch {
    /// Surface polygon ids.
    pub triangles: Range<u32>,
    /// World box of the triangles' vertices (smallest corner).
    pub lo: [f64; 3],
    /// World box of the triangles' vertices (largest corner).
    pub hi: [f64; 3],
}

/// The SlabPolygons of a selection (paper 1, section 4.1: built once by the
/// slab integration phase, "the set of surface nodes" of each brick): per
/// selected brick, its surface polygons grouped by terminal surface node into
/// [`PolygonBatch`]es with their world boxes. View independent: make it once
/// per selection (and surface); [`assign_batches`] (UpdatePosition) then
/// places the batches into the slabs of each new view in O(batches), without
/// touching a triangle.
///
/// A terminal surface node lies inside exactly one brick of the cut, its own
/// or an ancestor's, found by walking up the octree from the node (`(level,
/// c) -> (level - 1, c / 2)`); nodes under no brick (left out of the cut)
/// give no batch.
#[derive(Debug, Clone, PartialEq)]
pub struct SlabPolygons {
    /// The bricks' nodes, in selection order.
    bricks: Vec<NodeId>,
    /// Brick `i`'s batches are `batches[starts[i]..starts[i + 1]]`.
    starts: Vec<u32>,
    /// All batches, brick after brick, in surface order within a brick.
    batches: Vec<PolygonBatch>,
    /// The surface's polygon count (to check the surface given with it).
    polygons: usize,
}

impl SlabPolygons {
    /// The SlabPolygons of `selection`'s bricks for `surface` (see the type
    /// documentation). Parallel over surface nodes; deterministic.
    pub fn new(octree: &VolumeOctree, surface: &Surface, shape: &GridShape, selection: &Selection) -> Self {
        let bricks: Vec<NodeId> = selection.bricks.iter().map(|b| b.node).collect();
        let index: HashMap<NodeId, u32> = bricks.iter().enumerate().map(|(i, &id)| (id, i as u32)).collect();
        let layout = octree.layout();
        // (brick, batch) per surface node with polygons.
        let mut found: Vec<(u32, PolygonBatch)> = surface
            .node_ranges
            .par_iter()
            .filter(|&&(_, first, end)| first < end)
            .filter_map(|&(node, first, end)| {
                let (mut level, mut c) = layout.locate(node);
                let brick = loop {
                    if let Some(&b) = index.get(&layout.id(level, c)) {
                        break b;
                    }
                    if level == 0 {
                        return None;
                    }
                    level -= 1;
                    c = c.map(|v| v / 2);
                };
                let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for t in first..end {
                    for &v in surface.polygon(t as usize) {
                        let p = shape.world(surface.points[v as usize]);
                        for a in 0..3 {
                            lo[a] = lo[a].min(p[a]);
                            hi[a] = hi[a].max(p[a]);
                        }
                    }
                }
                Some((brick, PolygonBatch { triangles: first..end, lo, hi }))
            })
            .collect();
        // Stable: surface order within a brick.
        found.sort_by_key(|e| e.0);
        let mut starts = vec![0u32; bricks.len() + 1];
        for &(b, _) in &found {
            starts[b as usize + 1] += 1;
        }
        for i in 1..starts.len() {
            starts[i] += starts[i - 1];
        }
        let batches = found.into_iter().map(|e| e.1).collect();
        SlabPolygons { bricks, starts, batches, polygons: surface.polygon_count() }
    }

    /// The batches of brick `i` (selection order).
    pub fn brick(&self, i: usize) -> &[PolygonBatch] {
        &self.batches[self.starts[i] as usize..self.starts[i + 1] as usize]
    }

    /// Number of batches over all bricks.
    pub fn batch_count(&self) -> usize {
        self.batches.len()
    }

    /// Whether this was made for `selection`'s bricks (their nodes, in
    /// order: strides do not matter) and a surface of `polygons` polygons.
    pub fn fits(&self, selection: &Selection, polygons: usize) -> bool {
        self.polygons == polygons
            && self.bricks.len() == selection.bricks.len()
            && self.bricks.iter().zip(&selection.bricks).all(|(&a, b)| a == b.node)
    }
}

/// UpdatePosition (paper 1, section 4.1: "determines the new slab position
/// by applying the viewing transformation" to each surface node): the slab
/// batches of one brick's [`PolygonBatch`]es for a brick sliced at `slices`
/// (view depths, back to front, strictly decreasing, as [`slice_depths`]
/// gives them), seen from `camera`. A pure function of the camera, O(batches):
/// call it again for a new view.
///
/// A batch's depth range `[d_lo, d_hi]` is that of the 8 corners of its
/// box, widened by a few rounding units `r` (so that every vertex depth,
/// however rounded, lies inside). It covers the slabs
///
/// ```text
/// far = slab(d_hi + r),   near = slab(d_lo - r)
/// ```
///
/// and goes, if `far = near`, unclipped into that slab (`clip = None`), else
/// into every slab `far ..= near` with `clip = Some((near_s, far_s))`, the
/// slab's interval ([`slab_interval`]; the outer slabs' are unbounded): the
/// rule of [`slab_copies`], which the OpenGL mapper applies per triangle. As
/// the clip intervals are half-open (`near_s <= depth < far_s`) and tile the
/// depth axis, every point of every triangle is drawn in exactly one slab,
/// a flat triangle on a slice plane included (in the slab behind it).
///
/// Batches come back to front: by slab, and in a slab the unclipped ones
/// before the clipped ones, in the input order; consecutive batches of the
/// same slab and clip whose triangle ranges touch are merged into one. A
/// batch with a non-finite box goes unclipped into slab 0.
pub fn assign_batches(camera: &Camera, slices: &[f64], batches: &[PolygonBatch]) -> Vec<Batch> {
    debug_assert!(slices.windows(2).all(|w| w[0] > w[1]), "slices must be back to front: strictly decreasing");
    let f = camera.forward();
    let e = camera.position;
    // (slab * 2 + clipped, triangles), then stably sorted: back to front.
    let mut placed: Vec<(usize, Range<u32>)> = Vec::with_capacity(batches.len());
    for b in batches {
        // The nearest and farthest corners: per axis the side towards and away from the eye.
        let (mut d_lo, mut d_hi, mut size) = (0.0, 0.0, 0.0);
        for a in 0..3 {
            let (u, v) = ((b.lo[a] - e[a]) * f[a], (b.hi[a] - e[a]) * f[a]);
            d_lo += u.min(v);
            d_hi += u.max(v);
            size += u.abs().max(v.abs());
        }
        let r = 16.0 * f64::EPSILON * size;
        if !(d_lo.is_finite() && d_hi.is_finite()) {
            placed.push((0, b.triangles.clone()));
        } else {
            let copies = slab_copies(slices, d_lo - r, d_hi + r);
            placed.extend(copies.map(|(s, clip)| (2 * s + usize::from(clip.is_some()), b.triangles.clone())));
        }
    }
    placed.sort_by_key(|p| p.0);
    let mut out: Vec<Batch> = Vec::with_capacity(placed.len());
    for (key, triangles) in placed {
        let (slab, clipped) = (key / 2, key % 2 == 1);
        if let Some(last) = out.last_mut() {
            if last.slab == slab && last.clip.is_some() == clipped && last.triangles.end == triangles.start {
                last.triangles.end = triangles.end;
                continue;
            }
        }
        let clip = clipped.then(|| slab_interval(slices, slab));
        out.push(Batch { slab, triangles, clip });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::geometry::vec3::cross;
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, SelectOptions};
    use crate::surface::SurfaceOptions;

    /// A triangle in world space with its surface triangle id.
    type WorldTriangle = (u32, [[f64; 3]; 3]);

    /// A triangle drawn in a slab: (triangle, slab, clip).
    type Drawn = (u32, usize, Option<(f64, f64)>);

    fn cam(position: [f64; 3], focal: [f64; 3], parallel: bool) -> Camera {
        crate::geometry::camera::test_camera(position, focal, parallel.then_some(20.0))
    }

    fn polygon_area(p: &[[f64; 3]]) -> f64 {
        let mut n = [0.0; 3];
        for i in 1..p.len().saturating_sub(1) {
            let c = cross(sub(p[i], p[0]), sub(p[i + 1], p[0]));
            n = [0, 1, 2].map(|a| n[a] + c[a]);
        }
        0.5 * dot(n, n).sqrt()
    }

    /// Sutherland-Hodgman against `sign * (depth - bound) >= 0`.
    fn clip_plane(camera: &Camera, poly: Vec<[f64; 3]>, bound: f64, sign: f64) -> Vec<[f64; 3]> {
        if bound.is_infinite() {
            return poly; // an unbounded side cuts nothing
        }
        let inside = |p: [f64; 3]| sign * (camera.depth(p) - bound) >= 0.0;
        let mut out = Vec::new();
        for i in 0..poly.len() {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            if inside(p) {
                out.push(p);
            }
            if inside(p) != inside(q) {
                let (dp, dq) = (camera.depth(p), camera.depth(q));
                let t = (bound - dp) / (dq - dp);
                out.push([0, 1, 2].map(|a| p[a] + t * (q[a] - p[a])));
            }
        }
        out
    }

    /// Area of the part of `tri` with `near <= depth <= far` (the boundary planes have no area).
    fn clipped_area(camera: &Camera, tri: [[f64; 3]; 3], near: f64, far: f64) -> f64 {
        let poly = clip_plane(camera, tri.to_vec(), near, 1.0);
        polygon_area(&clip_plane(camera, poly, far, -1.0))
    }

    /// The area of `tri` drawn in a slab: all of it unclipped, else its part
    /// with `near <= depth < far` (a flat triangle wholly or not at all, by
    /// the half-open rule; for the others the planes have no area).
    fn drawn_area(camera: &Camera, tri: [[f64; 3]; 3], clip: Option<(f64, f64)>) -> f64 {
        let d = tri.map(|p| camera.depth(p));
        match clip {
            None => polygon_area(&tri),
            Some((near, far)) if d[0] == d[1] && d[1] == d[2] => {
                if near <= d[0] && d[0] < far {
                    polygon_area(&tri)
                } else {
                    0.0
                }
            }
            Some((near, far)) => clipped_area(camera, tri, near, far),
        }
    }

    /// The drawn area of each (triangle, slab) pair.
    fn areas(
        camera: &Camera,
        index: &HashMap<u32, [[f64; 3]; 3]>,
        drawn: impl IntoIterator<Item = Drawn>,
    ) -> HashMap<(u32, usize), f64> {
        let mut out: HashMap<(u32, usize), f64> = HashMap::new();
        for (t, slab, clip) in drawn {
            *out.entry((t, slab)).or_default() += drawn_area(camera, index[&t], clip);
        }
        out.retain(|_, a| *a > 0.0);
        out
    }

    /// The old per-triangle assignment (every triangle on its own, by its
    /// vertex depths `[d_lo, d_hi]`: `near = slab(d_lo)`, `far = #{ i :
    /// slices[i] >= d_hi }`, or `slab(d_hi)` if flat), as (triangle, slab,
    /// clip): the reference the batches must draw the same areas as.
    fn per_triangle(camera: &Camera, slices: &[f64], tris: &[WorldTriangle]) -> Vec<Drawn> {
        let mut out = Vec::new();
        for &(id, tri) in tris {
            let d = tri.map(|p| camera.depth(p));
            let (d_lo, d_hi) = (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]));
            let near = slab_of(slices, d_lo);
            let far = if d_lo < d_hi { slices.partition_point(|&s| s >= d_hi) } else { near };
            if far == near {
                out.push((id, near, None));
            } else {
                out.extend((far..=near).map(|s| (id, s, Some(slab_interval(slices, s)))));
            }
        }
        out
    }

    /// Batches of `size` consecutive triangles (ids consecutive, see
    /// [`random_triangles`]), each with its vertices' box.
    fn batches_of(tris: &[WorldTriangle], size: usize) -> Vec<PolygonBatch> {
        tris.chunks(size)
            .map(|c| {
                let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for p in c.iter().flat_map(|t| t.1) {
                    lo = [0, 1, 2].map(|a| lo[a].min(p[a]));
                    hi = [0, 1, 2].map(|a| hi[a].max(p[a]));
                }
                PolygonBatch { triangles: c[0].0..c[c.len() - 1].0 + 1, lo, hi }
            })
            .collect()
    }

    /// The batches of `batches` in `slices`, checked: back to front,
    /// intervals, unclipped triangles inside their slab, and per triangle
    /// the drawn area is its area (nothing lost, nothing drawn twice) and,
    /// slab by slab, what the old per-triangle assignment draws.
    fn check_areas(camera: &Camera, slices: &[f64], tris: &[WorldTriangle], batches: &[PolygonBatch]) -> Vec<Batch> {
        assert!(slices.windows(2).all(|w| w[0] > w[1]));
        let out = assign_batches(camera, slices, batches);
        assert!(out.windows(2).all(|w| w[0].slab < w[1].slab || (w[0].slab == w[1].slab && w[0].clip <= w[1].clip)));
        let index: HashMap<u32, [[f64; 3]; 3]> = tris.iter().copied().collect();
        let mut drawn = Vec::new();
        for b in &out {
            let (near, far) = slab_interval(slices, b.slab);
            for t in b.triangles.clone() {
                if b.clip.is_none() {
                    let d = index[&t].map(|p| camera.depth(p));
                    let (lo, hi) = (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]));
                    assert!(near <= lo && hi < far, "unclipped triangle {t} ({lo}, {hi}) outside slab ({near}, {far})");
                } else {
                    assert_eq!(b.clip, Some((near, far)));
                }
                drawn.push((t, b.slab, b.clip));
            }
        }
        let got = areas(camera, &index, drawn);
        let old = areas(camera, &index, per_triangle(camera, slices, tris));
        let close = |a: f64, b: f64, area: f64| (a - b).abs() <= 1e-9 * area;
        for &(t, tri) in tris {
            let area = polygon_area(&tri);
            let total: f64 = got.iter().filter(|e| e.0 .0 == t).map(|e| e.1).sum();
            assert!(close(total, area, area), "triangle {t}: drawn area {total}, area {area}");
        }
        for key in got.keys().chain(old.keys()) {
            let area = polygon_area(&index[&key.0]);
            let (g, o) = (got.get(key).copied().unwrap_or(0.0), old.get(key).copied().unwrap_or(0.0));
            assert!(close(g, o, area), "triangle {}, slab {}: {g} drawn, {o} before", key.0, key.1);
        }
        out
    }

    /// The slabs drawing a positive area of triangle `id`, with whether clipped.
    fn slabs_of(camera: &Camera, tris: &[WorldTriangle], batches: &[Batch], id: u32) -> Vec<(usize, bool)> {
        let tri = tris.iter().find(|t| t.0 == id).unwrap().1;
        batches
            .iter()
            .filter(|b| b.triangles.contains(&id) && drawn_area(camera, tri, b.clip) > 0.0)
            .map(|b| (b.slab, b.clip.is_some()))
            .collect()
    }

    /// Deterministic pseudo-random numbers in [0, 1).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn random_triangles(seed: u64, count: usize, lo: f64, hi: f64) -> Vec<WorldTriangle> {
        let mut r = Lcg(seed);
        (0..count as u32)
            .map(|id| {
                let c = [0, 1, 2].map(|_| lo + (hi - lo) * r.next());
                // Small and large triangles: some span many slabs, some none.
                let size = if id % 3 == 0 { 8.0 } else { 0.7 };
                (id, [0, 1, 2].map(|_| [0, 1, 2].map(|a| c[a] + size * (r.next() - 0.5))))
            })
            .filter(|(_, t)| polygon_area(t) > 1e-6)
            .enumerate()
            .map(|(k, (_, t))| (k as u32, t))
            .collect()
    }

    fn axis_cameras(c: [f64; 3], r: f64) -> Vec<Camera> {
        let mut cams = Vec::new();
        for a in 0..3 {
            for s in [-1.0, 1.0] {
                let mut p = c;
                p[a] += s * 3.0 * r;
                cams.push(cam(p, c, false));
                cams.push(cam(p, c, true));
            }
        }
        cams
    }

    #[test]
    fn slices_are_lattice_planes_back_to_front_and_shared() {
        // Looking along +z from z = -10: depth = z + 10 exactly.
        let camera = cam([0.5, 0.5, -10.0], [0.5, 0.5, 0.0], false);
        assert_eq!(
            slice_depths(&camera, [0.0; 3], [1.0, 1.0, 8.0], 1.0),
            (10..18).rev().map(f64::from).collect::<Vec<_>>()
        );
        assert_eq!(slice_depths(&camera, [0.0; 3], [1.0, 1.0, 8.0], 3.0), vec![15.0, 12.0]);
        // Two bricks stacked along the view: every plane once.
        let mut both = slice_depths(&camera, [0.0, 0.0, 8.0], [1.0, 1.0, 16.0], 1.0);
        both.extend(slice_depths(&camera, [0.0; 3], [1.0, 1.0, 8.0], 1.0));
        assert_eq!(both, (10..26).rev().map(f64::from).collect::<Vec<_>>());
        assert!(slice_depths(&camera, [0.0; 3], [1.0; 3], 0.0).is_empty());
        assert!(slice_depths(&camera, [0.0; 3], [1.0; 3], f64::NAN).is_empty());
        // Oblique views: exactly the multiples of the spacing in [d_min, d_max).
        for (p, spacing) in [([-7.0, 3.0, -9.0], 0.37), ([20.0, 21.0, 25.0], 2.0), ([1.0, -30.0, 2.0], 1.0)] {
            for parallel in [false, true] {
                let camera = cam(p, [4.0, 5.0, 6.0], parallel);
                let (lo, hi) = ([1.0, 2.0, 3.0], [9.0, 7.0, 11.0]);
                let s = slice_depths(&camera, lo, hi, spacing);
                let d: Vec<f64> = (0..8)
                    .map(|o| camera.depth([0, 1, 2].map(|a| if o >> a & 1 == 1 { hi[a] } else { lo[a] })))
                    .collect();
                let d_min = d.iter().copied().fold(f64::INFINITY, f64::min);
                let d_max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                assert!(s.windows(2).all(|w| w[0] > w[1]));
                assert!(s.iter().all(|&x| d_min <= x && x < d_max && x == (x / spacing).round() * spacing));
                let count = ((d_max / spacing).ceil() - (d_min / spacing).ceil()) as usize;
                assert!(s.len().abs_diff(count) <= 1, "{} slices, about {count} expected", s.len());
                assert!(s[0] + spacing >= d_max && s[s.len() - 1] - spacing < d_min, "a plane is missing");
            }
        }
    }

    #[test]
    fn slabs_and_intervals() {
        let slices = [5.0, 3.0, 1.0];
        assert_eq!([7.0, 5.0, 4.0, 3.0, 2.0, 1.0, 0.0].map(|d| slab_of(&slices, d)), [0, 0, 1, 1, 2, 2, 3]);
        assert_eq!(slab_interval(&slices, 0), (5.0, f64::INFINITY));
        assert_eq!(slab_interval(&slices, 2), (1.0, 3.0));
        assert_eq!(slab_interval(&slices, 3), (f64::NEG_INFINITY, 1.0));
        assert_eq!(slab_of(&[], 3.0), 0);
        assert_eq!(slab_interval(&[], 0), (f64::NEG_INFINITY, f64::INFINITY));
    }

    #[test]
    fn vertices_on_slice_planes_along_an_axis() {
        // Depth = z + 10 exactly; slices 17 .. 10 (brick z in [0, 8], spacing 1).
        let camera = cam([0.5, 0.5, -10.0], [0.5, 0.5, 0.0], false);
        let slices = slice_depths(&camera, [0.0; 3], [1.0, 1.0, 8.0], 1.0);
        assert_eq!(slices.len(), 8);
        let t = |z: [f64; 3]| [[0.0, 0.0, z[0]], [1.0, 0.0, z[1]], [0.0, 1.0, z[2]]];
        let tris: Vec<WorldTriangle> = vec![
            (0, t([4.0, 4.0, 4.0])),    // flat, on the plane of depth 14
            (1, t([4.0, 4.0, 4.5])),    // an edge on a plane, inside [14, 15)
            (2, t([4.0, 5.0, 4.0])),    // apex on the far plane 15: still one slab
            (3, t([3.0, 5.0, 4.0])),    // vertices on three planes: two slabs
            (4, t([-3.0, 12.0, 2.0])),  // beyond both ends
            (5, t([9.0, 9.0, 9.0])),    // flat, behind the first slice
            (6, t([-1.0, -1.0, -1.0])), // flat, in front of the last slice
            (7, t([7.0, 7.0, 7.0])),    // flat, on the first slice (depth 17)
            (8, t([0.0, 0.0, 0.0])),    // flat, on the last slice (depth 10)
            (9, t([4.2, 4.8, 4.5])),    // strictly inside [14, 15)
        ];
        let batches = check_areas(&camera, &slices, &tris, &batches_of(&tris, 1));
        let slabs_of = |id: u32| slabs_of(&camera, &tris, &batches, id);
        // Flat on slice 3 (depth 14): drawn in the slab behind it only (the
        // batch touches the plane, so it is clipped to both sides).
        assert_eq!(slabs_of(0), vec![(3, true)]);
        assert_eq!(slabs_of(1), vec![(3, true)]);
        assert_eq!(slabs_of(2), vec![(3, true)]);
        assert_eq!(slabs_of(3), vec![(3, true), (4, true)]);
        assert_eq!(slabs_of(4), (0..=8).map(|s| (s, true)).collect::<Vec<_>>());
        assert_eq!(slabs_of(5), vec![(0, false)]);
        assert_eq!(slabs_of(6), vec![(8, false)]);
        assert_eq!(slabs_of(7), vec![(0, true)]);
        assert_eq!(slabs_of(8), vec![(7, true)]);
        assert_eq!(slabs_of(9), vec![(3, false)]);
        // All in one batch: clipped in every slab, the same areas.
        check_areas(&camera, &slices, &tris, &batches_of(&tris, tris.len()));
        // Without slices: one unclipped batch (the consecutive ranges merged).
        let all = assign_batches(&camera, &[], &batches_of(&tris, 1));
        assert_eq!(all, vec![Batch { slab: 0, triangles: 0..10, clip: None }]);
    }

    #[test]
    fn vertices_on_slice_planes_in_any_view() {
        // Slices put exactly at vertex depths, whatever the view.
        let tris = random_triangles(7, 60, 0.0, 10.0);
        for camera in [cam([-7.0, 3.0, -9.0], [5.0; 3], false), cam([13.0, 22.0, -4.0], [5.0; 3], true)] {
            let mut slices: Vec<f64> = tris.iter().step_by(4).flat_map(|t| t.1.map(|p| camera.depth(p))).collect();
            slices.sort_by(|a, b| b.total_cmp(a));
            slices.dedup();
            for size in [1, 3, 20] {
                check_areas(&camera, &slices, &tris, &batches_of(&tris, size));
            }
        }
    }

    #[test]
    fn no_triangle_lost_or_drawn_twice_in_any_view() {
        let tris = random_triangles(42, 300, -2.0, 18.0);
        let c = [8.0; 3];
        let mut cameras = axis_cameras(c, 10.0);
        for p in [[-20.0, -15.0, -25.0], [30.0, -4.0, 11.0], [8.0, 8.0, 8.5], [3.0, 40.0, 8.0], [8.0, -30.0, 8.0001]] {
            cameras.push(cam(p, c, false));
            cameras.push(cam(p, c, true));
        }
        // Grazing: views with zero components, and one along the diagonal of the box.
        cameras.push(cam([30.0, 30.0, 8.0], c, true));
        cameras.push(cam([-20.0, 8.0, 36.0], c, false));
        cameras.push(cam([-10.0, -10.0, -10.0], c, true));
        // Perspective from inside the box.
        cameras.push(cam([5.0, 9.0, 7.0], [12.0, 2.0, 10.0], false));
        for camera in &cameras {
            for spacing in [0.5, 1.0, 4.0] {
                let slices = slice_depths(camera, [0.0; 3], [16.0; 3], spacing);
                assert!(!slices.is_empty());
                let batches = check_areas(camera, &slices, &tris, &batches_of(&tris, 1));
                assert!(batches.iter().any(|b| b.clip.is_some()) && batches.iter().any(|b| b.clip.is_none()));
                for size in [4, 50] {
                    check_areas(camera, &slices, &tris, &batches_of(&tris, size));
                }
            }
        }
    }

    #[test]
    fn triangles_parallel_to_the_slices_in_a_grazing_view() {
        // Looking along (1, 1, 0): slices are the planes x + y = const. Flat
        // triangles in those planes, some exactly on a slice (when the
        // rounding allows), some edge-on to the view (containing f).
        let camera = cam([-10.0, -10.0, 3.0], [5.0, 5.0, 3.0], true);
        let f = camera.forward();
        assert_eq!(f[2], 0.0);
        let slices = slice_depths(&camera, [0.0; 3], [8.0; 3], 1.0);
        let mut tris = Vec::new();
        for &d in &slices {
            // A point at depth d, and two offsets across the view: x - y and z.
            let p0 = [0, 1, 2].map(|a| camera.position[a] + d * f[a]);
            let tri = [p0, [p0[0] + 1.0, p0[1] - 1.0, p0[2]], [p0[0], p0[1], p0[2] + 1.0]];
            tris.push((tris.len() as u32, tri));
            // Edge-on: spans depth along f, zero extent across one direction.
            let edge_on = [p0, [p0[0] + 0.8, p0[1] + 0.8, p0[2]], [p0[0], p0[1], p0[2] + 2.0]];
            tris.push((tris.len() as u32, edge_on));
        }
        let batches = check_areas(&camera, &slices, &tris, &batches_of(&tris, 1));
        check_areas(&camera, &slices, &tris, &batches_of(&tris, 2));
        // Each in-plane triangle is drawn once, or, if rounding tilts it off
        // the plane, split across the plane without extra area (checked
        // above); the exact-depth ones in the slab behind the slice.
        for &(id, tri) in tris.iter().step_by(2) {
            let d = tri.map(|p| camera.depth(p));
            if d[0] == d[1] && d[1] == d[2] {
                let hits = slabs_of(&camera, &tris, &batches, id);
                assert_eq!(hits.len(), 1, "flat triangle {id} drawn {} times", hits.len());
                assert_eq!(hits[0].0, slab_of(&slices, d[0]));
            }
        }
    }

    #[test]
    fn a_new_camera_reassigns() {
        let tris = random_triangles(3, 100, 0.0, 16.0);
        let batches = batches_of(&tris, 3);
        let a = cam([-20.0, 8.0, 8.0], [8.0; 3], false);
        let b = cam([8.0, 30.0, 40.0], [8.0; 3], false);
        let sa = slice_depths(&a, [0.0; 3], [16.0; 3], 1.0);
        let sb = slice_depths(&b, [0.0; 3], [16.0; 3], 1.0);
        let first = assign_batches(&a, &sa, &batches);
        let moved = check_areas(&b, &sb, &tris, &batches);
        assert_ne!(first, moved);
        assert_eq!(assign_batches(&a, &sa, &batches), first, "deterministic");
    }

    #[test]
    fn a_real_surface_through_the_bricks_of_a_selection() {
        let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        let surface = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(0.5)).unwrap();
        assert!(surface.polygon_count() > 100);
        let shape = *grid.shape();
        let world = |t: u32| surface.polygon(t as usize).iter().map(|&v| shape.world(surface.points[v as usize]));
        let cameras = [
            cam([-30.0, 10.0, 60.0], [16.0; 3], false),
            cam([16.0, -50.0, 16.0], [16.0; 3], true),
            cam([16.0, 16.0, -40.0], [16.0; 3], false),
            cam([-20.0, -20.0, -20.0], [16.0; 3], true),
            cam([12.3, 17.1, 20.2], [30.0, 2.0, 16.0], false),
        ];
        for budget in [40_000, 300_000, 10_000_000] {
            let selection = select(&octree, &SelectOptions::new(budget, 0.0), |_, _| true).unwrap();
            let polygons = SlabPolygons::new(&octree, &surface, &shape, &selection);
            assert!(polygons.fits(&selection, surface.polygon_count()));
            assert!(!polygons.fits(&selection, surface.polygon_count() + 1));
            assert_eq!(SlabPolygons::new(&octree, &surface, &shape, &selection), polygons, "deterministic");
            let mut seen = vec![0u32; surface.polygon_count()];
            for (i, brick) in selection.bricks.iter().enumerate() {
                let (world_lo, world_hi) =
                    (shape.world(brick.lo.map(|v| v as f64)), shape.world(brick.hi.map(|v| v as f64)));
                let batches = polygons.brick(i);
                let mut tris: Vec<WorldTriangle> = Vec::new();
                for b in batches {
                    assert!(!b.triangles.is_empty());
                    // Independent of the ancestor walk: the batch lies in its brick's box.
                    assert!((0..3).all(|a| world_lo[a] <= b.lo[a] && b.hi[a] <= world_hi[a]));
                    for t in b.triangles.clone() {
                        seen[t as usize] += 1;
                        let p: Vec<[f64; 3]> = world(t).collect();
                        assert!(p.iter().all(|v| (0..3).all(|a| b.lo[a] <= v[a] && v[a] <= b.hi[a])), "tight box");
                        tris.push((t, [p[0], p[1], p[2]]));
                    }
                }
                for camera in &cameras {
                    let slices = slice_depths(camera, world_lo, world_hi, brick.stride as f64);
                    check_areas(camera, &slices, &tris, batches);
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "a triangle in no brick or in two");
            assert_eq!(
                polygons.batch_count(),
                (0..selection.bricks.len()).map(|i| polygons.brick(i).len()).sum::<usize>()
            );
        }
    }
}
