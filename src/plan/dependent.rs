//! Planning a two-field volume with dependent components (VTK's
//! `IndependentComponentsOff` on a 2-component array, ParaView's *Use
//! Separate Opacity Array*): each sample's colour is the colour function
//! at field 0 and its opacity the scalar opacity function at field 1, as
//! VTK 9.2's GPU ray caster computes them (`computeColor`: the colour table
//! at `scalar.x`; `computeOpacity`: the opacity table at `scalar.y`; the
//! gradient, for shading and gradient opacity, of component 0).
//!
//! The planner runs it only for a volume of two fields drawn in Composite
//! ([`Plan::dependent`], effect `dependent-components`, first of
//! [`Plan::effects`]); a single-field scene, or another blend mode, plans
//! nothing of it. The selection is made on the
//! [`DependentOctree`](crate::octree::DependentOctree)'s combined tree; the
//! textures carry both fields ([`crate::render::dependent`]).

use super::draw_list::{effects, DrawList, Plan, DEPENDENT_EFFECT};
use super::BlendMode;

/// The effect's name in [`Plan::effects`].
pub const EFFECT: &str = DEPENDENT_EFFECT;

/// Whether a plan draws two dependent fields: the volume has them
/// (`two_fields`), and the plan draws a volume in Composite.
pub fn plans_dependent(plan: &Plan, two_fields: bool) -> bool {
    two_fields && plan.volume && plan.blend.mode == BlendMode::Composite
}

/// `list` planned for a volume of one field (`two_fields` false: the plan
/// runs nothing of this) or of two dependent fields: [`Plan::dependent`]
/// and [`Plan::effects`] set, or cleared. Two dependent fields take
/// precedence over a 2D transfer function, which classifies one field (the
/// mapper warns).
pub fn plan_dependent(mut list: DrawList, two_fields: bool) -> DrawList {
    list.plan.dependent = plans_dependent(&list.plan, two_fields);
    if list.plan.dependent {
        // A 2D transfer function classifies one field: not with two.
        list.plan.transfer_2d = false;
        list.transfer_2d = None;
    }
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    list
}
