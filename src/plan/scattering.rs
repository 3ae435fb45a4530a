//! Planning volumetric scattering ([`crate::transfer::scattering`], VTK
//! 9.2's `VolumetricScatteringBlending`, `GlobalIlluminationReach`,
//! `ScatteringAnisotropy`).
//!
//! VTK casts scattered rays when the volume is shaded (`Shade` on), with at
//! least one light, and a blending `B > 0`; anything else leaves the picture
//! as it was, so the planner does not run it. A reach of 0 is not a no-op in
//! VTK (its shadow rays are then one sample long and the blend still
//! applies), so it is run. The planner runs it in Composite (the blend
//! mode of ParaView's Volume shading; under the others it is not drawn, nor
//! with two or four dependent fields or a 2D transfer function, whose opacity the
//! shadow rays would have to classify differently; plan it after both) and
//! names it [`EFFECT`] in [`Plan::effects`], after `shading`; the DrawList
//! carries the parameters and the lights in world space
//! ([`DrawList::scattering`]), and the gradient is taken for every sample
//! (VTK's blend weight reads its length).

use super::draw_list::{effects, DrawList, Plan};
use super::BlendMode;
use crate::transfer::lighting::{Lighting, Lights};
use crate::transfer::scattering::LitScattering;
use crate::transfer::Scattering;

/// The effect's name in [`Plan::effects`].
pub const EFFECT: &str = super::draw_list::SCATTERING_EFFECT;

/// Whether a plan scatters light for this shading (`lighting`: the scene's
/// Shade, `None` when off) and these parameters (module documentation).
pub fn scatters(plan: &Plan, lighting: Option<&Lighting>, scattering: Option<&Scattering>) -> bool {
    let lit = lighting.is_some_and(|l| match &l.lights {
        Lights::Headlight { .. } => true,
        Lights::Directional(lights) => !lights.is_empty(),
    });
    plan.volume
        && plan.blend.mode == BlendMode::Composite
        && !plan.dependent
        && !plan.rgba
        && !plan.transfer_2d
        && lit
        && scattering.is_some_and(Scattering::runs)
}

/// `list` planned for `scattering` under `lighting` (lights in world or view
/// space, for the list's camera): [`Plan::scattering`], its effect and
/// [`DrawList::scattering`] set, or cleared when it is not run.
///
/// # Errors
///
/// [`crate::Error::InvalidArgument`] for a bad parameter ([`Scattering::check`])
/// or lighting ([`Lighting::check`]).
pub fn plan_scattering(
    mut list: DrawList,
    lighting: Option<&Lighting>,
    scattering: Option<&Scattering>,
) -> crate::Result<DrawList> {
    if let Some(s) = scattering {
        s.check()?;
    }
    if let Some(l) = lighting {
        l.check()?;
    }
    list.plan.scattering = scatters(&list.plan, lighting, scattering);
    list.scattering = match (lighting, scattering) {
        (Some(l), Some(s)) if list.plan.scattering => {
            Some(LitScattering { scattering: *s, lighting: l.in_world(&list.camera) })
        }
        _ => None,
    };
    list.plan.effects = effects(&list.plan, list.region.as_ref());
    Ok(list)
}
