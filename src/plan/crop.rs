//! VTK's volume cropping and clipping planes: which samples of the volume a
//! frame keeps ([`KeptRegion::keeps`]); a removed sample is empty (no
//! colour, no opacity) in every renderer.
//!
//! Cropping (`vtkVolumeMapper::SetCropping`, `SetCroppingRegionPlanes`,
//! `SetCroppingRegionFlags`): the planes `x = xmin, xmax`, `y = ymin, ymax`,
//! `z = zmin, zmax` (data coordinates: origin and spacing considered) cut
//! space into 27 regions; bit `i + 3 j + 9 k` of the flags keeps region
//! `(i, j, k)`, where along each axis
//!
//! ```text
//! region coordinate = 0  if x < min,   1  if min <= x <= max,   2  if x > max
//! ```
//!
//! (VTK 9.2's `computeRegionCoord`, `vtkVolumeShaderComposer.h`, with the
//! middle interval closed on both sides: VTK's is half-open, `[min, max)`,
//! and it clamps the planes to the volume's bounds, so that a box of planes on
//! the volume's faces removes VTK's far face samples; here it removes
//! nothing. The two differ only on the plane `x = max`.)
//!
//! Clipping planes (`vtkAbstractMapper::SetClippingPlanes`, a
//! `vtkPlaneCollection`): a sample `x` is kept when, for every plane of
//! origin `o` and normal `n`,
//!
//! ```text
//! n . (x - o) >= 0
//! ```
//!
//! (VTK's GPU ray caster clips the part of the ray where `n . (o - x) > 0`;
//! at most [`MAX_CLIPPING_PLANES`], its limit).
//!
//! A sample is kept when the cropping (if any) and every plane keep it. A
//! box is [`removed`](KeptRegion::removes_box) when the cropping removes
//! every region it meets or one plane has all its corners on the removed
//! side (a brick there draws nothing: it is not selected), and
//! [`kept`](KeptRegion::keeps_box) when every region it meets is kept and
//! every corner is on every plane's kept side (the planner then drops the
//! cropping or plane: [`KeptRegion::acting_on`]).

use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;

/// VTK's cropping flags of the common configurations (`vtkVolumeMapper.h`).
pub mod flags {
    /// Only the central region (VTK's default).
    pub const SUBVOLUME: u32 = 0x000_2000;
    /// The regions central along at least one axis (between a plane pair).
    pub const FENCE: u32 = 0x2eb_feba;
    /// The complement of the fence.
    pub const INVERTED_FENCE: u32 = 0x514_0145;
    /// The regions central along at least two axes.
    pub const CROSS: u32 = 0x041_7410;
    /// The complement of the cross.
    pub const INVERTED_CROSS: u32 = 0x7be_8bef;
    /// All 27 regions.
    pub const ALL: u32 = 0x7ff_ffff;
}

/// The most clipping planes a frame takes (VTK 9.2's GPU ray caster:
/// "We support only 8 clipping planes for now").
pub const MAX_CLIPPING_PLANES: usize = 8;

/// Orthogonal cropping: the six region planes and the 27 region flags.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Cropping {
    /// `xmin, xmax, ymin, ymax, zmin, zmax`, world (data) coordinates.
    pub planes: [f64; 6],
    /// Bit `i + 3 j + 9 k` keeps region `(i, j, k)` ([`flags`]).
    pub flags: u32,
}

impl Cropping {
    /// The central box `planes`, VTK's default flags ([`flags::SUBVOLUME`]).
    pub fn subvolume(planes: [f64; 6]) -> Cropping {
        Cropping { planes, flags: flags::SUBVOLUME }
    }

    /// Finite planes, `min <= max` per axis, flags within 27 bits.
    pub fn check(&self) -> Result<()> {
        if self.planes.iter().any(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "cropping planes {:?}: give six finite numbers xmin, xmax, ymin, ymax, zmin, zmax",
                self.planes
            )));
        }
        if let Some(a) = (0..3).find(|&a| self.planes[2 * a] > self.planes[2 * a + 1]) {
            return Err(Error::InvalidArgument(format!(
                "cropping planes {:?}: {} min {} is above its max {}: give each axis' min first",
                self.planes,
                ["x", "y", "z"][a],
                self.planes[2 * a],
                self.planes[2 * a + 1]
            )));
        }
        if self.flags > flags::ALL {
            return Err(Error::InvalidArgument(format!(
                "cropping flags {:#x}: only the 27 lowest bits name regions (at most {:#x})",
                self.flags,
                flags::ALL
            )));
        }
        Ok(())
    }

    /// The region coordinate (0, 1, 2) of `v` along `axis`.
    #[inline]
    fn coordinate(&self, v: f64, axis: usize) -> usize {
        if v < self.planes[2 * axis] {
            0
        } else if v > self.planes[2 * axis + 1] {
            2
        } else {
            1
        }
    }

    /// True when the region of `p` is kept.
    #[inline]
    pub fn keeps(&self, p: [f64; 3]) -> bool {
        let bit = self.coordinate(p[0], 0) + 3 * self.coordinate(p[1], 1) + 9 * self.coordinate(p[2], 2);
        self.flags >> bit & 1 == 1
    }

    /// The region coordinates the closed box `[lo, hi]` meets along `axis`.
    fn met(&self, lo: f64, hi: f64, axis: usize) -> [bool; 3] {
        let (min, max) = (self.planes[2 * axis], self.planes[2 * axis + 1]);
        [lo < min, hi >= min && lo <= max, hi > max]
    }

    /// The flags of the regions the box `[lo, hi]` meets.
    fn regions_met(&self, lo: [f64; 3], hi: [f64; 3]) -> u32 {
        let m = [0, 1, 2].map(|a| self.met(lo[a], hi[a], a));
        let mut bits = 0;
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    if m[0][i] && m[1][j] && m[2][k] {
                        bits |= 1 << (i + 3 * j + 9 * k);
                    }
                }
            }
        }
        bits
    }
}

/// A clipping plane: samples with `normal . (x - origin) >= 0` are kept.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ClippingPlane {
    /// A point of the plane, world coordinates.
    pub origin: [f64; 3],
    /// The normal, pointing to the kept side (any length > 0).
    pub normal: [f64; 3],
}

impl ClippingPlane {
    /// Finite numbers and a normal of length > 0.
    pub fn check(&self) -> Result<()> {
        let finite = self.origin.iter().chain(&self.normal).all(|v| v.is_finite());
        let length = self.normal.iter().map(|v| v * v).sum::<f64>().sqrt();
        let usable = finite && length > 0.0 && length.is_finite();
        if !usable {
            return Err(Error::InvalidArgument(format!(
                "clipping plane of origin {:?} and normal {:?}: give finite numbers and a normal of length > 0",
                self.origin, self.normal
            )));
        }
        Ok(())
    }

    /// `normal . (p - origin)`.
    #[inline]
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        (0..3).map(|a| self.normal[a] * (p[a] - self.origin[a])).sum()
    }

    /// True when `p` is on the kept side (or on the plane).
    #[inline]
    pub fn keeps(&self, p: [f64; 3]) -> bool {
        self.distance(p) >= 0.0
    }

    /// The smallest and largest distance of the box `[lo, hi]`'s corners.
    fn box_range(&self, lo: [f64; 3], hi: [f64; 3]) -> (f64, f64) {
        let (mut min, mut max) = (0.0, 0.0);
        for a in 0..3 {
            let (x, y) = (self.normal[a] * (lo[a] - self.origin[a]), self.normal[a] * (hi[a] - self.origin[a]));
            min += x.min(y);
            max += x.max(y);
        }
        (min, max)
    }
}

/// The samples a frame keeps: an optional cropping and up to
/// [`MAX_CLIPPING_PLANES`] clipping planes (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KeptRegion {
    /// Orthogonal cropping, if on.
    pub cropping: Option<Cropping>,
    planes: [Option<ClippingPlane>; MAX_CLIPPING_PLANES],
}

impl serde::Serialize for KeptRegion {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct View<'a> {
            cropping: Option<Cropping>,
            clipping_planes: Vec<&'a ClippingPlane>,
        }
        View { cropping: self.cropping, clipping_planes: self.planes().collect() }.serialize(s)
    }
}

impl KeptRegion {
    /// A cropping (or none) and clipping planes, checked.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a bad cropping ([`Cropping::check`]) or
    /// plane ([`ClippingPlane::check`]), or more than [`MAX_CLIPPING_PLANES`] planes.
    pub fn new(cropping: Option<Cropping>, planes: &[ClippingPlane]) -> Result<KeptRegion> {
        if let Some(c) = &cropping {
            c.check()?;
        }
        if planes.len() > MAX_CLIPPING_PLANES {
            return Err(Error::InvalidArgument(format!(
                "{} clipping planes: at most {MAX_CLIPPING_PLANES} are drawn (VTK's GPU ray caster's limit); \
                 remove some",
                planes.len()
            )));
        }
        let mut region = KeptRegion { cropping, planes: [None; MAX_CLIPPING_PLANES] };
        for (i, p) in planes.iter().enumerate() {
            p.check()?;
            region.planes[i] = Some(*p);
        }
        Ok(region)
    }

    /// The clipping planes.
    pub fn planes(&self) -> impl Iterator<Item = &ClippingPlane> + '_ {
        self.planes.iter().flatten()
    }

    /// True when it removes nothing anywhere: no cropping, no plane.
    pub fn is_empty(&self) -> bool {
        self.cropping.is_none() && self.planes().next().is_none()
    }

    /// True when the sample at `p` is kept.
    #[inline]
    pub fn keeps(&self, p: [f64; 3]) -> bool {
        self.cropping.is_none_or(|c| c.keeps(p)) && self.planes().all(|plane| plane.keeps(p))
    }

    /// True when every point of the closed box `[lo, hi]` is removed (as
    /// far as each of the cropping and the planes alone tells).
    pub fn removes_box(&self, lo: [f64; 3], hi: [f64; 3]) -> bool {
        self.cropping.is_some_and(|c| c.regions_met(lo, hi) & c.flags == 0)
            || self.planes().any(|p| p.box_range(lo, hi).1 < 0.0)
    }

    /// True when every point of the closed box `[lo, hi]` is kept.
    pub fn keeps_box(&self, lo: [f64; 3], hi: [f64; 3]) -> bool {
        self.cropping.is_none_or(|c| c.regions_met(lo, hi) & !c.flags == 0)
            && self.planes().all(|p| p.box_range(lo, hi).0 >= 0.0)
    }

    /// What acts on the box `[lo, hi]` (the volume's): the cropping unless
    /// it keeps the whole box, the planes that cut it or remove it; `None`
    /// when nothing is left.
    pub fn acting_on(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<KeptRegion> {
        let mut region =
            KeptRegion { cropping: self.cropping.filter(|c| c.regions_met(lo, hi) & !c.flags != 0), ..*self };
        // The planes that cut the box, in order (a subset: they fit).
        let mut cutting = self.planes().filter(|p| p.box_range(lo, hi).0 < 0.0).copied();
        region.planes = [(); MAX_CLIPPING_PLANES].map(|_| cutting.next());
        (!region.is_empty()).then_some(region)
    }

    /// The effects the region has, as the plan names them: `cropping`,
    /// `clipping`.
    pub fn effects(&self) -> Vec<String> {
        let mut effects = Vec::new();
        if self.cropping.is_some() {
            effects.push("cropping".to_string());
        }
        if self.planes().next().is_some() {
            effects.push("clipping".to_string());
        }
        effects
    }

    /// The same region in the index space of `shape` (`i = (x - origin) /
    /// spacing` per axis): cropping planes through that map, a plane's
    /// origin likewise and its normal times the spacing (`n . (x - o) =
    /// (n s) . (i - i_o)`), so that a point keeps its side.
    pub fn to_index(&self, shape: &GridShape) -> KeptRegion {
        let index = |x: f64, a: usize| (x - shape.origin[a]) / shape.spacing[a];
        let mut out = *self;
        if let Some(c) = &mut out.cropping {
            c.planes = [0, 1, 2, 3, 4, 5].map(|i| index(c.planes[i], i / 2));
        }
        for p in out.planes.iter_mut().flatten() {
            p.origin = [0, 1, 2].map(|a| index(p.origin[a], a));
            p.normal = [0, 1, 2].map(|a| p.normal[a] * shape.spacing[a]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn common_flags_keep_their_regions() {
        let planes = [1.0, 2.0, 1.0, 2.0, 1.0, 2.0];
        let at = |i: usize, j: usize, k: usize| [0.5 + i as f64, 0.5 + j as f64, 0.5 + k as f64];
        let kept = |f: u32| {
            let c = Cropping { planes, flags: f };
            let mut n = 0;
            for k in 0..3 {
                for j in 0..3 {
                    for i in 0..3 {
                        n += usize::from(c.keeps(at(i, j, k)));
                    }
                }
            }
            n
        };
        assert_eq!(kept(flags::SUBVOLUME), 1);
        assert!(Cropping::subvolume(planes).keeps(at(1, 1, 1)) && !Cropping::subvolume(planes).keeps(at(0, 1, 1)));
        // Fence: central along at least one axis (19 regions); cross: along at least two (7).
        assert_eq!(kept(flags::FENCE), 27 - kept(flags::INVERTED_FENCE));
        assert_eq!(kept(flags::CROSS), 27 - kept(flags::INVERTED_CROSS));
        assert_eq!(kept(flags::CROSS), 7);
        assert_eq!(kept(flags::FENCE), 19);
        assert_eq!(kept(flags::ALL), 27);
        // The middle interval is closed.
        let c = Cropping::subvolume(planes);
        assert!(c.keeps([1.0, 2.0, 1.5]) && !c.keeps([2.0 + 1e-12, 1.5, 1.5]));
    }

    #[test]
    fn planes_keep_their_positive_side_and_boxes_are_classified() {
        let plane = ClippingPlane { origin: [1.0, 0.0, 0.0], normal: [2.0, 0.0, 0.0] };
        assert!(plane.keeps([1.0, 5.0, 5.0]) && plane.keeps([3.0, 0.0, 0.0]) && !plane.keeps([0.5, 0.0, 0.0]));
        let r = KeptRegion::new(None, &[plane]).unwrap();
        assert!(r.removes_box([-1.0; 3], [0.9, 5.0, 5.0]));
        assert!(!r.removes_box([-1.0; 3], [1.0, 5.0, 5.0]) && !r.keeps_box([-1.0; 3], [1.0, 5.0, 5.0]));
        assert!(r.keeps_box([1.0, -3.0, -3.0], [4.0, 5.0, 5.0]));
        let c = KeptRegion::new(Some(Cropping::subvolume([1.0, 2.0, 1.0, 2.0, 1.0, 2.0])), &[]).unwrap();
        assert!(c.removes_box([0.0; 3], [0.9, 3.0, 3.0]) && !c.removes_box([0.0; 3], [1.0, 3.0, 3.0]));
        assert!(c.keeps_box([1.0; 3], [2.0; 3]) && !c.keeps_box([1.0; 3], [2.1, 2.0, 2.0]));
        let fence = KeptRegion::new(Some(Cropping { flags: flags::FENCE, ..c.cropping.unwrap() }), &[]).unwrap();
        assert!(!fence.removes_box([0.0; 3], [0.9, 3.0, 3.0]) && fence.removes_box([0.0; 3], [0.9, 0.9, 0.9]));
    }

    #[test]
    fn no_op_parts_are_dropped_for_a_box() {
        let (lo, hi) = ([0.0; 3], [10.0; 3]);
        let around = Cropping::subvolume([0.0, 10.0, -1.0, 11.0, 0.0, 10.0]);
        let outside = ClippingPlane { origin: [-1.0, 0.0, 0.0], normal: [1.0, 0.0, 0.0] };
        let cutting = ClippingPlane { origin: [5.0, 5.0, 5.0], normal: [1.0, 1.0, 0.0] };
        assert_eq!(KeptRegion::new(Some(around), &[outside]).unwrap().acting_on(lo, hi), None);
        let acting = KeptRegion::new(Some(around), &[outside, cutting]).unwrap().acting_on(lo, hi).unwrap();
        assert_eq!(acting.cropping, None);
        assert_eq!(acting.planes().copied().collect::<Vec<_>>(), vec![cutting]);
        assert_eq!(acting.effects(), vec!["clipping"]);
        let inner = Cropping::subvolume([1.0, 9.0, 0.0, 10.0, 0.0, 10.0]);
        let acting = KeptRegion::new(Some(inner), &[]).unwrap().acting_on(lo, hi).unwrap();
        assert_eq!(acting.effects(), vec!["cropping"]);
    }

    #[test]
    fn bad_values_are_refused_with_the_reason() {
        let e = Cropping::subvolume([0.0, f64::NAN, 0.0, 1.0, 0.0, 1.0]).check().unwrap_err().to_string();
        assert!(e.contains("finite"), "{e}");
        let e = Cropping::subvolume([0.0, 1.0, 2.0, 1.0, 0.0, 1.0]).check().unwrap_err().to_string();
        assert!(e.contains("y min 2 is above its max 1"), "{e}");
        let e = Cropping { planes: [0.0, 1.0, 0.0, 1.0, 0.0, 1.0], flags: 1 << 27 }.check().unwrap_err().to_string();
        assert!(e.contains("27 lowest bits"), "{e}");
        let zero = ClippingPlane { origin: [0.0; 3], normal: [0.0; 3] };
        assert!(KeptRegion::new(None, &[zero]).unwrap_err().to_string().contains("length > 0"));
        let plane = ClippingPlane { origin: [0.0; 3], normal: [1.0, 0.0, 0.0] };
        let e = KeptRegion::new(None, &[plane; 9]).unwrap_err().to_string();
        assert!(e.contains("at most 8"), "{e}");
    }

    #[test]
    fn index_space_keeps_every_side() {
        let shape = GridShape { dims: [5, 6, 7], spacing: [0.5, 2.0, 1.5], origin: [-1.0, 3.0, 0.25] };
        let r = KeptRegion::new(
            Some(Cropping { planes: [-0.5, 0.5, 4.0, 9.0, 1.0, 5.0], flags: flags::CROSS }),
            &[ClippingPlane { origin: [0.0, 6.0, 2.0], normal: [1.0, -0.5, 0.3] }],
        )
        .unwrap();
        let index = r.to_index(&shape);
        for i in 0..5 {
            for j in 0..6 {
                for k in 0..7 {
                    let ijk = [i as f64, j as f64, k as f64];
                    assert_eq!(index.keeps(ijk), r.keeps(shape.world(ijk)), "{ijk:?}");
                }
            }
        }
    }
}
