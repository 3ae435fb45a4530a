//! The Volume Octree of a two-field volume with dependent components
//! (VTK's `vtkVolumeProperty::IndependentComponentsOff` on a 2-component
//! array; ParaView's *Use Separate Opacity Array*): the colour comes from
//! field 0 through the colour transfer function, the opacity from field 1
//! through the scalar opacity function.
//!
//! Both fields share one grid, so their octrees share one [`Layout`]: the
//! structure is kept, and the tree the selection refines
//! ([`DependentOctree::combined`]) carries per node
//!
//! ```text
//! min(n), max(n) = the opacity field's      (visible(min, max): opacity TF over them is not 0)
//! E_p(n)         = max(E^c_p(n), E^o_p(n))  (each normalised by its own field's range)
//! Q_p(n)         = Q^c_p(n) + Q^o_p(n)
//! ```
//!
//! The selection's visibility test is the opacity function over the
//! opacity field's range: a node the opacity field makes transparent is
//! never selected, whatever its colours, and a node with visible opacity is
//! selected even where its colour field is constant.
//!
//! The error is the larger of the two normalised errors, not a weighted sum
//! with the colour function's slope: the selection is made before (and
//! kept across) changes of the transfer functions, and the colour
//! function's sensitivity is unknown then; the max is a bound on the error
//! of either field drawn at level `p`, is non-increasing in `p`, and keeps
//! `E_p(parent) = max over children of E_(p-1)(child)` (max commutes with
//! max), so the combined tree is a well-formed Volume Octree
//! ([`VolumeOctree::validate`]). A node is homogeneous (terminal) only when
//! both fields are trilinear over it. `Q_p`, the squared error summed over
//! the node's samples, adds the two fields' (the squared length of the
//! error of the pair of normalised fields).
//!
//! [`Layout`]: super::Layout

use super::build::BuildOptions;
use super::volume_octree::VolumeOctree;
use crate::base::error::{Error, Result};
use crate::data::grid::Grid;

/// The octrees of a dependent two-field volume (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct DependentOctree {
    /// What the selection refines: the shared structure, the opacity field's
    /// min/max, the larger of the two fields' normalised errors.
    pub combined: VolumeOctree,
    /// Field 0's own tree: its min/max and errors per node, its value range
    /// (the colour function's domain).
    pub colour: VolumeOctree,
}

impl DependentOctree {
    /// Builds both fields' octrees (`colour`, `opacity`: the two fields of
    /// one grid, e.g. components 0 and 1 of one array; nothing is copied)
    /// and combines them, calling `progress(fraction)` between chunks of leaf
    /// bricks (the colour field fills the first half); `false` cancels.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the fields' grids differ in shape;
    /// the errors of [`VolumeOctree::build_with_progress`].
    pub fn build_with_progress(
        colour: &Grid<'_>,
        opacity: &Grid<'_>,
        options: &BuildOptions,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<DependentOctree> {
        if colour.shape() != opacity.shape() {
            return Err(Error::InvalidArgument(
                "the colour and opacity fields have different dims, spacing or origin: give two fields of one image"
                    .into(),
            ));
        }
        let colour_tree = VolumeOctree::build_with_progress(colour, options, &mut |f| progress(0.5 * f))?;
        let opacity_tree = VolumeOctree::build_with_progress(opacity, options, &mut |f| progress(0.5 + 0.5 * f))?;
        let combined = combine(&colour_tree, &opacity_tree)?;
        Ok(DependentOctree { combined, colour: colour_tree })
    }

    /// [`Self::build_with_progress`] without progress.
    pub fn build(colour: &Grid<'_>, opacity: &Grid<'_>, options: &BuildOptions) -> Result<DependentOctree> {
        Self::build_with_progress(colour, opacity, options, &mut |_| true)
    }

    /// The opacity field's (min, max).
    pub fn opacity_range(&self) -> (f64, f64) {
        self.combined.value_range()
    }

    /// The colour field's (min, max).
    pub fn colour_range(&self) -> (f64, f64) {
        self.colour.value_range()
    }

    /// Bytes owned by both trees.
    pub fn octree_bytes(&self) -> usize {
        self.combined.octree_bytes() + self.colour.octree_bytes()
    }
}

/// The combined tree of the module documentation: `opacity`'s min/max,
/// `max(E^c, E^o)`, `Q^c + Q^o`.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when the two trees have different layouts.
pub fn combine(colour: &VolumeOctree, opacity: &VolumeOctree) -> Result<VolumeOctree> {
    combine_fields(&[colour], opacity)
}

/// The combined tree of several fields of one grid: `opacity`'s min/max
/// (the selection's visibility test), per node and level the largest of
/// all the fields' normalised errors (`opacity`'s included) and the sum of
/// their squared errors,
///
/// ```text
/// E_p(n) = max(E^o_p(n), max_f E^f_p(n)),   Q_p(n) = Q^o_p(n) + sum_f Q^f_p(n)
/// ```
///
/// # Errors
///
/// [`Error::InvalidArgument`] when the trees have different layouts.
pub fn combine_fields(others: &[&VolumeOctree], opacity: &VolumeOctree) -> Result<VolumeOctree> {
    if others.iter().any(|t| t.layout != opacity.layout || t.error_offset != opacity.error_offset) {
        return Err(Error::InvalidArgument(
            "the fields' octrees have different layouts: build them from one grid with one leaf size".into(),
        ));
    }
    let mut errors = opacity.errors.clone();
    let mut squared = opacity.squared_errors.clone();
    for t in others {
        errors.iter_mut().zip(&t.errors).for_each(|(e, &c)| *e = e.max(c));
        squared.iter_mut().zip(&t.squared_errors).for_each(|(q, &c)| *q += c);
    }
    let build_ms = opacity.build_ms + others.iter().map(|t| t.build_ms).sum::<f64>();
    Ok(VolumeOctree::from_parts(
        opacity.layout.clone(),
        opacity.min.clone(),
        opacity.max.clone(),
        errors,
        squared,
        opacity.error_offset.clone(),
        build_ms,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, GridShape, Samples};

    /// Two interleaved fields: a constant colour field and an opacity field
    /// with a bump in one corner, and the reverse.
    fn fields(n: usize, bump_in_colour: bool) -> Vec<f32> {
        let mut data = Vec::with_capacity(2 * n * n * n);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let bump = if i < 4 && j < 4 && k < 4 { ((i * 7 + j * 3 + k) % 5) as f32 } else { 0.0 };
                    let (c, o) = if bump_in_colour { (bump, 0.5) } else { (0.5, bump) };
                    data.push(c);
                    data.push(o);
                }
            }
        }
        data
    }

    fn grids(data: &[f32], n: usize) -> (Grid<'_>, Grid<'_>) {
        let shape = GridShape { dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3] };
        let c = Grid::new(Samples::F32(data), shape, 2, Some(0)).unwrap();
        let o = Grid::new(Samples::F32(data), shape, 2, Some(1)).unwrap();
        (c, o)
    }

    /// The combined tree is a valid Volume Octree whose ranges are the
    /// opacity field's and whose errors are the larger of the two fields',
    /// so detail in either field keeps a node from being homogeneous.
    #[test]
    fn combined_tree_takes_the_opacity_range_and_both_errors() {
        let n = 33;
        for bump_in_colour in [true, false] {
            let data = fields(n, bump_in_colour);
            let (c, o) = grids(&data, n);
            let options = BuildOptions { leaf_size: 8 };
            let d = DependentOctree::build(&c, &o, &options).unwrap();
            d.combined.validate().unwrap();
            let alone = VolumeOctree::build(&o, &options).unwrap();
            let colour = VolumeOctree::build(&c, &options).unwrap();
            assert_eq!((alone.min.clone(), alone.max.clone()), (d.combined.min.clone(), d.combined.max.clone()));
            assert_eq!(d.colour, colour);
            let root = d.combined.node(d.combined.root());
            // The bump (in either field) makes the root inhomogeneous.
            assert!(!root.is_homogeneous(), "bump in colour {bump_in_colour}");
            for p in 0..root.errors.len() {
                let (ec, eo) = (colour.node(colour.root()).error(p), alone.node(alone.root()).error(p));
                assert_eq!(root.error(p), ec.max(eo));
            }
            // The node far from the bump is homogeneous in both fields.
            let far = d.combined.layout().id(2, [3, 3, 3]);
            assert!(d.combined.node(far).is_homogeneous());
        }
        let data = fields(n, true);
        let (c, _) = grids(&data, n);
        let small = vec![0.0f32; 2 * 17 * 17 * 17];
        let (_, o) = grids(&small, 17);
        let e = DependentOctree::build(&c, &o, &BuildOptions::default()).unwrap_err().to_string();
        assert!(e.contains("different dims"), "{e}");
    }
}
