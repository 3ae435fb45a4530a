//! The z-buffer and the scan conversion of octant faces (paper 2, procedure
//! "Scan-Convert a Face").
//!
//! An octant face is a parallelogram in the image. Its corners are lattice
//! points of the octree space, projected to fixed point (1/65536 pixel) by an
//! exact integer affine map, `corner(i, j, k) = o + i ex + j ey + k ez` with
//! `o, ex, ey, ez` rounded once ([`Projector::corner`]): a corner shared by
//! several faces has one position, and the corners along an octant's edge
//! stay exactly on that edge's line (a large face and the small faces beside
//! it meet without a crack), at most 256 x 1/131072 pixel from the exact
//! projection. A face covers pixel `(x, y)` when its centre `(x + 1/2, y + 1/2)`
//! lies in the half-open span of the face's scanline, `x_left <= x + 1/2 <
//! x_right`, with scanlines half-open at the bottom as well: faces sharing an
//! edge never both cover a pixel and never leave a gap. Each edge is stepped
//! from scanline to scanline with exact integer arithmetic (the edge
//! coherence of the paper; `t += 65536 (xb - xa)` per scanline), so the same
//! face always covers the same pixels, whatever else was drawn.
//!
//! Depth along a face is affine in the image (scanline coherence): with the
//! face in the plane `p_a = k` (`a` its axis), depth `z = -t` where
//! `p = c + sx right + sy up + t w`, i.e.
//!
//! ```text
//! z(sx, sy) = (sx right_a + sy up_a - (k - c_a)) / w_a
//! ```
//!
//! evaluated at the first pixel of a span and stepped by `dz/dx` along it.

use super::view::View;
use serde::Serialize;

/// Subpixel steps per pixel of the fixed-point corners.
const SUBPIXEL: i64 = 1 << 16;

/// Work counters (the paper's tables II and III).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Counters {
    /// White octants visited.
    pub white_visited: usize,
    /// Black octants visited.
    pub black_visited: usize,
    /// Gray octants visited.
    pub gray_visited: usize,
    /// Octant faces scan-converted.
    pub faces: usize,
    /// Scanlines crossed by the faces, accumulated.
    pub scanlines: usize,
    /// Pixels checked or painted by the faces, accumulated.
    pub pixels: usize,
}

/// Depth per pixel (infinite: not painted) and the axis of the face painted there.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthImage {
    /// Pixels per row and rows.
    pub size: usize,
    /// Distance from the view plane, smaller is nearer; `f64::INFINITY` where nothing was painted.
    pub depth: Vec<f64>,
    /// 0 where nothing was painted, else 1 + the axis of the face painted.
    pub face: Vec<u8>,
}

impl DepthImage {
    /// A `size x size` image with nothing painted.
    pub fn new(size: usize) -> DepthImage {
        DepthImage { size, depth: vec![f64::INFINITY; size * size], face: vec![0; size * size] }
    }

    /// The nearest painted depth and the depth extent of the painted pixels
    /// (1 when they are all at one depth or none is painted), for pictures
    /// that map depth to brightness.
    pub fn depth_span(&self) -> (f64, f64) {
        let painted = self.depth.iter().copied().filter(|z| z.is_finite());
        let (lo, hi) = painted.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| (lo.min(z), hi.max(z)));
        (lo, if hi > lo { hi - lo } else { 1.0 })
    }

    /// Every pixel back to not painted (infinite depth, no face), keeping the buffers.
    pub fn clear(&mut self) {
        self.depth.fill(f64::INFINITY);
        self.face.fill(0);
    }

    /// Painted pixels.
    pub fn painted(&self) -> usize {
        self.face.iter().filter(|&&f| f != 0).count()
    }

    /// Whether two depth images are identical, bit for bit.
    pub fn identical(&self, other: &DepthImage) -> bool {
        self.size == other.size
            && self.face == other.face
            && self.depth.iter().zip(&other.depth).all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

/// How a face is written into the z-buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Paint {
    /// Back to front: every covered pixel is overwritten.
    Overwrite,
    /// Front to back: only pixels not painted yet are written.
    Unpainted,
}

/// Projects the octree space onto a `size x size` image and scan-converts faces.
pub struct Projector {
    size: usize,
    /// Fixed-point image position of lattice point `(i, j, k)`: `origin + i ex + j ey + k ez`.
    origin: [i64; 2],
    axis_step: [[i64; 2]; 3],
    /// Per face axis: depth at pixel `(0, 0)`'s corner for `k = 0`, and its image gradients.
    depth_gradient: [[f64; 2]; 3],
    /// Per face axis: depth per unit of the face's plane coordinate `k`, and at `k = 0`.
    depth_k: [[f64; 2]; 3],
    /// The z-buffer.
    pub image: DepthImage,
    /// Work counters.
    pub counters: Counters,
}

impl Projector {
    /// A projector for an octree space of `side` voxels per axis on a `size`
    /// pixel square image, the whole space in view.
    pub fn new(view: &View, side: usize, size: usize) -> Projector {
        Projector::reusing(view, side, DepthImage::new(size))
    }

    /// A projector that paints into `image`, cleared first (a display run
    /// after run reuses its z-buffer instead of allocating a fresh one).
    pub fn reusing(view: &View, side: usize, mut image: DepthImage) -> Projector {
        image.clear();
        let size = image.size;
        let half = side as f64 / 2.0;
        // The space's bounding sphere fills 98 % of the image.
        let scale = 0.98 * size as f64 / (side as f64 * 3f64.sqrt());
        let centre = size as f64 / 2.0;
        let project = |v: [f64; 3]| -> [f64; 2] {
            let sx = v[0] * view.right[0] + v[1] * view.right[1] + v[2] * view.right[2];
            let sy = v[0] * view.up[0] + v[1] * view.up[1] + v[2] * view.up[2];
            [sx * scale, -sy * scale]
        };
        let fixed = |v: f64| (v * SUBPIXEL as f64).round() as i64;
        let o = project([-half, -half, -half]);
        let origin = [fixed(centre + o[0]), fixed(centre + o[1])];
        let axis_step =
            [project([1.0, 0.0, 0.0]), project([0.0, 1.0, 0.0]), project([0.0, 0.0, 1.0])].map(|step| step.map(fixed));
        let mut depth_gradient = [[0.0; 2]; 3];
        let mut depth_k = [[0.0; 2]; 3];
        for a in 0..3 {
            if view.w[a] == 0.0 {
                continue; // faces of this axis are edge-on: never drawn
            }
            // z = (sx right_a + sy up_a - (k - half)) / w_a, sx = (x - centre) / scale, sy = (centre - y) / scale.
            let dzdx = view.right[a] / (view.w[a] * scale);
            let dzdy = -view.up[a] / (view.w[a] * scale);
            depth_gradient[a] = [dzdx, dzdy];
            // Depth at image point (x, y) on plane k: -k / w_a + half / w_a - centre (dzdx + dzdy) + dzdx x + dzdy y.
            depth_k[a] = [-1.0 / view.w[a], half / view.w[a] - centre * (dzdx + dzdy)];
        }
        Projector { size, origin, axis_step, depth_gradient, depth_k, image, counters: Counters::default() }
    }

    /// Fixed-point image position of lattice point `p`.
    pub fn corner(&self, p: [usize; 3]) -> [i64; 2] {
        std::array::from_fn(|c| {
            self.origin[c]
                + p[0] as i64 * self.axis_step[0][c]
                + p[1] as i64 * self.axis_step[1][c]
                + p[2] as i64 * self.axis_step[2][c]
        })
    }

    /// Scan-converts the face of axis `axis` of the octant at `origin` of
    /// `size` voxels, on its high side if `high`.
    pub fn face(&mut self, origin: [usize; 3], size: usize, axis: usize, high: bool, paint: Paint) {
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut p = origin;
        if high {
            p[axis] += size;
        }
        let k = p[axis] as f64;
        let mut corners = [[0i64; 2]; 4];
        for (n, (db, dc)) in [(0, 0), (size, 0), (size, size), (0, size)].into_iter().enumerate() {
            let mut q = p;
            q[b] += db;
            q[c] += dc;
            corners[n] = self.corner(q);
        }
        self.counters.faces += 1;
        let [dzdx, dzdy] = self.depth_gradient[axis];
        let z_plane = self.depth_k[axis][0] * k + self.depth_k[axis][1];
        self.fill(&corners, z_plane, dzdx, dzdy, axis as u8 + 1, paint);
    }

    /// Fills the convex polygon `corners` (fixed point), depth
    /// `z_plane + dzdx x + dzdy y` at image point `(x, y)`.
    fn fill(&mut self, corners: &[[i64; 2]; 4], z_plane: f64, dzdx: f64, dzdy: f64, face: u8, paint: Paint) {
        let ymin = corners.iter().map(|c| c[1]).min().expect("four corners");
        let ymax = corners.iter().map(|c| c[1]).max().expect("four corners");
        let size = self.size as i64;
        // Scanline py has its centre at (py + 1/2) SUBPIXEL; rows [first, last).
        let first = ceil_div(ymin - SUBPIXEL / 2, SUBPIXEL).max(0);
        let last = ceil_div(ymax - SUBPIXEL / 2, SUBPIXEL).min(size);
        if first >= last {
            return;
        }
        // The non-horizontal edges, top end first, each with its stepped numerator.
        let mut edge_store = [EdgeStep::EMPTY; 4];
        let mut count = 0;
        for n in 0..4 {
            let (mut a, mut b) = (corners[n], corners[(n + 1) % 4]);
            if a[1] == b[1] {
                continue;
            }
            if a[1] > b[1] {
                std::mem::swap(&mut a, &mut b);
            }
            edge_store[count] = EdgeStep::new(a, b, first);
            count += 1;
        }
        let edges = &mut edge_store[..count];
        for py in first..last {
            let yc = py * SUBPIXEL + SUBPIXEL / 2;
            let mut span = [i64::MAX, i64::MIN];
            for e in edges.iter() {
                if e.top <= yc && yc < e.bottom {
                    let x = e.first_pixel();
                    span = [span[0].min(x), span[1].max(x)];
                }
            }
            for e in edges.iter_mut() {
                e.step();
            }
            if span[0] > span[1] {
                continue;
            }
            self.counters.scanlines += 1;
            let (x0, x1) = (span[0].max(0), span[1].min(size));
            if x0 >= x1 {
                continue;
            }
            self.counters.pixels += (x1 - x0) as usize;
            let row = py as usize * self.size;
            let mut z = z_plane + dzdx * (x0 as f64 + 0.5) + dzdy * (py as f64 + 0.5);
            for x in x0..x1 {
                let i = row + x as usize;
                if paint == Paint::Overwrite || self.image.face[i] == 0 {
                    self.image.depth[i] = z;
                    self.image.face[i] = face;
                }
                z += dzdx;
            }
        }
    }
}

/// An edge from `a` (top) to `b`, stepped one scanline at a time:
/// the first pixel whose centre is at or right of the edge at scanline
/// centre `yc` is `ceil(t / (den SUBPIXEL))` with
/// `t = (xa - SUBPIXEL / 2) den + (yc - ya)(xb - xa)`, `den = yb - ya`.
#[derive(Clone, Copy)]
struct EdgeStep {
    top: i64,
    bottom: i64,
    t: i128,
    dt: i128,
    div: i128,
}

impl EdgeStep {
    const EMPTY: EdgeStep = EdgeStep { top: 0, bottom: 0, t: 0, dt: 0, div: 1 };

    fn new(a: [i64; 2], b: [i64; 2], first_row: i64) -> EdgeStep {
        let den = (b[1] - a[1]) as i128;
        let yc = (first_row * SUBPIXEL + SUBPIXEL / 2) as i128;
        let dx = (b[0] - a[0]) as i128;
        let t = (a[0] - SUBPIXEL / 2) as i128 * den + (yc - a[1] as i128) * dx;
        EdgeStep { top: a[1], bottom: b[1], t, dt: SUBPIXEL as i128 * dx, div: den * SUBPIXEL as i128 }
    }

    fn first_pixel(&self) -> i64 {
        ceil_div_wide(self.t, self.div) as i64
    }

    fn step(&mut self) {
        self.t += self.dt;
    }
}

fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

fn ceil_div_wide(a: i128, b: i128) -> i128 {
    -((-a).div_euclid(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ceilings() {
        assert_eq!(ceil_div(5, 2), 3);
        assert_eq!(ceil_div(-5, 2), -2);
        assert_eq!(ceil_div(4, 2), 2);
        assert_eq!(ceil_div_wide(-4, 2), -2);
    }

    #[test]
    fn adjacent_faces_cover_each_pixel_once() {
        // Axis view: the +Z faces of the four octants of a 2x2 layer tile the
        // image of the whole +Z face, every pixel exactly once.
        let view = View::new([0.0, 0.0, 1.0]).unwrap();
        let mut whole = Projector::new(&view, 8, 64);
        whole.face([0, 0, 0], 8, 2, true, Paint::Overwrite);
        let mut parts = Projector::new(&view, 8, 64);
        let mut count = vec![0u32; 64 * 64];
        for (x, y) in [(0, 0), (4, 0), (0, 4), (4, 4)] {
            let mut one = Projector::new(&view, 8, 64);
            one.face([x, y, 0], 4, 2, true, Paint::Overwrite);
            for (c, f) in count.iter_mut().zip(&one.image.face) {
                *c += u32::from(*f != 0);
            }
            parts.face([x, y, 0], 4, 2, true, Paint::Overwrite);
        }
        assert!(count.iter().all(|&c| c <= 1), "a pixel painted twice");
        assert_eq!(whole.image.face, parts.image.face);
        assert!(whole.image.painted() > 0);
    }
}
