//! Two dependent fields across the bridge (VTK's `IndependentComponentsOff`
//! on a 2-component array; ParaView's *Use Separate Opacity Array*, whose
//! `<color>_and_opacity` array holds the colour array in component 0 and
//! the opacity array in component 1): the octree of both fields
//! ([`crate::octree::DependentOctree`]), their two-channel brick texels and
//! the CPU compositor's picture. The host's array is borrowed whole (both
//! components), nothing is copied or changed.

use super::grid::{grid_of, grid_unscanned, same_image};
use super::guard::{guarded, write_pixels, Bridged};
use super::octree::{next_id, HybridOctreeHandle};
use super::render::SelectionHandle;
use super::{BuildProgress, GridDesc};
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::hybrid::HybridOctree;
use crate::octree::{BuildOptions, DependentOctree};
use crate::plan::DrawList;
use crate::render::dependent::{brick_texels_dependent_f32_into, composite_dependent, upload_dependent};
use crate::transfer::TransferFunction;

/// The colour (component 0) and opacity (component 1) fields of a
/// 2-component image; `desc.component` is not read.
pub(crate) fn fields<'a>(bytes: &'a [u8], desc: &GridDesc, scan: bool) -> Result<(Grid<'a>, Grid<'a>)> {
    if desc.components != 2 {
        return Err(Error::InvalidArgument(format!(
            "two dependent fields are read from a 2-component array (colour, opacity); this one has {}: \
             give 2 components, 4 for an RGBA volume, or turn IndependentComponents on and choose a component",
            desc.components
        )));
    }
    let of = |component: i32| {
        let d = GridDesc { component, ..*desc };
        if scan {
            grid_of(bytes, &d)
        } else {
            grid_unscanned(bytes, &d)
        }
    };
    Ok((of(0)?, of(1)?))
}

pub(crate) fn build_dependent_octree(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &BuildProgress,
) -> Bridged<Box<HybridOctreeHandle>> {
    build_dependent_with(bytes, desc, leaf_size, &mut |fraction| progress.report(fraction))
}

/// Builds both fields' octrees (see [`DependentOctree::build_with_progress`]).
pub(crate) fn build_dependent_with(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Bridged<Box<HybridOctreeHandle>> {
    guarded(|| {
        match desc.components {
            2 => {}
            4 => return super::rgba::build_rgba(bytes, desc, leaf_size, progress),
            n => {
                return Err(Error::InvalidArgument(format!(
                    "dependent components (IndependentComponents off) are drawn for 2-component (colour, \
                     opacity) and 4-component (RGBA) arrays, as VTK draws them; this one has {n}{}: turn \
                     IndependentComponents on and choose a component, or append a component (e.g. an \
                     opacity array with vtkImageAppendComponents)",
                    if n == 3 { " (RGB without opacity: VTK reads the missing fourth component)" } else { "" }
                )))
            }
        }
        let (colour, opacity) = fields(bytes, desc, true)?;
        let options = BuildOptions { leaf_size: leaf_size as usize };
        let built = DependentOctree::build_with_progress(&colour, &opacity, &options, progress)?;
        Ok(Box::new(HybridOctreeHandle {
            hybrid: HybridOctree::volume_only(built.colour),
            shape: *colour.shape(),
            input_bytes: colour.input_bytes(),
            nan_samples: colour.nan_count() + opacity.nan_count(),
            scalar_type: colour.samples().scalar_type(),
            dependent: Some(built.combined),
            rgba: None,
            id: next_id(),
            surface_id: 0,
            selector: Default::default(),
            medium: Default::default(),
        }))
    })
}

impl SelectionHandle {
    /// Brick `brick`'s texels of both fields, `(colour, opacity)` pairs
    /// ([`brick_texels_dependent_f32_into`]), with the gradient border when `bordered`.
    pub(crate) fn brick_texels_dependent(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        brick: usize,
        bordered: bool,
        texels: &mut [f32],
    ) -> Bridged<()> {
        guarded(|| {
            if !self.dependent {
                return Err(Error::InvalidArgument(if self.rgba.is_some() {
                    "this selection was made from an RGBA volume: read its texels with brick_texels_rgba".into()
                } else {
                    "this selection was made from one field: read its texels with brick_texels".into()
                }));
            }
            let (colour, opacity) = fields(bytes, desc, false)?;
            same_image(&self.shape, &colour)?;
            let b = &self.selected_brick(brick)?;
            brick_texels_dependent_f32_into(&colour, &opacity, b, bordered, texels)?;
            if let Some(i) = texels.iter().position(|v| v.is_infinite()) {
                return Err(Error::InvalidArgument(format!(
                    "brick {brick} holds an infinite value (texel {}): the image changed since the octree was \
                     built, or its values exceed a 32-bit float; fix the values and rebuild it",
                    i / 2
                )));
            }
            Ok(())
        })
    }
}

/// The CPU compositor's picture of a dependent DrawList into `rgba`.
pub(crate) fn composite_into(
    list: &DrawList,
    bytes: &[u8],
    desc: &GridDesc,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    rgba: &mut [f32],
) -> Result<()> {
    let (colour, opacity) = fields(bytes, desc, true)?;
    let textures = upload_dependent(&colour, &opacity, list)?;
    let image = composite_dependent(&textures, list, tf, width, height)?;
    write_pixels(&image.rgba, rgba)
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{as_bytes, select_desc};
    use super::super::{CameraDesc, ScalarType};
    use super::*;

    /// Colour a ramp along x, opacity 1 only in the half x >= 8.
    fn two_fields(n: usize) -> Vec<f32> {
        let mut data = Vec::new();
        for _k in 0..n {
            for _j in 0..n {
                for i in 0..n {
                    data.push(i as f32 / (n - 1) as f32);
                    data.push(if i >= 8 { 1.0 } else { 0.0 });
                }
            }
        }
        data
    }

    fn desc(n: usize, components: usize) -> GridDesc {
        GridDesc {
            scalar_type: ScalarType::F32,
            dims: [n; 3],
            spacing: [1.0; 3],
            origin: [0.0; 3],
            components,
            component: 0,
        }
    }

    /// The bridge builds both fields, selects on the opacity field (the half
    /// of opacity 0 skipped, 8 bytes a texel), its DrawLists say
    /// `dependent-components`, its texels interleave the fields, and a
    /// 1- or 4-component array is refused with the reason.
    #[test]
    fn bridge_selects_on_the_opacity_field_and_interleaves_texels() {
        let n = 17;
        let data = two_fields(n);
        let h = build_dependent_with(as_bytes(&data), &desc(n, 2), 4, &mut |_| true).unwrap();
        let mut select = select_desc(1 << 30);
        select.opacity_points = vec![0.0, 0.0, 1.0, 0.5];
        let s = h.select_bricks(&select).unwrap();
        assert!(s.dependent);
        let summary = s.summary().unwrap();
        assert!(summary.skipped > 0, "{summary:?}");
        assert!(s.selection.bricks.iter().all(|b| b.hi[0] >= 8));
        let texels: usize = s.selection.bricks.iter().map(|b| b.texels.iter().product::<usize>()).sum();
        assert_eq!(summary.texture_bytes, 8 * texels, "two f32 fields a texel");
        let camera = CameraDesc {
            position: [8.0, 8.0, 60.0],
            focal_point: [8.0; 3],
            view_up: [0.0, 1.0, 0.0],
            parallel: true,
            parallel_scale: 10.0,
            view_angle: 30.0,
        };
        let list = s.draw_list(&h, &camera, 0.0).unwrap();
        assert_eq!(list.effects, "dependent-components");
        let b = &s.selection.bricks[0];
        let count: usize = b.texels.iter().product();
        let mut out = vec![0.0f32; 2 * count];
        s.brick_texels_dependent(as_bytes(&data), &desc(n, 2), 0, false, &mut out).unwrap();
        assert_eq!((out[0], out[1]), (b.lo[0] as f32 / 16.0, if b.lo[0] >= 8 { 1.0 } else { 0.0 }));
        let mut short = vec![0.0f32; count];
        assert!(s.brick_texels_dependent(as_bytes(&data), &desc(n, 2), 0, false, &mut short).is_err());
        let mut rgba = vec![0.0f32; 4 * 16 * 16];
        s.composite(
            &h,
            &camera,
            as_bytes(&data),
            &desc(n, 2),
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0],
            &[0.0, 0.0, 1.0, 0.5],
            false,
            &[1.0, 1.0, 1.0, 0.0],
            16,
            16,
            &mut rgba,
        )
        .unwrap();
        // The left half (x < 8) is transparent, the right half red-ish (colour ramp near 1).
        let at = |x: usize, y: usize| &rgba[4 * (x + 16 * y)..4 * (x + 16 * y) + 4];
        assert_eq!(at(2, 8)[3], 0.0);
        assert!(at(13, 8)[3] > 0.5 && at(13, 8)[0] > at(13, 8)[2], "{:?}", at(13, 8));
        let one: Vec<f32> = data.iter().step_by(2).copied().collect();
        let e = build_dependent_with(as_bytes(&one), &desc(n, 1), 4, &mut |_| true).unwrap_err();
        assert!(e.contains("2-component") && e.contains("has 1"), "{e}");
        let three: Vec<f32> = one.iter().flat_map(|&v| [v, v, v]).collect();
        let e = build_dependent_with(as_bytes(&three), &desc(n, 3), 4, &mut |_| true).unwrap_err();
        assert!(e.contains("4-component (RGBA)") && e.contains("has 3") && e.contains("RGB without opacity"), "{e}");
        let e = s.brick_texels_rgba(as_bytes(&data), &desc(n, 2), 0, false, &mut out, &mut []).unwrap_err();
        assert!(e.contains("two dependent fields"), "{e}");
    }
}
