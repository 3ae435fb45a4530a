//! The Volume Octree of an RGBA volume with dependent components (VTK's
//! `vtkVolumeProperty::IndependentComponentsOff` on a 4-component array;
//! ParaView's *Map Scalars* off, *Multi Components Mapping* on): components
//! 0, 1, 2 are the colour itself (component 0 gives the gradient),
//! component 3 goes through the scalar opacity function at `v'`, the value
//! VTK 9.2 reads it as ([`crate::transfer::direct_colour`]).
//!
//! The four fields share one grid, hence one [`Layout`]; the tree the
//! selection refines ([`RgbaOctree::combined`],
//! [`combine_fields`]) carries per node
//!
//! ```text
//! min(n), max(n) = v' of component 3's   (visible(min, max): opacity TF over them is not 0;
//!                                         v' is non-decreasing: they bound v' over the node)
//! E_p(n)         = max over the 4 components of E^k_p(n)   (each normalised by its own range)
//! Q_p(n)         = sum over the 4 components of Q^k_p(n)
//! ```
//!
//! for the reasons of [`super::dependent`]: the max bounds the error of any
//! component drawn at level `p`, keeps the tree well formed, and does not
//! depend on the transfer functions (the selection is kept across their
//! changes). Each component's error is normalised by its own range.
//!
//! [`Layout`]: super::Layout

use super::build::BuildOptions;
use super::dependent::combine_fields;
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};
use crate::data::grid::Grid;
use crate::transfer::direct_colour::RgbaScale;

/// The octrees of an RGBA volume (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct RgbaOctree {
    /// What the selection refines: the shared structure, `v'` of component
    /// 3's min/max, the largest of the four components' normalised errors.
    pub combined: VolumeOctree,
    /// Component 0's own tree (the gradient's field).
    pub red: VolumeOctree,
    /// The finite (min, max) of the four components.
    pub ranges: [(f64, f64); 4],
    /// VTK's reading of the components (their type and ranges).
    pub scale: RgbaScale,
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
        let mut trees = Vec::with_capacity(4);
        for (k, field) in fields.iter().enumerate() {
            let q = k as f64 / 4.0;
            trees.push(VolumeOctree::build_with_progress(field, options, &mut |f| progress(q + 0.25 * f))?);
        }
        let ranges = [0, 1, 2, 3].map(|k| trees[k].value_range());
        let scale = RgbaScale::vtk(fields[3].samples().scalar_type(), ranges);
        let mut combined = combine_fields(&[&trees[0], &trees[1], &trees[2]], &trees[3])?;
        for v in combined.min.iter_mut().chain(combined.max.iter_mut()) {
            *v = scale.opacity_value(*v);
        }
        let red = trees.swap_remove(0);
        Ok(RgbaOctree { combined, red, ranges, scale })
    }

    /// [`Self::build_with_progress`] without progress.
    pub fn build(fields: [&Grid<'_>; 4], options: &BuildOptions) -> Result<RgbaOctree> {
        Self::build_with_progress(fields, options, &mut |_| true)
    }

    /// Bytes owned by the kept trees.
    pub fn octree_bytes(&self) -> usize {
        self.combined.octree_bytes() + self.red.octree_bytes()
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
            // The combined ranges are v' of alpha's (VTK's reading of the u8 values).
            let v = |x: &f64| t.scale.opacity_value(*x);
            assert_eq!(t.combined.min, alone[3].min.iter().map(v).collect::<Vec<_>>());
            assert_eq!(t.combined.max, alone[3].max.iter().map(v).collect::<Vec<_>>());
            assert_eq!(t.red, alone[0]);
            let root = t.combined.node(t.combined.root());
            assert!(!root.is_homogeneous(), "bump in component {bump}");
            for p in 0..root.errors.len() {
                let max = alone.iter().map(|a| a.node(a.root()).error(p)).fold(0.0f32, f32::max);
                assert_eq!(root.error(p), max);
            }
            assert_eq!(t.ranges.to_vec(), alone.iter().map(VolumeOctree::value_range).collect::<Vec<_>>());
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
