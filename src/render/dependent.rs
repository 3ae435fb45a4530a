//! Drawing two fields with dependent components (the plan's
//! `dependent-components`, [`crate::plan::dependent`]): VTK 9.2's GPU ray
//! caster on a 2-component array with `IndependentComponentsOff`,
//!
//! ```text
//! c(x) = colour function (f_0(x))          (computeColor: the colour table at scalar.x)
//! a(x) = scalar opacity function (f_1(x))  (computeOpacity: the opacity table at scalar.y)
//! g(x) = grad f_0(x)                       (computeGradient of component 0: shading, gradient opacity)
//! ```
//!
//! each field in its own values (VTK maps each component to its table
//! through that component's range; the functions here are over values).
//!
//! Textures carry both fields: one [`Textures`] per field, the same bricks
//! and texel positions, so a texel coordinate reads both
//! ([`DependentTextures::bytes`] counts both; a GPU executor uploads them as
//! one two-channel texture, [`brick_texels_dependent_f32_into`], field 0 in
//! the first channel). The CPU compositor and the reference caster read
//! the colour from field 0 and the opacity from field 1; everything else
//! (slices, opacity correction, effects) is theirs unchanged.

use super::check::{check_list, check_size};
use super::compositor::execute_counted;
use super::fields::OtherFields;
use super::image::Image;
use super::reference::{reference_fields, ReferenceOptions};
use super::texture::{brick_texels_f32_bordered_into, brick_texels_f32_into, upload, upload_field, Texels, Textures};
use crate::base::error::{Error, Result};
use crate::data::grid::Grid;
use crate::geometry::camera::Camera;
use crate::plan::select::Brick;
use crate::plan::{Blend, DrawList};
use crate::transfer::TransferFunction;

/// The two fields' textures of a DrawList's bricks, stored alike (`f64`
/// for both when either needs it).
#[derive(Debug, Clone)]
pub struct DependentTextures {
    /// Field 0's (the colour field).
    pub colour: Textures,
    /// Field 1's (the opacity field).
    pub opacity: Textures,
}

impl DependentTextures {
    /// Bytes of texel data of both fields.
    pub fn bytes(&self) -> usize {
        self.colour.bytes() + self.opacity.bytes()
    }
}

/// `colour` and `opacity` are two fields of one image.
fn check_fields(colour: &Grid<'_>, opacity: &Grid<'_>) -> Result<()> {
    if colour.shape() != opacity.shape() {
        return Err(Error::InvalidArgument(
            "the colour and opacity fields have different dims, spacing or origin: give two fields of one image".into(),
        ));
    }
    Ok(())
}

/// The list draws two dependent fields.
fn check_dependent(list: &DrawList) -> Result<()> {
    if list.bricks.is_empty() || list.plan.dependent {
        Ok(())
    } else {
        Err(Error::InvalidArgument(
            "the DrawList does not plan dependent components (plan::dependent::plan_dependent with two fields, \
             Composite): draw it with the single-field compositor"
                .into(),
        ))
    }
}

/// Uploads `list`'s bricks from both fields (see [`super::texture::upload`]).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for fields of different images, and as [`upload`].
pub fn upload_dependent(colour: &Grid<'_>, opacity: &Grid<'_>, list: &DrawList) -> Result<DependentTextures> {
    check_fields(colour, opacity)?;
    if list.texel.format != crate::plan::texel_format::TexelFormat::Float32 {
        return Err(Error::InvalidArgument(format!(
            "dependent components are drawn from float32 texels, not {}: resolve the list's texel format as float32",
            list.texel.format.name()
        )));
    }
    // The gradient is the colour field's (module documentation).
    let (c, o) = (upload(colour, list)?, upload_field(opacity, list, false)?);
    let (colour, opacity) = match (&c.texels, &o.texels) {
        (Texels::F32(_), Texels::F64(_)) => (c.widened(), o),
        (Texels::F64(_), Texels::F32(_)) => (c, o.widened()),
        _ => (c, o),
    };
    Ok(DependentTextures { colour, opacity })
}

/// The CPU compositor ([`super::compositor`]) on a dependent-components
/// DrawList: colour from the colour texture, opacity from the opacity
/// texture (module documentation).
///
/// # Errors
///
/// [`Error::InvalidArgument`] when the list does not plan dependent
/// components or the textures are not its bricks', and as
/// [`super::compositor::composite_textures`].
pub fn composite_dependent(
    textures: &DependentTextures,
    list: &DrawList,
    tf: &TransferFunction,
    width: usize,
    height: usize,
) -> Result<Image> {
    check_size(width, height)?;
    check_dependent(list)?;
    check_list(list, &textures.colour.shape, None)?;
    textures.colour.check(list)?;
    textures.opacity.check(list)?;
    Ok(execute_counted(
        &textures.colour,
        Some(OtherFields::Opacity(&textures.opacity)),
        None,
        list,
        tf,
        width,
        height,
        None,
        None,
    )?
    .0)
}

/// The full-resolution reference ([`super::reference::reference_blend`],
/// Composite) of two dependent fields: colour from `colour`, opacity from
/// `opacity`, the gradient `colour`'s.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for fields of different images, and as [`super::reference::reference`].
pub fn reference_dependent(
    colour: &Grid<'_>,
    opacity: &Grid<'_>,
    tf: &TransferFunction,
    camera: &Camera,
    width: usize,
    height: usize,
    options: &ReferenceOptions<'_>,
) -> Result<Image> {
    check_fields(colour, opacity)?;
    reference_fields(colour, Some(OtherFields::Opacity(opacity)), tf, camera, width, height, options, &Blend::default())
}

/// Brick `brick`'s texels of both fields as `f32` pairs, field 0 first
/// (`[c_0, o_0, c_1, o_1, ...]`, texels x fastest as
/// [`brick_texels_f32_into`]), with the gradient border when `bordered`:
/// what a GPU executor uploads as one two-channel texture. `texels` holds
/// twice the brick's texel count.
///
/// # Errors
///
/// As [`brick_texels_f32_into`], for fields of different images, and for a buffer of another length.
pub fn brick_texels_dependent_f32_into(
    colour: &Grid<'_>,
    opacity: &Grid<'_>,
    brick: &Brick,
    bordered: bool,
    texels: &mut [f32],
) -> Result<()> {
    check_fields(colour, opacity)?;
    let count = brick.texels.iter().map(|n| n + 2 * usize::from(bordered)).product::<usize>();
    if texels.len() != 2 * count {
        return Err(Error::InvalidArgument(format!(
            "a buffer of {} floats for brick (node {}) of {count} two-field texels: give {}",
            texels.len(),
            brick.node.0,
            2 * count
        )));
    }
    let mut field = vec![0.0f32; count];
    for (grid, channel) in [(colour, 0), (opacity, 1)] {
        if bordered {
            brick_texels_f32_bordered_into(grid, brick, &mut field)?;
        } else {
            brick_texels_f32_into(grid, brick, &mut field)?;
        }
        for (pair, &v) in texels.chunks_exact_mut(2).zip(&field) {
            pair[channel] = v;
        }
    }
    Ok(())
}
