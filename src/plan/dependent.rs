//! Planning a volume with dependent components (VTK's
//! `IndependentComponentsOff`), as VTK 9.2's GPU ray caster draws it:
//!
//! - two fields (a 2-component array, ParaView's *Use Separate Opacity
//!   Array*): each sample's colour is the colour function at field 0 and
//!   its opacity the scalar opacity function at field 1 (`computeColor`:
//!   the colour table at `scalar.x`; `computeOpacity`: the opacity table at
//!   `scalar.y`; the gradient, for shading and gradient opacity, of
//!   component 0); [`Plan::dependent`], effect `dependent-components`;
//! - four fields (an RGBA array, ParaView's *Map Scalars* off with *Multi
//!   Components Mapping*): the colour is fields 0, 1, 2 themselves, read
//!   as VTK 9.2 reads them ([`crate::transfer::direct_colour`];
//!   `computeColor`: `scalar.xyz`), the opacity the scalar opacity function
//!   at field 3's `v'` (`computeOpacity`: the opacity table at `scalar.w`),
//!   the gradient field 0's (`computeLighting(.., 0, ..)`); [`Plan::rgba`],
//!   effect `rgba-components`.
//!
//! The planner runs either only for a volume of that many fields drawn in
//! Composite (first of [`Plan::effects`]); a single-field scene, or another
//! blend mode, plans nothing of it. The selection is made on the combined
//! tree ([`DependentOctree`](crate::octree::DependentOctree),
//! [`RgbaOctree`](crate::octree::RgbaOctree)); the textures carry every
//! field ([`crate::render::dependent`], [`crate::render::rgba`]).

use super::draw_list::{effects, DrawList, Plan, DEPENDENT_EFFECT, RGBA_COMPONENTS_EFFECT};
use super::BlendMode;
use crate::data::grid::ScalarType;

/// The two-field effect's name in [`Plan::effects`].
pub const EFFECT: &str = DEPENDENT_EFFECT;

/// The four-field (RGBA) effect's name in [`Plan::effects`].
pub const RGBA_EFFECT: &str = RGBA_COMPONENTS_EFFECT;

/// How many fields a volume's samples read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fields {
    /// One field through the transfer function.
    One,
    /// Colour field and opacity field.
    Two,
    /// Red, green, blue and the opacity field.
    Rgba,
}

/// Whether a plan draws two dependent fields: the volume has them
/// (`two_fields`), and the plan draws a volume in Composite.
pub fn plans_dependent(plan: &Plan, two_fields: bool) -> bool {
    two_fields && plan.volume && plan.blend.mode == BlendMode::Composite
}

/// `list` planned for a volume of one field (`two_fields` false: the plan
/// runs nothing of this) or of two dependent fields: [`plan_fields`].
pub fn plan_dependent(list: DrawList, two_fields: bool) -> DrawList {
    plan_fields(list, if two_fields { Fields::Two } else { Fields::One })
}

/// `list` planned for a volume of `fields`: [`Plan::dependent`] (two),
/// [`Plan::rgba`] (four) and [`Plan::effects`] set, or cleared (one: the
/// plan runs nothing of this). Dependent fields take precedence over a 2D
/// transfer function, which classifies one field (the mapper warns).
pub fn plan_fields(mut list: DrawList, fields: Fields) -> DrawList {
    let composite = list.plan.volume && list.plan.blend.mode == BlendMode::Composite;
    list.plan.dependent = composite && fields == Fields::Two;
    list.plan.rgba = composite && fields == Fields::Rgba;
    if list.plan.dependent || list.plan.rgba {
        // A 2D transfer function classifies one field: not with two or four.
        list.plan.transfer_2d = false;
        list.transfer_2d = None;
    }
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}

/// Bytes a GPU texture holds per texel of an RGBA volume of `scalar`
/// values, as uploaded: RGBA8 (4 bytes, exact) for u8, as VTK uploads an
/// `unsigned char` array; four 32-bit floats (16 bytes) otherwise. The
/// selection's budget counts these.
pub fn rgba_texel_bytes(scalar: ScalarType) -> usize {
    match scalar {
        ScalarType::U8 => 4,
        _ => 16,
    }
}
