//! How a point is drawn on the picture (paper 3, section 4): where it lands
//! ([`project`]) and the pixels its footprint covers ([`footprint`]).
//!
//! The point covers one sample spacing `d0`, `s = d0 / pixel` pixels across
//! at its depth. A square is drawn `S = ceil(s)` pixels wide with its opacity scaled
//! by `s^2 / S^2` ("point sizes are always rounded up ... and their opacity is
//! adjusted downward proportional to the increase in area"); a Gaussian
//! splat with `sigma = s / 2` over a `ceil(3 sigma)` radius, its weights
//! scaled to sum to `s^2` pixels of full coverage.

use crate::base::error::{Error, Result};
use crate::geometry::camera::{Camera, Projection};
use crate::geometry::vec3::{dot, sub};

/// The footprint a point is drawn with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Footprint {
    /// A square of whole pixels (an OpenGL point).
    Square,
    /// A Gaussian splat.
    Gaussian,
}

impl std::str::FromStr for Footprint {
    type Err = Error;
    fn from_str(s: &str) -> Result<Footprint> {
        match s {
            "square" => Ok(Footprint::Square),
            "gaussian" => Ok(Footprint::Gaussian),
            _ => Err(Error::InvalidArgument(format!("unknown point footprint '{s}': use square or gaussian"))),
        }
    }
}

/// Where a point lands on a `width x height` picture: its centre in pixel
/// coordinates (pixel `(x, y)` covers `[x, x + 1) x [y, y + 1)`), and its
/// footprint size `s` in pixels; `None` behind a perspective camera.
pub fn project(camera: &Camera, width: usize, height: usize, p: [f64; 3], d0: f64) -> Option<([f64; 2], f64)> {
    let (right, up, forward) = camera.basis();
    let r = sub(p, camera.position);
    let h = height as f64;
    // Half the view height in world units at the point's depth.
    let half = match camera.projection {
        Projection::Parallel { scale } => scale,
        Projection::Perspective { view_angle_deg } => {
            let z = dot(r, forward);
            if z <= 0.0 {
                return None;
            }
            z * (view_angle_deg.to_radians() / 2.0).tan()
        }
    };
    let (u, v) = (dot(r, right) / half, dot(r, up) / half);
    let centre = [(u * h + width as f64) / 2.0, (h - v * h) / 2.0];
    Some((centre, d0 * h / (2.0 * half)))
}

/// The pixels a footprint of size `s` centred at `centre` covers, each with
/// its coverage weight (see the module documentation), clipped to the picture.
pub fn footprint(
    kind: Footprint,
    centre: [f64; 2],
    s: f64,
    width: usize,
    height: usize,
    mut pixel: impl FnMut(usize, usize, f64),
) {
    let mut emit = |x: i64, y: i64, w: f64| {
        if x >= 0 && y >= 0 && (x as usize) < width && (y as usize) < height && w > 0.0 {
            pixel(x as usize, y as usize, w);
        }
    };
    match kind {
        Footprint::Square => {
            let side = s.ceil().max(1.0);
            let w = (s * s / (side * side)).min(1.0);
            // The side x side pixels whose centres are nearest the point's centre.
            let x0 = (centre[0] - side / 2.0).round() as i64;
            let y0 = (centre[1] - side / 2.0).round() as i64;
            for y in y0..y0 + side as i64 {
                for x in x0..x0 + side as i64 {
                    emit(x, y, w);
                }
            }
        }
        Footprint::Gaussian => {
            let sigma = (s / 2.0).max(0.5);
            let radius = (3.0 * sigma).ceil() as i64;
            let (cx, cy) = (centre[0].floor() as i64, centre[1].floor() as i64);
            let weight = |x: i64, y: i64| {
                let (dx, dy) = (x as f64 + 0.5 - centre[0], y as f64 + 0.5 - centre[1]);
                (-(dx * dx + dy * dy) / (2.0 * sigma * sigma)).exp()
            };
            let mut sum = 0.0;
            for y in cy - radius..=cy + radius {
                for x in cx - radius..=cx + radius {
                    sum += weight(x, y);
                }
            }
            let scale = s * s / sum;
            for y in cy - radius..=cy + radius {
                for x in cx - radius..=cx + radius {
                    emit(x, y, (weight(x, y) * scale).min(1.0));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprints_cover_the_point_area_once_rounded_up() {
        for kind in [Footprint::Square, Footprint::Gaussian] {
            for s in [0.4, 1.0, 1.7, 3.2] {
                // Total coverage is the point's area s^2 (pixels), whatever the rounding.
                let mut total = 0.0;
                let mut max: f64 = 0.0;
                footprint(kind, [20.3, 17.8], s, 64, 64, |_, _, w| {
                    total += w;
                    max = max.max(w);
                });
                assert!(
                    (total - s * s).abs() < 1e-9 * s * s + if kind == Footprint::Gaussian { 1e-3 } else { 0.0 },
                    "{kind:?} s {s}: {total}"
                );
                assert!(max <= 1.0);
            }
        }
        // Clipped at the picture's edge: nothing outside.
        let mut n = 0;
        footprint(Footprint::Square, [0.0, 0.0], 4.0, 8, 8, |x, y, _| {
            assert!(x < 8 && y < 8);
            n += 1;
        });
        assert_eq!(n, 4);
    }

    #[test]
    fn projection_matches_the_camera_rays() {
        for parallel in [true, false] {
            let c = Camera::around([0.0; 3], [10.0; 3], 30.0, 20.0, parallel).unwrap();
            for (x, y) in [(3usize, 5usize), (40, 17), (63, 63)] {
                let ray = c.ray(x, y, 64, 48);
                let p = [0, 1, 2].map(|a| ray.origin[a] + 7.5 * ray.direction[a]);
                let (centre, s) = project(&c, 64, 48, p, 1.0).unwrap();
                assert!((centre[0] - (x as f64 + 0.5)).abs() < 1e-9 && (centre[1] - (y as f64 + 0.5)).abs() < 1e-9);
                assert!(s > 0.0);
            }
        }
    }
}
