//! How far the Discretized Marching Cubes surface lies from the interpolated
//! one: what the DiscMC's merged facets cost in accuracy, in voxel units.
//!
//! Both surfaces come from the same case table, so cell by cell they have the
//! same triangles (the same edge keys) at different positions. The samples of
//! one surface are its vertices (each once) and the centroid of each of its
//! triangles; each sample's distance to the other surface is the distance to
//! the nearest triangle of the other surface in the 3 x 3 x 3 cells around it
//! (the two surfaces never lie more than one cell apart: each point of either
//! lies in the cell its triangle came from). Reported: the mean and the max
//! over the samples of both directions (a sampled symmetric Hausdorff
//! distance; the max is a lower bound of the true one, reached at vertices).

use super::build::{march_nodes, surface_nodes};
use super::extract::midpoint2;
use super::place::interpolated_point;
use crate::base::error::Result;
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::geometry::vec3::{dot, sub};
use crate::octree::VolumeOctree;
use rayon::prelude::*;

/// Mean and max distance, in voxel (index) units.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Distance {
    /// Mean over all samples of both directions.
    pub mean: f64,
    /// Max over all samples of both directions.
    pub max: f64,
    /// Number of samples.
    pub samples: usize,
}

/// The distance between the DiscMC and the interpolated surface of `grid` at `isovalue`.
pub fn discretized_to_interpolated(grid: &Grid<'_>, octree: &VolumeOctree, isovalue: f64) -> Result<Distance> {
    struct Run<'a> {
        octree: &'a VolumeOctree,
        iso: f64,
    }
    impl GridVisitor for Run<'_> {
        type Output = Distance;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Distance {
            let nodes = surface_nodes(self.octree, self.iso);
            let marched = march_nodes(&g, self.octree, &nodes, self.iso);
            let mut cells: Vec<(u64, [u64; 3])> = marched
                .iter()
                .flat_map(|m| m.cells.iter().copied().zip((0..m.triangles.len()).map(|i| m.keys_of(i))))
                .collect();
            cells.par_sort_unstable();
            // Vertices numbered once; both surfaces' positions computed once.
            let mut keys: Vec<u64> = cells.iter().flat_map(|c| c.1).collect();
            keys.par_sort_unstable();
            keys.dedup();
            let tris: Vec<(u64, [u32; 3])> =
                cells.par_iter().map(|&(c, t)| (c, t.map(|k| keys.binary_search(&k).unwrap_or(0) as u32))).collect();
            let dims = g.dims;
            let disc: Vec<[f64; 3]> = keys.par_iter().map(|&k| midpoint2(k, dims).map(|v| v as f64 / 2.0)).collect();
            let interp: Vec<[f64; 3]> = keys.par_iter().map(|&k| interpolated_point(&g, k, self.iso)).collect();
            // Each vertex is sampled once, by the first cell (in cell order) that uses it.
            let mut owner = vec![u64::MAX; keys.len()];
            for &(c, t) in &tris {
                for v in t {
                    owner[v as usize] = owner[v as usize].min(c);
                }
            }
            let (s1, m1, n1) = one_way(&tris, &owner, dims, &disc, &interp);
            let (s2, m2, n2) = one_way(&tris, &owner, dims, &interp, &disc);
            let samples = n1 + n2;
            Distance { mean: if samples > 0 { (s1 + s2) / samples as f64 } else { 0.0 }, max: m1.max(m2), samples }
        }
    }
    Ok(grid.visit(Run { octree, iso: isovalue }))
}

/// Sum, max and count of the distances from samples of surface `from` to
/// surface `to` (positions per vertex). Parallel over cells: each cell
/// gathers the `to` triangles of its 27-cell neighbourhood once, then measures
/// its own `from` samples.
fn one_way(
    tris: &[(u64, [u32; 3])],
    owner: &[u64],
    dims: [usize; 3],
    from: &[[f64; 3]],
    to: &[[f64; 3]],
) -> (f64, f64, usize) {
    // Runs of equal cells: (cell, first, end).
    let mut runs: Vec<(u64, usize, usize)> = Vec::new();
    for (i, &(c, _)) in tris.iter().enumerate() {
        match runs.last_mut() {
            Some(r) if r.0 == c => r.2 = i + 1,
            _ => runs.push((c, i, i + 1)),
        }
    }
    // Per run (sum, max, count), collected in run order and summed in that
    // order: the same total on any thread count.
    let per_run: Vec<(f64, f64, usize)> = runs
        .par_iter()
        .map_init(
            || (Vec::new(), Vec::new()),
            |(candidates, sampled): &mut (Vec<[[f64; 3]; 3]>, Vec<u32>), &(cell, first, end)| {
                let c = cell as usize;
                let xyz = [c % dims[0], (c / dims[0]) % dims[1], c / (dims[0] * dims[1])];
                candidates.clear();
                sampled.clear();
                for_neighbours(&runs, dims, xyz, |r| {
                    candidates.extend(tris[r.1..r.2].iter().map(|e| e.1.map(|v| to[v as usize])))
                });
                let (mut sum, mut max, mut count) = (0.0, 0.0f64, 0usize);
                let mut measure = |q: [f64; 3]| {
                    let d = candidates.iter().map(|&t| point_triangle(q, t)).fold(f64::INFINITY, f64::min);
                    sum += d;
                    max = max.max(d);
                    count += 1;
                };
                for &(_, tri) in &tris[first..end] {
                    let p = tri.map(|v| from[v as usize]);
                    measure([0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0));
                    for (k, &v) in tri.iter().enumerate() {
                        if owner[v as usize] == cell && !sampled.contains(&v) {
                            sampled.push(v);
                            measure(p[k]);
                        }
                    }
                }
                (sum, max, count)
            },
        )
        .collect();
    per_run.iter().fold((0.0, 0.0, 0), |a, b| (a.0 + b.0, a.1.max(b.1), a.2 + b.2))
}

/// Calls `f` with the run of every non-empty cell in the 3 x 3 x 3 block around `xyz`.
fn for_neighbours(
    runs: &[(u64, usize, usize)],
    dims: [usize; 3],
    xyz: [usize; 3],
    mut f: impl FnMut(&(u64, usize, usize)),
) {
    for dz in -1i64..=1 {
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let n = [xyz[0] as i64 + dx, xyz[1] as i64 + dy, xyz[2] as i64 + dz];
                if (0..3).any(|a| n[a] < 0 || n[a] >= dims[a] as i64 - 1) {
                    continue;
                }
                let cell = (n[0] as usize + dims[0] * (n[1] as usize + dims[1] * n[2] as usize)) as u64;
                if let Ok(i) = runs.binary_search_by_key(&cell, |r| r.0) {
                    f(&runs[i]);
                }
            }
        }
    }
}

/// Distance from `p` to triangle `t` (closest point by Voronoi regions,
/// Ericson, Real-Time Collision Detection, 5.1.5).
pub fn point_triangle(p: [f64; 3], t: [[f64; 3]; 3]) -> f64 {
    let [a, b, c] = t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let closest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else {
            let vc = d1 * d4 - d3 * d2;
            if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
                let v = d1 / (d1 - d3);
                [a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]]
            } else {
                let cp = sub(p, c);
                let (d5, d6) = (dot(ab, cp), dot(ac, cp));
                if d6 >= 0.0 && d5 <= d6 {
                    c
                } else {
                    let vb = d5 * d2 - d1 * d6;
                    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
                        let w = d2 / (d2 - d6);
                        [a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]]
                    } else {
                        let va = d3 * d6 - d5 * d4;
                        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
                            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
                            [b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])]
                        } else {
                            let denom = 1.0 / (va + vb + vc);
                            let (v, w) = (vb * denom, vc * denom);
                            [a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w]
                        }
                    }
                }
            }
        }
    };
    let d = sub(p, closest);
    dot(d, d).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_triangle_regions() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(point_triangle([0.2, 0.2, 2.0], t), 2.0); // face
        assert_eq!(point_triangle([-1.0, 0.0, 0.0], t), 1.0); // vertex a
        assert_eq!(point_triangle([0.5, -3.0, 0.0], t), 3.0); // edge ab
        assert!((point_triangle([1.0, 1.0, 0.0], t) - 0.5f64.sqrt()).abs() < 1e-15);
        // edge bc
    }

    #[test]
    fn the_distance_is_the_same_on_any_thread_count() {
        use crate::datasets::{generate, Dataset};
        use crate::grid::ScalarType;
        use crate::octree::BuildOptions;
        let volume = generate(Dataset::SheppLogan, 48, ScalarType::F32);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| discretized_to_interpolated(&grid, &octree, 0.5).unwrap())
        };
        let one = on(1);
        assert!(one.samples > 0);
        for threads in [2, 3, 8] {
            let d = on(threads);
            assert_eq!(
                (d.mean.to_bits(), d.max.to_bits(), d.samples),
                (one.mean.to_bits(), one.max.to_bits(), one.samples)
            );
        }
    }
}
