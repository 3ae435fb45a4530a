//! The Volume Octree of an RGBA volume with dependent components (VTK's
//! `vtkVolumeProperty::IndependentComponentsOff` on a 4-component array;
//! ParaView's *Map Scalars* off, *Multi Components Mapping* on): components
//! 0, 1, 2 are the colour itself, component 3 goes through the scalar
//! opacity function and gives the gradient.
//!
//! The four fields share one grid, hence one [`Layout`]; the tree the
//! selection refines ([`RgbaOctree::combined`],
//! [`combine_fields`](super::dependent::combine_fields)) carries per node
//!
//! ```text
//! min(n), max(n) = component 3's           (visible(min, max): opacity function over them is not 0)
//! E_p(n)         = max over the 4 components of E^k_p(n)   (each normalised by its own range)
//! Q_p(n)         = sum over the 4 components of Q^k_p(n)
//! ```
//!
//! for the reasons of [`super::dependent`]: the max bounds the error of any
//! component drawn at level `p`, keeps the tree well formed, and does not
//! depend on the transfer functions (the selection is kept across their
//! changes). Each component's error is normalised by its own range as VTK
//! normalises each colour component by its range
//! ([`crate::transfer::direct_colour`]), so it is the error in colour units.
//!
//! [`Layout`]: super::Layout

use super::build::BuildOptions;
use super::dependent::combine_fields;
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};
use crate::data::grid::Grid;

/// The octrees of an RGBA volume (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct RgbaOctree {
    /// What the selection refines: the shared structure, component 3's
    /// min/max, the largest of the four components' normalised errors.
    pub combined: VolumeOctree,
    /// Component 3's own tree (the opacity and gradient field): its value
    /// range is the opacity function's domain.
    pub alpha: VolumeOctree,
    /// The finite (min, max) of components 0, 1, 2 (what VTK scales the colour by).
    pub colour_ranges: [(f64, f64); 3],
}

impl RgbaOctree {
    /// Builds the four components' octrees (`fields`: components 0..3 of one
    /// grid; nothing is copied) and combines them, calling
    /// `progress(fraction)` between chunks of leaf bricks (a quarter per
    /// component); `false` cancels.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the fields' grids differ in shape;
    /// the errors of [`VolumeOctree::build_with_progress`].
    pub fn build_with_progress(
        fields: [&Grid<'_>; 4],
        options: &BuildOptions,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<RgbaOctree> {
        if fields.iter().any(|f| f.shape() != fields[3].shape()) {
            return Err(Error::InvalidArgument(
                "the RGBA components have different dims, spacing or origin: give four components of one image".into(),
            ));
        }
        let mut colour = Vec::with_capacity(3);
        for (k, field) in fields[..3].iter().enumerate() {
            let q = k as f64 / 4.0;
            colour.push(VolumeOctree::build_with_progress(field, options, &mut |f| progress(q + 0.25 * f))?);
        }
        let alpha = VolumeOctree::build_with_progress(fields[3], options, &mut |f| progress(0.75 + 0.25 * f))?;
        let combined = combine_fields(&[&colour[0], &colour[1], &colour[2]], &alpha)?;
        let colour_ranges = [0, 1, 2].map(|k| colour[k].value_range());
        Ok(RgbaOctree { combined, alpha, colour_ranges })
    }

    /// [`Self::build_with_progress`] without progress.
    pub fn build(fields: [&Grid<'_>; 4], options: &BuildOptions) -> Result<RgbaOctree> {
        Self::build_with_progress(fields, options, &mut |_| true)
    }

    /// Bytes owned by the kept trees.
    pub fn octree_bytes(&self) -> usize {
        self.combined.octree_bytes() + self.alpha.octree_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{GridShape, Samples};

    /// Four interleaved u8 components on an `n^3` grid, constant (a grey
    /// colour, opacity 200) except a bump in component `bump` in the corner `[0, 4)^3`.
    fn rgba(n: usize, bump: usize) -> Vec<u8> {
        let mut data = Vec::with_capacity(4 * n * n * n);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    for c in 0..4 {
                        let base = if c == 3 { 200 } else { 90 + 10 * c as u8 };
                        let detail =
                            if c == bump && i < 4 && j < 4 && k < 4 { ((i * 7 + j * 3 + k) % 5) as u8 * 9 } else { 0 };
                        data.push(base + detail);
                    }
                }
            }
        }
        data
    }

    /// The combined tree is valid, takes component 3's ranges and the
    /// largest error of the four: detail in any one component keeps the
    /// root from being homogeneous, and the far node stays homogeneous.
    #[test]
    fn combined_tree_takes_alpha_range_and_all_errors() {
        let n = 33;
        let shape = GridShape { dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3] };
        let options = BuildOptions { leaf_size: 8 };
        for bump in 0..4 {
            let data = rgba(n, bump);
            let grids: Vec<Grid<'_>> =
                (0..4).map(|c| Grid::new(Samples::U8(&data), shape, 4, Some(c)).unwrap()).collect();
            let t = RgbaOctree::build([&grids[0], &grids[1], &grids[2], &grids[3]], &options).unwrap();
            t.combined.validate().unwrap();
            let alone: Vec<VolumeOctree> = grids.iter().map(|g| VolumeOctree::build(g, &options).unwrap()).collect();
            assert_eq!((t.combined.min.clone(), t.combined.max.clone()), (alone[3].min.clone(), alone[3].max.clone()));
            assert_eq!(t.alpha, alone[3]);
            let root = t.combined.node(t.combined.root());
            assert!(!root.is_homogeneous(), "bump in component {bump}");
            for p in 0..root.errors.len() {
                let max = alone.iter().map(|a| a.node(a.root()).error(p)).fold(0.0f32, f32::max);
                assert_eq!(root.error(p), max);
            }
            for c in 0..3 {
                assert_eq!(t.colour_ranges[c], alone[c].value_range());
            }
            let far = t.combined.layout().id(2, [3, 3, 3]);
            assert!(t.combined.node(far).is_homogeneous());
        }
        let data = rgba(n, 0);
        let small = vec![0u8; 4 * 17 * 17 * 17];
        let g = Grid::new(Samples::U8(&data), shape, 4, Some(0)).unwrap();
        let s = Grid::new(Samples::U8(&small), GridShape { dims: [17; 3], ..shape }, 4, Some(3)).unwrap();
        let e = RgbaOctree::build([&g, &g, &g, &s], &options).unwrap_err().to_string();
        assert!(e.contains("different dims"), "{e}");
    }
}
