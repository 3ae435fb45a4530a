//! Drawing an RGBA volume with dependent components (the plan's
//! `rgba-components`, [`crate::plan::dependent`]): VTK 9.2's GPU ray caster
//! on a 4-component array with `IndependentComponentsOff`,
//!
//! ```text
//! c(x) = clamp((s_0(f_0(x)), s_1(f_1(x)), s_2(f_2(x))), 0, 1)   (computeColor: scalar.xyz,
//!                                                               clamped after the shading)
//! a(x) = scalar opacity function (v'(f_3(x)))                   (computeOpacity: the opacity table at scalar.w)
//! g(x) = grad f_0(x)                                            (computeLighting(.., 0, ..): shading, gradient opacity)
//! ```
//!
//! `s_k`, `v'` VTK 9.2's reading of the components by their type and
//! ranges ([`crate::transfer::direct_colour`]); the fields are
//! interpolated, then read (the reading is affine: the same as reading the
//! texels). The colour transfer function is not used.
//!
//! Textures carry the four fields: one [`Textures`] per field, the same
//! bricks and texel positions. A GPU executor uploads them as one
//! four-channel texture ([`brick_texels_rgba_f32_into`], or for u8 data
//! [`brick_texels_rgba_u8_into`]: RGBA8, what VTK uploads, exact), whose
//! bytes per texel [`crate::plan::dependent::rgba_texel_bytes`] gives; the
//! selection counts those. The CPU compositor and the reference caster
//! read the red and the gradient from field 0 (it is their texture or
//! grid), green, blue and the opacity from fields 1, 2, 3; everything else
//! is theirs unchanged.

use super::check::{check_list, check_size};
use super::compositor::execute_counted;
use super::fields::OtherFields;
use super::image::Image;
use super::reference::{reference_fields, ReferenceOptions};
use super::texture::{brick_texels_f32_bordered_into, brick_texels_f32_into, upload, upload_field, Texels, Textures};
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, Samples};
use crate::geometry::camera::Camera;
use crate::plan::select::Brick;
use crate::plan::{Blend, DrawList};
use crate::transfer::direct_colour::RgbaScale;
use crate::transfer::TransferFunction;

/// The four fields' textures of a DrawList's bricks, stored alike (`f64`
/// for all when any needs it), and the colour components' scaling.
#[derive(Debug, Clone)]
pub struct RgbaTextures {
    /// Fields 0, 1, 2, 3 (red with the gradient's lattice differences, green, blue, alpha).
    pub fields: [Textures; 4],
    /// VTK's reading of the fields.
    pub scale: RgbaScale,
}

impl RgbaTextures {
    /// Bytes of texel data of the four fields (the CPU compositor's copy).
    pub fn bytes(&self) -> usize {
        self.fields.iter().map(Textures::bytes).sum()
    }
}

/// The four fields are components of one image.
fn check_fields(fields: [&Grid<'_>; 4]) -> Result<()> {
    if fields.iter().any(|f| f.shape() != fields[3].shape()) {
        return Err(Error::InvalidArgument(
            "the RGBA components have different dims, spacing or origin: give four components of one image".into(),
        ));
    }
    Ok(())
}

/// The list draws an RGBA volume.
fn check_rgba(list: &DrawList) -> Result<()> {
    if list.bricks.is_empty() || list.plan.rgba {
        Ok(())
    } else {
        Err(Error::InvalidArgument(
            "the DrawList does not plan an RGBA volume (plan::dependent::plan_fields with Fields::Rgba, Composite): \
             draw it with the compositor of its fields"
                .into(),
        ))
    }
}

/// Uploads `list`'s bricks from the four fields (see [`super::texture::upload`]);
/// field 0 carries the gradient's lattice differences.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for fields of different images, a texel
/// format other than float32, and as [`upload`].
pub fn upload_rgba(fields: [&Grid<'_>; 4], scale: RgbaScale, list: &DrawList) -> Result<RgbaTextures> {
    check_fields(fields)?;
    if list.texel.format != crate::plan::texel_format::TexelFormat::Float32 {
        return Err(Error::InvalidArgument(format!(
            "RGBA volumes are drawn from float32 texels (u8 data exactly), not {}: resolve the list's texel format \
             as float32",
            list.texel.format.name()
        )));
    }
    let fields = [
        upload(fields[0], list)?,
        upload_field(fields[1], list, false)?,
        upload_field(fields[2], list, false)?,
        upload_field(fields[3], list, false)?,
    ];
    if fields.iter().any(|t| matches!(t.texels, Texels::F64(_))) {
        return Ok(RgbaTextures { fields: fields.map(Textures::widened), scale });
    }
    Ok(RgbaTextures { fields, scale })
}

/// The CPU compositor ([`super::compositor`]) on an RGBA DrawList (module documentation).
///
/// # Errors
///
/// [`Error::InvalidArgument`] when the list does not plan an RGBA volume
/// or the textures are not its bricks', and as
/// [`super::compositor::composite_textures`].
pub fn composite_rgba(
    textures: &RgbaTextures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
) -> Result<Image> {
    composite_rgba_counted(textures, list, tf, width, height).map(|(image, _)| image)
}

/// [`composite_rgba`], and the work it did.
pub(crate) fn composite_rgba_counted(
    textures: &RgbaTextures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
) -> Result<(Image, super::compositor::Counts)> {
    check_size(width, height)?;
    check_rgba(list)?;
    let [r, g, b, a] = &textures.fields;
    check_list(list, &r.shape, None)?;
    for t in &textures.fields {
        t.check(list)?;
    }
    let other = OtherFields::Rgba([g, b], a, textures.scale);
    execute_counted(r, Some(other), None, list, tf, width, height, None, None)
}

/// The full-resolution reference ([`super::reference::reference_blend`],
/// Composite) of an RGBA volume: colour from fields 0, 1, 2 and opacity
/// from field 3 read by `scale`, the gradient field 0's.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for fields of different images, and as [`super::reference::reference`].
pub fn reference_rgba(
    fields: [&Grid<'_>; 4],
    scale: RgbaScale,
    tf: &TransferFunction,
    camera: &Camera,
    width: usize,
    height: usize,
    options: &ReferenceOptions<'_>,
) -> Result<Image> {
    check_fields(fields)?;
    let other = OtherFields::Rgba([fields[1], fields[2]], fields[3], scale);
    reference_fields(fields[0], Some(other), tf, camera, width, height, options, &Blend::default())
}

/// The texels of brick `brick`, `bordered` or not, as one field's `f32`s.
fn field_texels(grid: &Grid<'_>, brick: &Brick, bordered: bool, out: &mut [f32]) -> Result<()> {
    if bordered {
        brick_texels_f32_bordered_into(grid, brick, out)
    } else {
        brick_texels_f32_into(grid, brick, out)
    }
}

/// Texels of `brick`, the gradient border included when `bordered`.
fn texel_count(brick: &Brick, bordered: bool) -> usize {
    brick.texels.iter().map(|n| n + 2 * usize::from(bordered)).product()
}

/// Brick `brick`'s texels of the four fields as `f32` quadruples
/// (`[r_0, g_0, b_0, a_0, r_1, ...]`, texels x fastest as
/// [`brick_texels_f32_into`]), with the gradient border when `bordered`:
/// what a GPU executor uploads as one RGBA32F texture. `texels` holds four
/// times the brick's texel count.
///
/// # Errors
///
/// As [`brick_texels_f32_into`], for fields of different images, and for a buffer of another length.
pub fn brick_texels_rgba_f32_into(
    fields: [&Grid<'_>; 4],
    brick: &Brick,
    bordered: bool,
    texels: &mut [f32],
) -> Result<()> {
    check_fields(fields)?;
    let count = texel_count(brick, bordered);
    check_buffer(texels.len(), count, brick, "floats")?;
    let mut field = vec![0.0f32; count];
    for (channel, grid) in fields.iter().enumerate() {
        field_texels(grid, brick, bordered, &mut field)?;
        for (quad, &v) in texels.chunks_exact_mut(4).zip(&field) {
            quad[channel] = v;
        }
    }
    Ok(())
}

/// [`brick_texels_rgba_f32_into`] for u8 fields, as bytes (RGBA8, exact):
/// what VTK uploads for an `unsigned char` array.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for fields that are not u8, and as
/// [`brick_texels_rgba_f32_into`].
pub fn brick_texels_rgba_u8_into(
    fields: [&Grid<'_>; 4],
    brick: &Brick,
    bordered: bool,
    texels: &mut [u8],
) -> Result<()> {
    check_fields(fields)?;
    if fields.iter().any(|f| !matches!(f.samples(), Samples::U8(_))) {
        return Err(Error::InvalidArgument(format!(
            "RGBA8 texels are read from an unsigned char image, not {:?}: read float texels",
            fields[0].samples().scalar_type()
        )));
    }
    let count = texel_count(brick, bordered);
    check_buffer(texels.len(), count, brick, "bytes")?;
    let mut field = vec![0.0f32; count];
    for (channel, grid) in fields.iter().enumerate() {
        field_texels(grid, brick, bordered, &mut field)?;
        for (quad, &v) in texels.chunks_exact_mut(4).zip(&field) {
            // An exact u8 value read as f32.
            quad[channel] = v as u8;
        }
    }
    Ok(())
}

/// A buffer of `len` holds four channels of `count` texels.
fn check_buffer(len: usize, count: usize, brick: &Brick, unit: &str) -> Result<()> {
    if len != 4 * count {
        return Err(Error::InvalidArgument(format!(
            "a buffer of {len} {unit} for brick (node {}) of {count} four-channel texels: give {}",
            brick.node.0,
            4 * count
        )));
    }
    Ok(())
}
