//! The viewing direction (paper 2, section 2 and "Arbitrary Viewing
//! Direction"): the view plane normal (VPN) points from the object to the
//! viewer; the projection is parallel orthographic along it.
//!
//! - Front-to-back order: the octant nearest the viewer first (label bit `a`
//!   set when `vpn[a] > 0`), then the three whose labels differ from it in
//!   one bit, then the three differing in two, then the farthest.
//!   Back-to-front is the reverse.
//! - Potentially visible faces: for each axis `a` with `vpn[a] != 0`, the
//!   face at the high side of the octant if `vpn[a] > 0`, else the low side.
//!   The view case names these axes: XYZ, XY, XZ, YZ, X, Y or Z.
//! - Screen frame: `w = vpn / |vpn|` towards the viewer, `up` the projection
//!   of +Y on the view plane (of +Z when the VPN is along Y: the paper's two
//!   rotations about Y then X make Y, Z and the VPN coplanar), `right = up x w`.
//!   A point `p` of the octree space lands at screen `((p - c) . right,
//!   (p - c) . up)` and depth `-(p - c) . w` (smaller is nearer), `c` the
//!   centre of the octree space.

use crate::base::error::{Error, Result};
use serde::Serialize;

/// Which octant faces a direction can see.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ViewCase {
    /// An X, a Y and a Z face.
    XYZ,
    /// An X and a Y face (`vpn[2] = 0`).
    XY,
    /// An X and a Z face (`vpn[1] = 0`).
    XZ,
    /// A Y and a Z face (`vpn[0] = 0`).
    YZ,
    /// An X face only.
    X,
    /// A Y face only.
    Y,
    /// A Z face only.
    Z,
}

/// A view plane normal and everything derived from it.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// The view plane normal as given.
    pub vpn: [f64; 3],
    /// Unit vector towards the viewer.
    pub w: [f64; 3],
    /// Screen right.
    pub right: [f64; 3],
    /// Screen up.
    pub up: [f64; 3],
    /// Axes whose faces are potentially visible (`axis` of the paper), in X, Y, Z order.
    pub axes: Vec<usize>,
    /// Per axis: the potentially visible face is the high one (`vpn[a] > 0`).
    pub high_face: [bool; 3],
    /// Suboctant labels front to back.
    pub ftb_order: [usize; 8],
}

impl View {
    /// The view along `vpn`; (0, 0, 0) or a non-finite component is an error.
    pub fn new(vpn: [f64; 3]) -> Result<View> {
        if vpn.iter().any(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!("the view plane normal {vpn:?} is not finite")));
        }
        let len = (vpn[0] * vpn[0] + vpn[1] * vpn[1] + vpn[2] * vpn[2]).sqrt();
        if len == 0.0 {
            return Err(Error::InvalidArgument(
                "the view plane normal (0, 0, 0) has no direction: give the direction towards the viewer, \
                 e.g. --vpn 1,-1,1"
                    .into(),
            ));
        }
        let w = vpn.map(|v| v / len);
        // Up: +Y projected on the view plane, or +Z when the VPN is along Y.
        let reference = if vpn[0] == 0.0 && vpn[2] == 0.0 { [0.0, 0.0, 1.0] } else { [0.0, 1.0, 0.0] };
        let d = dot(reference, w);
        let up = normalize([reference[0] - d * w[0], reference[1] - d * w[1], reference[2] - d * w[2]]);
        let right = cross(up, w);
        let axes: Vec<usize> = (0..3).filter(|&a| vpn[a] != 0.0).collect();
        let high_face = [vpn[0] > 0.0, vpn[1] > 0.0, vpn[2] > 0.0];
        let nearest = (0..3).filter(|&a| high_face[a]).map(|a| 1 << a).sum::<usize>();
        let mut ftb_order = [0; 8];
        let mut k = 0;
        for bits in 0..=3 {
            for other in 0..8usize {
                if (other ^ nearest).count_ones() == bits {
                    ftb_order[k] = other;
                    k += 1;
                }
            }
        }
        Ok(View { vpn, w, right, up, axes, high_face, ftb_order })
    }

    /// The view case (the paper's seven).
    pub fn case(&self) -> ViewCase {
        match self.axes.as_slice() {
            [0, 1, 2] => ViewCase::XYZ,
            [0, 1] => ViewCase::XY,
            [0, 2] => ViewCase::XZ,
            [1, 2] => ViewCase::YZ,
            [0] => ViewCase::X,
            [1] => ViewCase::Y,
            _ => ViewCase::Z,
        }
    }

    /// Suboctant labels back to front (Meagher's order): the reverse of [`Self::ftb_order`].
    pub fn btf_order(&self) -> [usize; 8] {
        let mut order = self.ftb_order;
        order.reverse();
        order
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    a.map(|v| v / l)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_order_for_1_1_1() {
        let v = View::new([1.0, 1.0, 1.0]).unwrap();
        // 7, then 6 5 3, then 4 1 2 (in some order), then 0.
        assert_eq!(v.ftb_order[0], 7);
        assert_eq!(v.ftb_order[7], 0);
        let mut ones: Vec<usize> = v.ftb_order[1..4].to_vec();
        ones.sort();
        assert_eq!(ones, vec![3, 5, 6]);
        assert_eq!(v.case(), ViewCase::XYZ);
    }

    #[test]
    fn cases_and_frames() {
        for (vpn, case) in [
            ([1.0, -1.0, 0.0], ViewCase::XY),
            ([0.0, -1.0, 0.0], ViewCase::Y),
            ([2.0, 0.0, -1.0], ViewCase::XZ),
            ([0.0, 0.0, 3.0], ViewCase::Z),
            ([0.0, 1.0, 1.0], ViewCase::YZ),
            ([-1.0, 0.0, 0.0], ViewCase::X),
        ] {
            let v = View::new(vpn).unwrap();
            assert_eq!(v.case(), case, "{vpn:?}");
            // An orthonormal right-handed frame.
            assert!((dot(v.right, v.up)).abs() < 1e-12 && (dot(v.up, v.w)).abs() < 1e-12);
            let c = cross(v.right, v.up);
            assert!((0..3).all(|k| (c[k] - v.w[k]).abs() < 1e-12), "{vpn:?}");
        }
    }

    #[test]
    fn zero_vpn_is_a_clear_error() {
        let e = View::new([0.0, 0.0, 0.0]).unwrap_err().to_string();
        assert!(e.contains("(0, 0, 0)"), "{e}");
        assert!(View::new([f64::NAN, 1.0, 0.0]).is_err());
    }
}
