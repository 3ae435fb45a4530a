//! An RGBA volume across the bridge (VTK's `IndependentComponentsOff` on a
//! 4-component array; ParaView's *Map Scalars* off with *Multi Components
//! Mapping* on): the octrees of the four components
//! ([`crate::octree::RgbaOctree`]), their four-channel brick texels (RGBA8
//! for u8 data, RGBA32F otherwise) and the CPU compositor's picture. The
//! host's array is borrowed whole, nothing is copied or changed.

use super::grid::{grid_of, grid_unscanned, same_image};
use super::guard::{guarded, write_pixels, Bridged};
use super::octree::{next_id, HybridOctreeHandle};
use super::render::SelectionHandle;
use super::GridDesc;
use crate::data::grid::ScalarType;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::hybrid::HybridOctree;
use crate::octree::{BuildOptions, RgbaOctree};
use crate::plan::DrawList;
use crate::render::rgba::{brick_texels_rgba_f32_into, brick_texels_rgba_u8_into, composite_rgba, upload_rgba};
use crate::transfer::direct_colour::RgbaScale;
use crate::transfer::TransferFunction;

/// The four components of a 4-component image; `desc.component` is not read.
pub(crate) fn fields<'a>(bytes: &'a [u8], desc: &GridDesc, scan: bool) -> Result<[Grid<'a>; 4]> {
    if desc.components != 4 {
        return Err(Error::InvalidArgument(format!(
            "an RGBA volume is read from a 4-component array; this one has {}: give 4 components, 2 for \
             (colour, opacity), or turn IndependentComponents on and choose a component",
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
    Ok([of(0)?, of(1)?, of(2)?, of(3)?])
}

/// Builds the four components' octrees ([`RgbaOctree::build_with_progress`]):
/// the handle's volume is component 0's tree (the gradient's field), its
/// `dependent` tree the combined one.
pub(crate) fn build_rgba(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Box<HybridOctreeHandle>> {
    let f = fields(bytes, desc, true)?;
    let options = BuildOptions { leaf_size: leaf_size as usize };
    let built = RgbaOctree::build_with_progress([&f[0], &f[1], &f[2], &f[3]], &options, progress)?;
    let scalar = f[3].samples().scalar_type();
    Ok(Box::new(HybridOctreeHandle {
        hybrid: HybridOctree::volume_only(built.red),
        shape: *f[3].shape(),
        input_bytes: f[3].input_bytes(),
        nan_samples: f.iter().map(Grid::nan_count).sum(),
        scalar_type: scalar,
        dependent: Some(built.combined),
        rgba: Some(built.scale),
        selector: Default::default(),
        medium: Default::default(),
        id: next_id(),
        surface_id: 0,
    }))
}

/// VTK's reading of a texture read `t` of an RGBA volume of `scalar` data:
/// the colour channels' `s = scale t + bias` (the three scales, then the
/// three biases), then channel a's `v' = scale t + bias` (before the
/// table's clamp). RGBA8 reads `t = v / 255` of u8 data; RGBA32F reads the
/// values in r, g, b and `v'` itself in a ([`SelectionHandle::brick_texels_rgba`]).
pub(crate) fn texel_reading(scale: &RgbaScale, scalar: ScalarType) -> Vec<f64> {
    let per_texel = if scalar == ScalarType::U8 { 255.0 } else { 1.0 };
    let (a, b) = if scalar == ScalarType::U8 { scale.opacity_affine() } else { (1.0 / per_texel, 0.0) };
    let rgb = scale.rgb;
    rgb.iter().map(|s| s.scale * per_texel).chain(rgb.iter().map(|s| s.bias)).chain([a * per_texel, b]).collect()
}

impl SelectionHandle {
    /// Brick `brick`'s texels of the four components (see the bridge's
    /// `brick_texels_rgba`), with the gradient border when `bordered`:
    /// `decoded` holds the values of r, g, b and `v'` of a (what the block
    /// ranges are measured on, and RGBA32F uploads), `encoded` the RGBA8
    /// bytes of u8 data.
    pub(crate) fn brick_texels_rgba(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        brick: usize,
        bordered: bool,
        decoded: &mut [f32],
        encoded: &mut [u8],
    ) -> Bridged<()> {
        guarded(|| {
            let Some(scale) = self.rgba else {
                return Err(Error::InvalidArgument(if self.dependent {
                    "this selection was made from two dependent fields: read its texels with brick_texels_dependent"
                        .into()
                } else {
                    "this selection was made from one field: read its texels with brick_texels".into()
                }));
            };
            let f = fields(bytes, desc, false)?;
            same_image(&self.shape, &f[3])?;
            let four = [&f[0], &f[1], &f[2], &f[3]];
            let b = &self.selected_brick(brick)?;
            brick_texels_rgba_f32_into(four, b, bordered, decoded)?;
            if let Some(i) = decoded.iter().position(|v| v.is_infinite()) {
                return Err(Error::InvalidArgument(format!(
                    "brick {brick} holds an infinite value (texel {}, component {}): the image changed since the \
                     octree was built, or its values exceed a 32-bit float; fix the values and rebuild it",
                    i / 4,
                    i % 4
                )));
            }
            for quad in decoded.chunks_exact_mut(4) {
                quad[3] = scale.opacity_value(f64::from(quad[3])) as f32;
            }
            match f[3].samples().scalar_type() {
                ScalarType::U8 => brick_texels_rgba_u8_into(four, b, bordered, encoded),
                _ if encoded.is_empty() => Ok(()),
                other => Err(Error::InvalidArgument(format!(
                    "{} encoded bytes for a {other:?} RGBA volume, uploaded as RGBA32F from the decoded floats: \
                     pass an empty buffer",
                    encoded.len()
                ))),
            }
        })
    }
}

/// The CPU compositor's picture of an RGBA DrawList into `rgba`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn composite_into(
    list: &DrawList,
    scale: RgbaScale,
    bytes: &[u8],
    desc: &GridDesc,
    tf: &TransferFunction,
    width: usize,
    height: usize,
    rgba: &mut [f32],
) -> Result<()> {
    let f = fields(bytes, desc, true)?;
    let textures = upload_rgba([&f[0], &f[1], &f[2], &f[3]], scale, list)?;
    let image = composite_rgba(&textures, list, tf, width, height)?;
    write_pixels(&image.rgba, rgba)
}

#[cfg(test)]
mod tests {
    use super::super::dependent::build_dependent_with;
    use super::super::test_support::select_desc;
    use super::super::{CameraDesc, ScalarType as BridgeType};
    use super::*;

    /// u8 RGBA on `n^3`: red a ramp along x, green 60, blue 200 - red,
    /// alpha 255 in the half x >= 8, 0 elsewhere.
    fn rgba_u8(n: usize) -> Vec<u8> {
        let mut data = Vec::new();
        for _k in 0..n {
            for _j in 0..n {
                for i in 0..n {
                    let r = (i * 255 / (n - 1)) as u8;
                    data.extend([r, 60, 200 - r.min(200), if i >= 8 { 255 } else { 0 }]);
                }
            }
        }
        data
    }

    fn desc(n: usize, scalar_type: BridgeType) -> GridDesc {
        GridDesc { scalar_type, dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3], components: 4, component: 0 }
    }

    /// The bridge builds an RGBA volume from a 4-component image: selects on
    /// alpha (the transparent half skipped) at 4 bytes a texel (RGBA8) for
    /// u8 and 16 for f32, says `rgba-components` with VTK's colour scaling,
    /// gives RGBA8 bytes and the decoded floats, and draws the data's
    /// colours; texels of the wrong kind or buffer length are refused.
    #[test]
    fn bridge_draws_rgba_volumes() {
        let n = 17;
        let data = rgba_u8(n);
        let h = build_dependent_with(&data, &desc(n, BridgeType::U8), 4, &mut |_| true).unwrap();
        let mut select = select_desc(1 << 30);
        select.opacity_points = vec![0.0, 0.0, 255.0, 0.5];
        let s = h.select_bricks(&select).unwrap();
        assert!(s.rgba.is_some() && !s.dependent);
        let summary = s.summary().unwrap();
        assert!(summary.skipped > 0, "{summary:?}");
        assert!(s.selection.bricks.iter().all(|b| b.hi[0] >= 8));
        let texels: usize = s.selection.bricks.iter().map(|b| b.texels.iter().product::<usize>()).sum();
        assert_eq!(summary.texture_bytes, 4 * texels, "RGBA8: 4 bytes a texel");
        let camera = CameraDesc {
            position: [8.0, 8.0, 60.0],
            focal_point: [8.0; 3],
            view_up: [0.0, 1.0, 0.0],
            parallel: true,
            parallel_scale: 10.0,
            view_angle: 30.0,
        };
        let list = s.draw_list(&h, &camera, 0.0).unwrap();
        assert_eq!(list.effects, "rgba-components");
        assert_eq!((list.texel_bytes, list.texel_format, list.texel_scale), (4, 4, 255.0));
        // RGBA8: t = v / 255 is the colour itself; alpha over [0, 255]: v' = 255 t.
        assert_eq!(list.rgba_reading.len(), 8);
        assert!(list.rgba_reading[..6].iter().zip([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]).all(|(a, b)| (a - b).abs() < 1e-12));
        assert!(
            (list.rgba_reading[6] - 255.0).abs() < 1e-9 && list.rgba_reading[7].abs() < 1e-12,
            "{:?}",
            list.rgba_reading
        );
        let b = &s.selection.bricks[0];
        let count: usize = b.texels.iter().product();
        let (mut decoded, mut encoded) = (vec![0.0f32; 4 * count], vec![0u8; 4 * count]);
        s.brick_texels_rgba(&data, &desc(n, BridgeType::U8), 0, false, &mut decoded, &mut encoded).unwrap();
        let at = 4 * (b.lo[0] + n * (b.lo[1] + n * b.lo[2]));
        assert_eq!(&encoded[..4], &data[at..at + 4]);
        assert!(encoded.iter().zip(&decoded).all(|(&e, &d)| f32::from(e) == d));
        assert!(s.brick_texels_rgba(&data, &desc(n, BridgeType::U8), 0, false, &mut decoded, &mut []).is_err());
        let mut rgba = vec![0.0f32; 4 * 16 * 16];
        // A colour function that would paint magenta: the data's colours show instead.
        s.composite(
            &h,
            &camera,
            &data,
            &desc(n, BridgeType::U8),
            &[0.0, 1.0, 0.0, 1.0, 255.0, 1.0, 0.0, 1.0],
            &[0.0, 0.0, 255.0, 0.5],
            false,
            &[1.0, 1.0, 1.0, 0.0],
            16,
            16,
            &mut rgba,
        )
        .unwrap();
        let px = |x: usize, y: usize| &rgba[4 * (x + 16 * y)..4 * (x + 16 * y) + 4];
        assert_eq!(px(2, 8)[3], 0.0);
        let p = px(13, 8);
        assert!(p[3] > 0.5, "{p:?}");
        // Straight colour: green 60 / 255 (VTK reads u8 as GL does); red high, blue low on the right.
        let green = p[1] / p[3];
        assert!((f64::from(green) - 60.0 / 255.0).abs() < 1e-3, "{p:?}");
        assert!(p[0] > p[2], "{p:?}");

        // f32: 16 bytes a texel, no encoded bytes.
        let floats: Vec<f32> = data.iter().map(|&v| f32::from(v) / 255.0).collect();
        let bytes = super::super::test_support::as_bytes(&floats);
        let h = build_dependent_with(bytes, &desc(n, BridgeType::F32), 4, &mut |_| true).unwrap();
        select.opacity_points = vec![0.0, 0.0, 1.0, 0.5];
        let s = h.select_bricks(&select).unwrap();
        let summary = s.summary().unwrap();
        let texels: usize = s.selection.bricks.iter().map(|b| b.texels.iter().product::<usize>()).sum();
        assert_eq!(summary.texture_bytes, 16 * texels, "RGBA32F: 16 bytes a texel");
        let list = s.draw_list(&h, &camera, 0.0).unwrap();
        assert_eq!((list.texel_bytes, list.texel_format, list.texel_scale), (16, 1, 1.0));
        let count: usize = s.selection.bricks[0].texels.iter().product();
        let mut decoded = vec![0.0f32; 4 * count];
        s.brick_texels_rgba(bytes, &desc(n, BridgeType::F32), 0, false, &mut decoded, &mut []).unwrap();
        let e =
            s.brick_texels_rgba(bytes, &desc(n, BridgeType::F32), 0, false, &mut decoded, &mut [0u8; 4]).unwrap_err();
        assert!(e.contains("empty buffer"), "{e}");
        let mut pairs = vec![0.0f32; 2 * count];
        let e = s.brick_texels_dependent(bytes, &desc(n, BridgeType::F32), 0, false, &mut pairs).unwrap_err();
        assert!(e.contains("brick_texels_rgba"), "{e}");
    }
}
