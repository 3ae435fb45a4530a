//! Volumetric scattering: VTK 9.2's model of single scattering with
//! volumetric shadows (vtkGPUVolumeRayCastMapper's
//! `VolumetricScatteringBlending` and `GlobalIlluminationReach`,
//! vtkVolumeProperty's `ScatteringAnisotropy`; ParaView's
//! `VolumetricScatteringBlending`, `GlobalIlluminationReach`,
//! `VolumeAnisotropy`), as `vtkVolumeShaderComposer.h`
//! (`ComputeLightingDeclaration`, `ComputeVolumetricShadowDec`,
//! `PhaseFunctionDeclaration`) and `vtkOpenGLGPUVolumeRayCastMapper.cxx`
//! (`in_giReach`, `in_anisotropy`, `in_volumetricScatteringBlending`) write it.
//!
//! VTK runs it only with `Shade` on, a blending `B > 0` and at least one
//! light. A sample of straight colour `c`, opacity `a` (the transfer
//! function's, before gradient opacity) and shaded colour `c_s` (the
//! gradient shading of [`super::lighting`], not yet clamped) becomes
//!
//! ```text
//! c' = clamp((1 - k) c_s + k S, 0, 1)
//! S  = sum_i [ T_i P(cos_i) kd Ld_i c + ka La_i ]
//! k  = B exp(-B |g| a)                        B < 1
//!    = (2 - B) exp(-B |g| a) + B - 1          B >= 1
//! ```
//!
//! (VTK's `vol_coef` with `in_volumetricScatteringBlending = B / 2`), where
//! `|g|` is the length of VTK's shading gradient, the central difference of
//! the value normalised to the data range over one cell (`(n(x + h) - n(x -
//! h)) / h`, [`Scattering::vtk_gradient_magnitude`]), `T_i` the transmittance
//! towards light `i` ([`shadow`](Scattering::shadow_extent)), `P` the
//! Henyey-Greenstein phase function ([`Scattering::phase`]) of the angle
//! between the light's direction of travel and the direction from the sample
//! to the eye, and `ka, kd, La_i, Ld_i` the material's and lights' ambient
//! and diffuse terms. VTK's default lighting (one headlight) is a light *at
//! the eye*: its shadow ray runs towards the camera position, `cos = -1`
//! always, and its ambient colour is the headlight's (the gradient shading
//! leaves it out, the scattering term takes it: [`Scattering::headlight_ambient`]).
//!
//! The shadow ray runs in VTK's texture space: the unit cube over the
//! volume's texels (the points' box grown by half a spacing on each side,
//! `t = (x + 1/2) / N` for index `x` of `N` points), from the sample one step
//! towards the light, in steps of the view ray's step `s0` (its sample
//! distance in texture units), up to the cube's exit and the reach
//! extent `R`, multiplying `(1 - a(v))` of each step's sample:
//!
//! ```text
//! T = prod_k (1 - a(v(p + s0 n + k s0 n))),  0 <= k s0 < min(exit, R)
//! R = (r_min - sqrt 3) (1 - reach)^0.33 + sqrt 3,   r_min = d / max_a(size_a)
//! ```
//!
//! (`d` the sample distance, `size_a` the texture's world size; `a` and the
//! opacity `a` of the blend weight are VTK's per `d`, its table's, see
//! [`Scattering::sample_distance`]). A reach of
//! 0 still casts one step (`R = r_min`): it is not a no-op.

use crate::base::error::{Error, Result};

/// VTK's `maxExtent`, the texture cube's diagonal (as VTK writes it).
pub const CUBE_DIAGONAL: f64 = 1.73205;

/// The anisotropy below which VTK's phase function is the isotropic 1.
pub const ISOTROPIC_BELOW: f64 = 0.01;

/// VolumetricScattering's parameters (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Scattering {
    /// VolumetricScatteringBlending `B` in `[0, 2]`: 0 none, 1 a blend of
    /// the surface and volume models, 2 the volume model only.
    pub blending: f64,
    /// GlobalIlluminationReach in `[0, 1]`: the shadow rays' length.
    pub reach: f64,
    /// vtkVolumeProperty's ScatteringAnisotropy `g` in `[-1, 1]`.
    pub anisotropy: f64,
    /// The headlight's ambient colour times its intensity (VTK's
    /// `in_lightAmbientColor[0]` under its default lighting).
    pub headlight_ambient: [f64; 3],
    /// The data range VTK normalises the values by (`n = (v - lo) / (hi - lo)`).
    pub value_range: [f64; 2],
    /// VTK's sample distance `d`, world units (0: the reference spacing
    /// `d0`): its opacities are per `d` (`a_d = 1 - (1 - a)^(d / d0)` of the
    /// transfer function's `a`, per `d0`), its shadow rays step by `d`.
    pub sample_distance: f64,
}

impl Scattering {
    /// Checks the ranges VTK clamps to and ParaView's domains give.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] naming the first value out of its range.
    pub fn check(&self) -> Result<()> {
        for (name, v, lo, hi) in [
            ("blending", self.blending, 0.0, 2.0),
            ("reach", self.reach, 0.0, 1.0),
            ("anisotropy", self.anisotropy, -1.0, 1.0),
        ] {
            if !(v.is_finite() && (lo..=hi).contains(&v)) {
                return Err(Error::InvalidArgument(format!(
                    "volumetric scattering: {name} {v}: give a number from {lo} to {hi}"
                )));
            }
        }
        if !self.headlight_ambient.iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "volumetric scattering: headlight ambient colour {:?}: give finite values >= 0",
                self.headlight_ambient
            )));
        }
        if !(self.sample_distance.is_finite() && self.sample_distance >= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "volumetric scattering: sample distance {}: give a finite distance >= 0 (0: the reference spacing)",
                self.sample_distance
            )));
        }
        if !(self.value_range.iter().all(|v| v.is_finite()) && self.value_range[0] <= self.value_range[1]) {
            return Err(Error::InvalidArgument(format!(
                "volumetric scattering: value range {:?}: give finite lo <= hi",
                self.value_range
            )));
        }
        Ok(())
    }

    /// Whether VTK casts scattered rays: `B > 0` (with Shade and a light,
    /// which the planner checks).
    pub fn runs(&self) -> bool {
        self.blending > 0.0
    }

    /// The Henyey-Greenstein phase function normalised to `4 pi` (VTK's
    /// `phase_function`): 1 when `|g| < 0.01`, else
    /// `(1 - g^2) / (1 + g^2 - 2 g cos)^(3/2)`.
    pub fn phase(&self, cos: f64) -> f64 {
        let g = self.anisotropy;
        if g.abs() < ISOTROPIC_BELOW {
            return 1.0;
        }
        let d = 1.0 + g * g - 2.0 * g * cos;
        (1.0 - g * g) / (d * d.sqrt())
    }

    /// VTK's `vol_coef` `k` for a shading gradient of length `g` (VTK's,
    /// [`Self::vtk_gradient_magnitude`]) and opacity `a` (module documentation).
    pub fn volume_coefficient(&self, g: f64, a: f64) -> f64 {
        let b = self.blending;
        let e = (-b * g * a).exp();
        if b < 1.0 {
            b * e
        } else {
            (2.0 - b) * e + b - 1.0
        }
    }

    /// VTK's shading-gradient length from the world gradient `grad` of the
    /// values: `2 |grad| / (hi - lo)` (its difference spans two cells and is
    /// divided by one; 0 over an empty range).
    pub fn vtk_gradient_magnitude(&self, grad: [f64; 3]) -> f64 {
        let span = self.value_range[1] - self.value_range[0];
        let l = (grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]).sqrt();
        if span > 0.0 && l.is_finite() {
            2.0 * l / span
        } else {
            0.0
        }
    }

    /// The shadow rays' extent `R` in texture units for the shortest one
    /// `r_min` (one sample distance; module documentation).
    pub fn shadow_extent(&self, r_min: f64) -> f64 {
        (r_min - CUBE_DIAGONAL) * (1.0 - self.reach).powf(0.33) + CUBE_DIAGONAL
    }
}

/// Scattering with the material and lights it scatters (what a DrawList
/// carries, lights in world space).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LitScattering {
    /// VTK's parameters.
    pub scattering: Scattering,
    /// The material and the lights.
    pub lighting: super::lighting::Lighting,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(blending: f64, anisotropy: f64) -> Scattering {
        Scattering {
            blending,
            reach: 0.5,
            anisotropy,
            headlight_ambient: [1.0; 3],
            value_range: [0.0, 1.0],
            sample_distance: 0.0,
        }
    }

    /// VTK's formulas at known points.
    #[test]
    fn vtk_formulas() {
        // Isotropic below 0.01, HG above: forward scattering peaks at cos = 1.
        assert_eq!(s(1.0, 0.009).phase(0.3), 1.0);
        let g = 0.5;
        assert!((s(1.0, g).phase(1.0) - (1.0 - g * g) / ((1.0 - g) * (1.0 - g) * (1.0 - g))).abs() < 1e-12);
        assert!(s(1.0, g).phase(1.0) > s(1.0, g).phase(-1.0));
        // k: B exp(-B g a) below 1, continuous at 1, 1 at B = 2.
        assert!((s(0.5, 0.0).volume_coefficient(2.0, 0.5) - 0.5 * (-0.5f64).exp()).abs() < 1e-15);
        let below = s(1.0 - 1e-12, 0.0).volume_coefficient(1.0, 0.3);
        assert!((below - s(1.0, 0.0).volume_coefficient(1.0, 0.3)).abs() < 1e-9);
        assert_eq!(s(2.0, 0.0).volume_coefficient(3.0, 0.7), 1.0);
        // Reach 0: one step; reach 1: the diagonal.
        let r = s(1.0, 0.0);
        assert!((Scattering { reach: 0.0, ..r }.shadow_extent(0.02) - 0.02).abs() < 1e-12);
        assert!((Scattering { reach: 1.0, ..r }.shadow_extent(0.02) - CUBE_DIAGONAL).abs() < 1e-12);
        assert_eq!(r.vtk_gradient_magnitude([3.0, 0.0, 4.0]), 10.0);
        assert!(!s(0.0, 0.0).runs() && s(0.1, 0.0).runs());
        assert!(s(2.5, 0.0).check().unwrap_err().to_string().contains("blending"));
        assert!(s(1.0, -1.5).check().unwrap_err().to_string().contains("anisotropy"));
        assert!(r.check().is_ok());
    }
}
