//! Rays against surface triangles in world space, through a uniform grid of
//! bins, and headlight shading of the hits.
//!
//! Möller–Trumbore, for a triangle `(v0, v1, v2)` and the ray `o + t d`:
//!
//! ```text
//! e1 = v1 - v0,  e2 = v2 - v0,  p = d x e2,  det = e1 . p
//! s = o - v0,  u = (s . p) / det,  q = s x e1,  v = (d . q) / det,  t = (e2 . q) / det
//! hit when u >= -eps, v >= -eps, u + v <= 1 + eps, t >= 0     (eps = 1e-9: no cracks on shared edges)
//! ```
//!
//! Bins: the triangles' bounding box cut into about two cells per triangle
//! (at most 2^22); each triangle is listed in every cell its bounding box
//! touches; a ray walks the cells it crosses in order (Amanatides & Woo), so
//! the first hit is final once it lies before the current cell's exit.
//! Shading (headlight Lambert): `rgb = colour |n . d|`, `n` the vertex normals
//! interpolated with `(1 - u - v, u, v)` and normalised.

use super::geometry::ray_box;
use crate::data::grid::GridShape;
use crate::geometry::camera::Ray;
use crate::geometry::vec3::{cross, dot, sub};
use crate::surface::Surface;

const EPS: f64 = 1e-9;
const MAX_CELLS: f64 = (1u64 << 22) as f64;

/// A ray-triangle hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// Ray parameter (world distance: ray directions are unit).
    pub t: f64,
    /// Surface polygon id.
    pub polygon: u32,
    /// The triangle hit (a fan triangle of the polygon), index in the grid.
    triangle: u32,
    /// Barycentric weights of corners 1 and 2.
    u: f64,
    v: f64,
}

/// Triangles binned in a uniform grid.
#[derive(Debug, Clone)]
pub(crate) struct TriangleGrid {
    world: Vec<[[f64; 3]; 3]>,
    corners: Vec<[u32; 3]>,
    polygon: Vec<u32>,
    lo: [f64; 3],
    hi: [f64; 3],
    cell: [f64; 3],
    res: [usize; 3],
    /// `items[start[c]..start[c + 1]]`: the triangles of cell `c` (x fastest).
    start: Vec<u32>,
    items: Vec<u32>,
}

/// Möller–Trumbore (module documentation): `(t, u, v)`.
#[inline]
fn intersect(ray: &Ray, tri: &[[f64; 3]; 3]) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (sub(tri[1], tri[0]), sub(tri[2], tri[0]));
    let p = cross(ray.direction, e2);
    let det = dot(e1, p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let s = sub(ray.origin, tri[0]);
    let u = dot(s, p) / det;
    if !(-EPS..=1.0 + EPS).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(ray.direction, q) / det;
    if v < -EPS || u + v > 1.0 + EPS {
        return None;
    }
    let t = dot(e2, q) / det;
    (t >= 0.0).then_some((t, u, v))
}

impl TriangleGrid {
    /// The polygons `polygons` of `surface` (index space, mapped to world by
    /// `shape`), fanned into triangles and binned; `None` when there are none.
    pub(crate) fn new(
        surface: &Surface,
        shape: &GridShape,
        polygons: impl Iterator<Item = u32>,
    ) -> Option<TriangleGrid> {
        let (mut world, mut corners, mut polygon) = (Vec::new(), Vec::new(), Vec::new());
        for id in polygons {
            let poly = surface.polygon(id as usize);
            for k in 1..poly.len().saturating_sub(1) {
                let c = [poly[0], poly[k], poly[k + 1]];
                world.push(c.map(|i| shape.world(surface.points[i as usize])));
                corners.push(c);
                polygon.push(id);
            }
        }
        if world.is_empty() {
            return None;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for v in world.iter().flatten() {
            for a in 0..3 {
                (lo[a], hi[a]) = (lo[a].min(v[a]), hi[a].max(v[a]));
            }
        }
        let largest = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max).max(1e-12);
        for a in 0..3 {
            let pad = 1e-6 * largest.max(lo[a].abs()).max(hi[a].abs());
            (lo[a], hi[a]) = (lo[a] - pad, hi[a] + pad);
        }
        let extent = [0, 1, 2].map(|a| (hi[a] - lo[a]).max(1e-3 * largest));
        let target = (2.0 * world.len() as f64).min(MAX_CELLS);
        let k = (target / (extent[0] * extent[1] * extent[2])).cbrt();
        let res = extent.map(|e| ((e * k).ceil() as usize).clamp(1, 1024));
        let cell = [0, 1, 2].map(|a| (hi[a] - lo[a]) / res[a] as f64);
        let mut grid =
            TriangleGrid { world, corners, polygon, lo, hi, cell, res, start: Vec::new(), items: Vec::new() };
        grid.bin();
        Some(grid)
    }

    /// Cell range `[c0, c1]` per axis of a triangle's bounding box.
    fn cell_range(&self, tri: &[[f64; 3]; 3]) -> [(usize, usize); 3] {
        [0, 1, 2].map(|a| {
            let (mn, mx) =
                tri.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(mn, mx), v| (mn.min(v[a]), mx.max(v[a])));
            (self.cell_of(a, mn), self.cell_of(a, mx))
        })
    }

    #[inline]
    fn cell_of(&self, a: usize, x: f64) -> usize {
        (((x - self.lo[a]) / self.cell[a]).floor().max(0.0) as usize).min(self.res[a] - 1)
    }

    /// Counting sort of the triangles into their cells.
    fn bin(&mut self) {
        let [rx, ry, rz] = self.res;
        let mut count = vec![0u32; rx * ry * rz + 1];
        let ranges: Vec<[(usize, usize); 3]> = self.world.iter().map(|t| self.cell_range(t)).collect();
        let each = |r: &[(usize, usize); 3], f: &mut dyn FnMut(usize)| {
            for z in r[2].0..=r[2].1 {
                for y in r[1].0..=r[1].1 {
                    for x in r[0].0..=r[0].1 {
                        f(x + rx * (y + ry * z));
                    }
                }
            }
        };
        for r in &ranges {
            each(r, &mut |c| count[c + 1] += 1);
        }
        for c in 1..count.len() {
            count[c] += count[c - 1];
        }
        let mut next = count.clone();
        let mut items = vec![0u32; count[count.len() - 1] as usize];
        for (i, r) in ranges.iter().enumerate() {
            each(r, &mut |c| {
                items[next[c] as usize] = i as u32;
                next[c] += 1;
            });
        }
        (self.start, self.items) = (count, items);
    }

    /// Walks the cells `ray` crosses for `t` in `[0, t_max]`, front to back,
    /// calling `visit(triangles, t_exit)` until it returns true.
    fn walk(&self, ray: &Ray, t_max: f64, mut visit: impl FnMut(&[u32], f64) -> bool) {
        let Some((t0, t1)) = ray_box(ray, self.lo, self.hi) else { return };
        let t1 = t1.min(t_max);
        if t0 > t1 {
            return;
        }
        let mut c = [0usize; 3];
        let mut step = [0isize; 3];
        let mut next = [f64::INFINITY; 3];
        let mut delta = [f64::INFINITY; 3];
        for a in 0..3 {
            let d = ray.direction[a];
            c[a] = self.cell_of(a, ray.origin[a] + t0 * d);
            if d != 0.0 {
                step[a] = if d > 0.0 { 1 } else { -1 };
                let face = self.lo[a] + (c[a] + (d > 0.0) as usize) as f64 * self.cell[a];
                next[a] = (face - ray.origin[a]) / d;
                delta[a] = self.cell[a] / d.abs();
            }
        }
        loop {
            let a = if next[0] <= next[1] && next[0] <= next[2] {
                0
            } else if next[1] <= next[2] {
                1
            } else {
                2
            };
            let cell = c[0] + self.res[0] * (c[1] + self.res[1] * c[2]);
            let items = &self.items[self.start[cell] as usize..self.start[cell + 1] as usize];
            if visit(items, next[a].min(t1)) || next[a] > t1 {
                return;
            }
            let moved = c[a] as isize + step[a];
            if moved < 0 || moved >= self.res[a] as isize {
                return;
            }
            c[a] = moved as usize;
            next[a] += delta[a];
        }
    }

    fn hit(&self, ray: &Ray, i: u32) -> Option<Hit> {
        let i = i as usize;
        let (t, u, v) = intersect(ray, &self.world[i])?;
        Some(Hit { t, polygon: self.polygon[i], triangle: i as u32, u, v })
    }

    /// The nearest hit with `t <= t_max` (ties: the smaller polygon id).
    pub(crate) fn first_hit(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        self.walk(ray, t_max, |items, t_exit| {
            for &i in items {
                if let Some(h) = self.hit(ray, i).filter(|h| h.t <= t_max) {
                    if best.is_none_or(|b| (h.t, h.polygon) < (b.t, b.polygon)) {
                        best = Some(h);
                    }
                }
            }
            best.is_some_and(|b| b.t <= t_exit)
        });
        best
    }

    /// Headlight Lambert shading of `hit` (module documentation): straight
    /// RGB `colour |n . d|` (the colour's alpha is the caller's); the face
    /// normal where the vertex normals cancel out.
    pub(crate) fn shade(&self, surface: &Surface, hit: &Hit, direction: [f64; 3], colour: [f32; 4]) -> [f64; 3] {
        let i = hit.triangle as usize;
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let mut n = [0.0f64; 3];
        for (k, &c) in self.corners[i].iter().enumerate() {
            let normal = surface.normals.get(c as usize).copied().unwrap_or([0.0; 3]);
            for a in 0..3 {
                n[a] += w[k] * normal[a] as f64;
            }
        }
        // A vanishing or NaN normal (none is made, but a surface may come from outside) takes the face's.
        let len2 = dot(n, n);
        if len2 < 1e-24 || len2.is_nan() {
            let t = &self.world[i];
            n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        }
        let len = dot(n, n).sqrt();
        let lambert = if len > 0.0 { (dot(n, direction) / len).abs() } else { 1.0 };
        [0, 1, 2].map(|a| colour[a] as f64 * lambert)
    }

    /// Every hit with `t <= t_max`, by increasing `t`, into `out` (cleared
    /// first): each triangle once, and of hits at the same `t` (a shared
    /// edge or vertex) only the first.
    pub(crate) fn all_hits(&self, ray: &Ray, t_max: f64, out: &mut Vec<Hit>) {
        out.clear();
        self.walk(ray, t_max, |items, _| {
            out.extend(items.iter().filter_map(|&i| self.hit(ray, i)).filter(|h| h.t <= t_max));
            false
        });
        out.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.polygon.cmp(&b.polygon)));
        let mut last: Option<f64> = None;
        out.retain(|h| {
            let keep = last.is_none_or(|t| h.t - t > 1e-9 * (1.0 + h.t.abs()));
            if keep {
                last = Some(h.t);
            }
            keep
        });
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::surface::{SurfaceMode, SurfaceStats};

    /// A surface of the given index-space triangles (normals +z), for tests.
    pub(crate) fn surface_of(triangles: &[[[f64; 3]; 3]]) -> Surface {
        let points: Vec<[f64; 3]> = triangles.iter().flatten().copied().collect();
        let n = triangles.len() as u32;
        Surface {
            isovalue: 0.5,
            mode: SurfaceMode::Interpolated,
            keys: (0..points.len() as u64).collect(),
            normals: vec![[0.0, 0.0, 1.0]; points.len()],
            points,
            offsets: (0..=n).map(|i| 3 * i).collect(),
            connectivity: (0..3 * n).collect(),
            polygon_node: vec![crate::octree::NodeId(0); n as usize],
            polygon_face: (0..n).collect(),
            node_ranges: vec![(crate::octree::NodeId(0), 0, n)],
            stats: SurfaceStats::default(),
        }
    }

    /// Pseudo-random numbers in [0, 1) (a fixed LCG: tests stay deterministic).
    fn lcg(state: &mut u64) -> f64 {
        *state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn grid_walk_finds_what_brute_force_finds() {
        let mut s = 7u64;
        let mut tris = Vec::new();
        for _ in 0..400 {
            let c = [0, 1, 2].map(|_| 1.0 + 8.0 * lcg(&mut s));
            tris.push([0, 1, 2].map(|_| [0, 1, 2].map(|a| c[a] + 1.5 * (lcg(&mut s) - 0.5))));
        }
        let surface = surface_of(&tris);
        let shape = GridShape { dims: [11; 3], spacing: [1.0, 0.5, 2.0], origin: [1.0, -2.0, 0.5] };
        let grid = TriangleGrid::new(&surface, &shape, 0..tris.len() as u32).unwrap();
        let world: Vec<[[f64; 3]; 3]> = tris.iter().map(|t| t.map(|p| shape.world(p))).collect();
        let mut all = Vec::new();
        let mut found = 0;
        for _ in 0..2000 {
            let origin = [0, 1, 2].map(|_| -5.0 + 25.0 * lcg(&mut s));
            let target = shape.world([0, 1, 2].map(|_| 10.0 * lcg(&mut s)));
            let ray = Ray { origin, direction: crate::geometry::vec3::normalize(sub(target, origin)) };
            let mut brute: Vec<(f64, u32)> =
                world.iter().enumerate().filter_map(|(i, t)| intersect(&ray, t).map(|h| (h.0, i as u32))).collect();
            brute.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let first = grid.first_hit(&ray, f64::INFINITY);
            assert_eq!(first.map(|h| (h.t, h.polygon)), brute.first().copied());
            grid.all_hits(&ray, f64::INFINITY, &mut all);
            assert_eq!(all.len(), brute.len());
            found += brute.len();
            // A limit keeps only the hits before it.
            if let Some(&(t, _)) = brute.get(1) {
                grid.all_hits(&ray, t, &mut all);
                assert_eq!(all.len(), 2);
            }
        }
        assert!(found > 500, "only {found} hits: the test rays miss");
    }

    #[test]
    fn shared_edges_are_hit_once_and_shading_is_headlight_lambert() {
        // Two triangles of the square [0, 2]^2 at z = 1, diagonal from (0, 0) to (2, 2).
        let tris =
            [[[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [2.0, 2.0, 1.0]], [[0.0, 0.0, 1.0], [2.0, 2.0, 1.0], [0.0, 2.0, 1.0]]];
        let surface = surface_of(&tris);
        let shape = GridShape { dims: [3; 3], spacing: [1.0; 3], origin: [0.0; 3] };
        let grid = TriangleGrid::new(&surface, &shape, 0..2).unwrap();
        let d = crate::geometry::vec3::normalize([0.0, 0.6, -0.8]);
        let ray = Ray { origin: [1.0, 1.0 - 0.6 * 5.0 / 0.8, 6.0], direction: d }; // through (1, 1, 1), on the diagonal
        let mut all = Vec::new();
        grid.all_hits(&ray, f64::INFINITY, &mut all);
        assert_eq!(all.len(), 1);
        let h = grid.first_hit(&ray, f64::INFINITY).unwrap();
        assert!((h.t - 6.25).abs() < 1e-12);
        let rgb = grid.shade(&surface, &h, d, [1.0, 0.5, 0.0, 1.0]);
        assert!((rgb[0] - 0.8).abs() < 1e-12 && (rgb[1] - 0.4).abs() < 1e-12 && rgb[2] == 0.0);
        assert!(grid.first_hit(&ray, 6.0).is_none());
    }
}
