//! The OpenGL mapper's vertices of a DrawList: each brick's slices with the
//! translucent surface's triangles and the hybrid points in the slabs between
//! them (paper 1, sections 3 and 4.1; paper 3, section 4), every vertex
//! naming its brick, so that the bricks of one texture page draw in one call.
//!
//! With a brick's slices at view depths `S[0] > S[1] > ... > S[n-1]` (back
//! to front, `z = (x - eye) . forward`), slab `s = {z : S[s] <= z < S[s-1]}`
//! and `slab(z) = #{k : S[k] > z}` ([`crate::plan::slab::slab_of`]). Each triangle named by the
//! brick's batches (the union of their ranges, once each) goes, from the
//! depths `[z_min, z_max]` of its vertices, where [`slab_copies`] puts it,
//! the rule the CPU compositor applies to the batches: unclipped when
//! `slab(z_max) = slab(z_min)`, else once per slab `slab(z_max) ..= slab(z_min)`
//! clipped to it, the shader's `gl_ClipDistance[0] = z - near`,
//! `gl_ClipDistance[1] = far - z` (an unbounded side `±1e30`). A brick's
//! vertices are then, back to front,
//!
//! ```text
//! slab 0's items, slice 0, slab 1's items, slice 1, ..., slice n-1, slab n's items
//! ```
//!
//! a slab's items (its triangle copies and the points of the DrawList's
//! buckets of that slab that add something, opacity `a_p > 0`) far first,
//! as the CPU compositor sorts a pixel's hits in a slab: a triangle at its
//! centroid's depth clamped to its clip interval, a point at its depth, ties
//! in that order (stable). A slice is the polygon of its plane inside the
//! brick's drawn box ([`append_slice_polygon`]), none when the brick is not
//! drawn (no visible block). A brick with no triangle or point between its
//! slices is ray-marched: drawn as its drawn box's 12 triangles instead,
//! wound counter-clockwise seen from inside (culling back faces leaves the
//! faces rays leave by: one fragment a pixel).
//!
//! Each vertex is [`FLOATS_PER_VERTEX`] floats: position, normal, clip
//! interval `(near, far)`, [`PrimitiveKind`], point opacity, and its brick's
//! index in the list (exact in `f32` below [`MAX_BRICKS`]). A point is a quad
//! (two triangles) whose six vertices all hold its centre, its straight
//! colour in the normal, their corner `(±1, ±1)` in the clip interval and
//! its opacity. Depths are computed as the mapper computed them: a triangle's
//! in `f64` from `f32` differences `(p - eye)` times `f64(f32(forward))`, a
//! point's in `f64` throughout; the vertex stream is bit for bit the one the
//! C++ made.

use super::slice_polygon::{append_slice_polygon, corner, view_basis};
use crate::base::error::{Error, Result};
use crate::plan::slab::slab_copies;
use crate::plan::DrawList;
use std::cmp::Ordering;
use std::ops::Range;

/// Floats per vertex: position (3), normal (3), clip interval (2), kind, point opacity, brick index.
pub const FLOATS_PER_VERTEX: usize = 11;

/// The most bricks a geometry names: every index below it is an exact `f32` (2^24).
pub const MAX_BRICKS: usize = 1 << 24;

/// An unbounded side of a clip interval (the shader's clip distances stay finite).
pub const UNBOUNDED: f32 = 1.0e30;

/// What a vertex belongs to, as the shaders name them (SLICE, SURFACE_TRIANGLE, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(i32)]
pub enum PrimitiveKind {
    /// A slice polygon.
    Slice = 0,
    /// A surface triangle in a slab.
    SurfaceTriangle = 1,
    /// A face of a ray-marched brick's box.
    RayMarchedBox = 2,
    /// A point drawn as a square.
    SquarePoint = 3,
    /// A point drawn as a Gaussian splat.
    GaussianPoint = 4,
}

/// The camera the geometry is made for (model coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeometryView {
    /// The eye.
    pub eye: [f64; 3],
    /// The unit view direction (the DrawList's).
    pub forward: [f64; 3],
    /// The camera's view up.
    pub view_up: [f64; 3],
}

/// One brick of the DrawList, as the geometry needs it.
#[derive(Debug, Clone, PartialEq)]
pub struct BrickSlabs<'a> {
    /// View depths of its slices, back to front.
    pub slices: &'a [f64],
    /// The box its slices are clipped to (VTK order: its visible blocks, see
    /// [`super::occupancy`]).
    pub bounds: [f64; 6],
    /// Whether it is drawn at all (false: no visible block).
    pub drawn: bool,
    /// The triangle ranges of its batches, in any order (a batch spanning
    /// slabs is listed once per slab: each triangle is placed once).
    pub batches: Vec<Range<u32>>,
    /// Its point buckets, back to front: (slab, point ids).
    pub buckets: Vec<(usize, &'a [u32])>,
}

/// The translucent surface: 6 floats a vertex (position, normal), triangle
/// `t`'s vertex ids at `3t .. 3t + 3` (the DrawList's triangle ids).
#[derive(Debug, Clone, Copy)]
pub struct SurfaceVertices<'a> {
    /// Position and normal, 6 floats a vertex.
    pub vertices: &'a [f32],
    /// 3 vertex ids a triangle.
    pub triangles: &'a [u32],
}

/// The hybrid points the buckets name.
#[derive(Debug, Clone, Copy)]
pub struct PointVertices<'a> {
    /// Positions, 3 floats a point.
    pub positions: &'a [f32],
    /// What each adds: straight colour and opacity `a_p`, 4 floats a point.
    pub shades: &'a [f32],
    /// Gaussian footprints (else squares).
    pub gaussian: bool,
}

/// The vertices of every brick (see the module documentation).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BrickGeometry {
    /// [`FLOATS_PER_VERTEX`] floats a vertex.
    pub vertices: Vec<f32>,
    /// Brick `i`'s vertices are `brick_first[i] .. brick_first[i + 1]`.
    pub brick_first: Vec<usize>,
    /// Per brick: drawn as its ray-marched box (else as slices).
    pub ray_marched: Vec<bool>,
    /// The view's up (unit, perpendicular to forward): a point quad's up.
    pub point_up: [f32; 3],
    /// Triangle copies placed (a triangle in several slabs counted each time).
    pub triangles_placed: usize,
    /// Points placed.
    pub points_placed: usize,
}

/// A triangle copy in a slab, clipped to `[near, far)`.
struct Placed {
    slab: usize,
    triangle: u32,
    near: f32,
    far: f32,
}

/// A slab's item at its view depth: a triangle copy (index into the
/// brick's placed copies) or a point (point id).
struct SlabItem {
    depth: f64,
    id: u32,
    point: bool,
}

/// `std::max(a, b)`: `b` only when `a < b` (NaN stays where it is).
fn cxx_max(a: f64, b: f64) -> f64 {
    if a < b {
        b
    } else {
        a
    }
}

/// `std::min(a, b)`: `b` only when `b < a`.
fn cxx_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The clip bound of a slab interval side: `±UNBOUNDED` for an outer slab.
fn clip_bound(v: f64) -> f32 {
    if v == f64::INFINITY {
        UNBOUNDED
    } else if v == f64::NEG_INFINITY {
        -UNBOUNDED
    } else {
        v as f32
    }
}

/// The vertex stream under construction.
struct Stream {
    data: Vec<f32>,
    /// The index of the brick being emitted (every vertex carries it).
    brick: f32,
}

impl Stream {
    fn emit(&mut self, position: &[f32], normal: &[f32], near: f32, far: f32, kind: PrimitiveKind, alpha: f32) {
        self.data.extend_from_slice(&position[..3]);
        self.data.extend_from_slice(&normal[..3]);
        self.data.extend([near, far, kind as i32 as f32, alpha, self.brick]);
    }

    /// The 12 triangles of a box, wound counter-clockwise seen from inside.
    fn emit_box(&mut self, bounds: &[f64; 6]) {
        const FACES: [[usize; 4]; 6] =
            [[0, 2, 6, 4], [1, 5, 7, 3], [0, 4, 5, 1], [2, 3, 7, 6], [0, 1, 3, 2], [4, 6, 7, 5]];
        for f in FACES {
            for k in [0, 1, 2, 0, 2, 3] {
                let p = corner(bounds, f[k]).map(|v| v as f32);
                self.emit(&p, &[0.0; 3], -UNBOUNDED, UNBOUNDED, PrimitiveKind::RayMarchedBox, 0.0);
            }
        }
    }

    /// Point `id`'s quad: two triangles, corners `(±1, ±1)`.
    fn emit_point(&mut self, points: &PointVertices<'_>, id: u32) {
        const CORNERS: [[f32; 2]; 6] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let kind = if points.gaussian { PrimitiveKind::GaussianPoint } else { PrimitiveKind::SquarePoint };
        let id = id as usize;
        let p = &points.positions[3 * id..3 * id + 3];
        let shade = &points.shades[4 * id..4 * id + 4];
        for c in CORNERS {
            self.emit(p, shade, c[0], c[1], kind, shade[3]);
        }
    }
}

/// The surface's triangle `t`'s vertices, each `[position, normal]`.
fn triangle<'a>(surface: &SurfaceVertices<'a>, t: u32) -> Result<[&'a [f32]; 3]> {
    let at = 3 * t as usize;
    let ids = surface.triangles.get(at..at + 3).ok_or_else(|| {
        Error::InvalidArgument(format!(
            "the DrawList names surface triangle {t}, the surface has {}: give the surface the list was made with",
            surface.triangles.len() / 3
        ))
    })?;
    let count = surface.vertices.len() / 6;
    let mut out: [&[f32]; 3] = [&[]; 3];
    for (c, &v) in ids.iter().enumerate() {
        let v = v as usize;
        if v >= count {
            return Err(Error::InvalidArgument(format!(
                "surface triangle {t} names vertex {v}, the surface has {count}"
            )));
        }
        out[c] = &surface.vertices[6 * v..6 * v + 6];
    }
    Ok(out)
}

/// The vertices of `bricks` seen from `view` (see the module documentation),
/// with the translucent `surface`'s triangles of their batches and the
/// `points` of their buckets when given.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when a batch names a triangle the surface does
/// not have, or a triangle a vertex it does not have, or for more than
/// [`MAX_BRICKS`] bricks.
pub fn brick_geometry(
    view: &GeometryView,
    bricks: &[BrickSlabs<'_>],
    surface: Option<&SurfaceVertices<'_>>,
    points: Option<&PointVertices<'_>>,
) -> Result<BrickGeometry> {
    let basis = view_basis(view.forward, view.view_up);
    let eye = Eye32 { e: view.eye.map(|v| v as f32), f: view.forward.map(|v| v as f32) };
    let point_count = points.map_or(0, |p| (p.positions.len() / 3).min(p.shades.len() / 4));
    let mut out = BrickGeometry {
        point_up: basis.1.map(|v| v as f32),
        brick_first: Vec::with_capacity(bricks.len() + 1),
        ray_marched: Vec::with_capacity(bricks.len()),
        ..BrickGeometry::default()
    };
    out.brick_first.push(0);
    if bricks.len() > MAX_BRICKS {
        return Err(Error::InvalidArgument(format!(
            "{} bricks to draw, at most {MAX_BRICKS} a frame: give a smaller texture budget",
            bricks.len()
        )));
    }
    let mut stream = Stream { data: Vec::new(), brick: 0.0 };
    let (mut placed, mut items, mut ranges) = (Vec::<Placed>::new(), Vec::<SlabItem>::new(), Vec::new());
    for (index, brick) in bricks.iter().enumerate() {
        stream.brick = index as f32;
        let slices = brick.slices;
        placed.clear();
        if let Some(surface) = surface {
            place_triangles(brick, surface, &eye, &mut ranges, &mut placed)?;
            out.triangles_placed += placed.len();
        }
        let mut buckets = if points.is_some() { &brick.buckets[..] } else { &[][..] };
        if placed.is_empty() && buckets.is_empty() {
            // No triangles or points between its slices: ray-marched, drawn as its box.
            if brick.drawn && !slices.is_empty() {
                stream.emit_box(&brick.bounds);
            }
            out.brick_first.push(stream.data.len() / FLOATS_PER_VERTEX);
            out.ray_marched.push(true);
            continue;
        }
        let mut next = 0;
        for s in 0..=slices.len() {
            items.clear();
            next = collect_triangles(s, &placed, next, surface, &eye, &mut items)?;
            if let Some(points) = points {
                buckets = collect_points(s, buckets, points, point_count, view, &mut items);
            }
            sort_far_first(&mut items);
            out.points_placed += emit_items(&items, &placed, surface, points, &mut stream)?;
            if let (Some(&depth), true) = (slices.get(s), brick.drawn) {
                emit_slice(&mut stream, brick, view, basis, depth);
            }
        }
        out.brick_first.push(stream.data.len() / FLOATS_PER_VERTEX);
        out.ray_marched.push(false);
    }
    out.vertices = stream.data;
    Ok(out)
}

/// The eye and view direction in `f32`, as the mapper held them.
struct Eye32 {
    e: [f32; 3],
    f: [f32; 3],
}

impl Eye32 {
    /// A triangle vertex's depth `(p - eye) . forward`: f32 differences, f64
    /// products and sums.
    fn depth(&self, p: &[f32]) -> f64 {
        let (e, f) = (self.e, self.f);
        ((p[0] - e[0]) as f64 * f[0] as f64 + (p[1] - e[1]) as f64 * f[1] as f64) + (p[2] - e[2]) as f64 * f[2] as f64
    }

    /// A triangle's centroid depth, `sum over corners and axes of (p - eye) f / 3`.
    fn centroid_depth(&self, corners: [&[f32]; 3]) -> f64 {
        let mut z = 0.0;
        for p in corners {
            for ((&v, &e), &f) in p[..3].iter().zip(&self.e).zip(&self.f) {
                z += (v - e) as f64 * f as f64 / 3.0;
            }
        }
        z
    }
}

/// The triangle copies of `brick` into `placed`, by slab: each triangle of
/// the union of its batches' ranges (once) where [`slab_copies`] puts it
/// from its vertices' depth range, with its clip interval.
fn place_triangles(
    brick: &BrickSlabs<'_>,
    surface: &SurfaceVertices<'_>,
    eye: &Eye32,
    ranges: &mut Vec<(u32, u32)>,
    placed: &mut Vec<Placed>,
) -> Result<()> {
    ranges.clear();
    ranges.extend(brick.batches.iter().map(|r| (r.start, r.end)));
    // The union of the batches' ranges.
    ranges.sort_unstable();
    let mut covered = 0u32;
    for &(first, end) in ranges.iter() {
        for t in first.max(covered)..end {
            let corners = triangle(surface, t)?;
            let (mut z_min, mut z_max) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in corners {
                let z = eye.depth(p);
                z_min = z_min.min(z);
                z_max = z_max.max(z);
            }
            for (slab, clip) in slab_copies(brick.slices, z_min, z_max) {
                let (near, far) = clip.map_or((-UNBOUNDED, UNBOUNDED), |(a, b)| (clip_bound(a), clip_bound(b)));
                placed.push(Placed { slab, triangle: t, near, far });
            }
        }
        covered = covered.max(end);
    }
    placed.sort_by_key(|p| p.slab);
    Ok(())
}

/// Slab `s`'s triangle copies (those of `placed` from `next` on, which is
/// sorted by slab) into `items` at their centroid's depth clamped to their
/// clip interval; the index after the last one taken.
fn collect_triangles(
    s: usize,
    placed: &[Placed],
    mut next: usize,
    surface: Option<&SurfaceVertices<'_>>,
    eye: &Eye32,
    items: &mut Vec<SlabItem>,
) -> Result<usize> {
    for (k, copy) in placed.iter().enumerate().skip(next).take_while(|(_, c)| c.slab == s) {
        let corners = triangle(surface.expect("placed triangles have a surface"), copy.triangle)?;
        let z = cxx_min(cxx_max(eye.centroid_depth(corners), copy.near as f64), copy.far as f64);
        items.push(SlabItem { depth: z, id: k as u32, point: false });
        next = k + 1;
    }
    Ok(next)
}

/// The points of the buckets of slab `s` and before (the head of
/// `buckets`, sorted by slab) that add something (`a_p > 0`) into `items`
/// at their depth; the buckets left.
fn collect_points<'b>(
    s: usize,
    mut buckets: &'b [(usize, &'b [u32])],
    points: &PointVertices<'_>,
    point_count: usize,
    view: &GeometryView,
    items: &mut Vec<SlabItem>,
) -> &'b [(usize, &'b [u32])] {
    while let Some(((slab, ids), rest)) = buckets.split_first() {
        if *slab > s {
            break;
        }
        buckets = rest;
        for &id in *ids {
            let i = id as usize;
            // Not in the set, or adds nothing (a_p not above 0, NaN included).
            if i >= point_count || points.shades[4 * i + 3].partial_cmp(&0.0) != Some(Ordering::Greater) {
                continue;
            }
            let mut z = 0.0;
            for (a, &v) in points.positions[3 * i..3 * i + 3].iter().enumerate() {
                z += (v as f64 - view.eye[a]) * view.forward[a];
            }
            items.push(SlabItem { depth: z, id, point: true });
        }
    }
    buckets
}

/// Far first, stably (std::stable_sort with a.depth > b.depth).
fn sort_far_first(items: &mut [SlabItem]) {
    items.sort_by(|a, b| {
        if a.depth > b.depth {
            Ordering::Less
        } else if b.depth > a.depth {
            Ordering::Greater
        } else {
            Ordering::Equal
        }
    });
}

/// A slab's items as vertices: a point's quad, a triangle copy's three
/// vertices with its clip interval; the points emitted.
fn emit_items(
    items: &[SlabItem],
    placed: &[Placed],
    surface: Option<&SurfaceVertices<'_>>,
    points: Option<&PointVertices<'_>>,
    stream: &mut Stream,
) -> Result<usize> {
    let mut emitted = 0;
    for item in items {
        if item.point {
            stream.emit_point(points.expect("point items have points"), item.id);
            emitted += 1;
            continue;
        }
        let copy = &placed[item.id as usize];
        for p in triangle(surface.expect("placed triangles have a surface"), copy.triangle)? {
            stream.emit(&p[..3], &p[3..], copy.near, copy.far, PrimitiveKind::SurfaceTriangle, 0.0);
        }
    }
    Ok(emitted)
}

/// The slice at view depth `depth`: its plane's polygon in the brick's drawn box.
fn emit_slice(
    stream: &mut Stream,
    brick: &BrickSlabs<'_>,
    view: &GeometryView,
    basis: ([f64; 3], [f64; 3]),
    depth: f64,
) {
    let first = stream.data.len();
    let mut polygon = Vec::new();
    append_slice_polygon(&brick.bounds, view.eye, view.forward, basis, depth, &mut polygon);
    stream.data.reserve(polygon.len() / 3 * FLOATS_PER_VERTEX);
    for v in polygon.chunks_exact(3) {
        stream.emit(v, &[0.0; 3], -UNBOUNDED, UNBOUNDED, PrimitiveKind::Slice, 0.0);
    }
    debug_assert_eq!((stream.data.len() - first) % (3 * FLOATS_PER_VERTEX), 0);
}

/// The bricks of a Rust [`DrawList`] for [`brick_geometry`]: every brick
/// drawn in its whole world box, its batches and point buckets.
pub fn list_bricks(list: &DrawList) -> Vec<BrickSlabs<'_>> {
    list.bricks
        .iter()
        .map(|b| BrickSlabs {
            slices: &b.slices,
            bounds: [b.world_lo[0], b.world_hi[0], b.world_lo[1], b.world_hi[1], b.world_lo[2], b.world_hi[2]],
            drawn: true,
            batches: b.batches.iter().map(|batch| batch.triangles.clone()).collect(),
            buckets: b.points.iter().map(|bucket| (bucket.slab, &bucket.points[..])).collect(),
        })
        .collect()
}

#[cfg(test)]
#[path = "brick_geometry_tests.rs"]
mod tests;
