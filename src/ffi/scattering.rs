//! Volumetric scattering across the bridge ([`crate::render::scattering`]):
//! the parameters a selection's DrawLists are planned with, what the brick
//! shader's `HO_SCATTERING` variant reads, and the shadow volume's texels.

use super::grid::{grid_of, same_image};
use super::guard::{check_len, guarded, Bridged};
use super::{GridDesc, ScatteringDesc, ScatteringFrameDesc};
use crate::render::scattering::{
    reach_extent, sample_distance, shadow_dims, shadow_texture_transform, texture_space, ShadowVolume, MAX_SHADOW_STEPS,
};
use crate::transfer::Scattering;

impl super::SelectionHandle {
    /// The scattering of the DrawLists and pictures made after this call,
    /// over this selection's value range (checked).
    pub(crate) fn set_scattering(&self, desc: &ScatteringDesc) -> Bridged<()> {
        guarded(|| {
            let made = Scattering {
                blending: desc.blending,
                reach: desc.reach,
                anisotropy: desc.anisotropy,
                headlight_ambient: desc.headlight_ambient,
                value_range: [self.value_range.0, self.value_range.1],
                sample_distance: desc.sample_distance,
            };
            made.check()?;
            *self.scattering.lock().unwrap_or_else(|e| e.into_inner()) = Some(made).filter(Scattering::runs);
            Ok(())
        })
    }

    /// What the brick shader reads for the scattering last set (zeros before one).
    pub(crate) fn scattering_frame(&self) -> Bridged<ScatteringFrameDesc> {
        guarded(|| {
            let shape = self.shape;
            let stored = *self.scattering.lock().unwrap_or_else(|e| e.into_inner());
            let s = stored.unwrap_or(Scattering {
                blending: 0.0,
                reach: 0.0,
                anisotropy: 0.0,
                headlight_ambient: [0.0; 3],
                value_range: [self.value_range.0, self.value_range.1],
                sample_distance: 0.0,
            });
            let d0 = crate::data::spacing::reference_spacing(&shape);
            let distance = sample_distance(&s, d0);
            let (corner, size) = texture_space(&shape);
            let dims = shadow_dims(shape.dims);
            let (scale, shift) = shadow_texture_transform(shape.dims, dims);
            let span = s.value_range[1] - s.value_range[0];
            Ok(ScatteringFrameDesc {
                blending: s.blending,
                anisotropy: s.anisotropy,
                headlight_ambient: s.headlight_ambient,
                gradient_scale: if span > 0.0 { 2.0 / span } else { 0.0 },
                texture_corner: corner,
                texture_size: size,
                extent: reach_extent(&s, &shape, distance),
                distance,
                to_vtk: distance / d0,
                shadow_dims: dims,
                shadow_scale: scale,
                shadow_shift: shift,
                max_steps: MAX_SHADOW_STEPS,
            })
        })
    }

    /// The shadow volume's values of the image the octree was built from
    /// (`texels`: the product of `scattering_frame().shadow_dims` floats, x fastest).
    pub(crate) fn shadow_volume_texels(&self, bytes: &[u8], desc: &GridDesc, texels: &mut [f32]) -> Bridged<()> {
        guarded(|| {
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let shadow = ShadowVolume::new(&grid)?;
            check_len("the shadow volume", texels, shadow.values.len())?;
            texels.copy_from_slice(&shadow.values);
            Ok(())
        })
    }
}
