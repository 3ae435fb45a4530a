//! The volumetric scattering options of a scene (VTK 9.2's
//! VolumetricScatteringBlending, GlobalIlluminationReach and
//! ScatteringAnisotropy; ParaView's Volume Scattering Blending, Global
//! Illumination Reach, Volume Anisotropy), with `--shade`.

use clap::Args;
use hybrid_octree::transfer::Scattering;
use hybrid_octree::Result;

/// Volumetric scattering (with `--shade`; VTK's sample distance taken as the
/// reference spacing).
#[derive(Args, Debug, Clone, Default)]
pub struct ScatteringArgs {
    /// Blending between gradient shading and scattered light, 0 to 2 (0: none).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub scatter_blending: f64,
    /// Reach of the shadow rays, 0 to 1.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub scatter_reach: f64,
    /// Henyey-Greenstein anisotropy, -1 (backward) to 1 (forward).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub scatter_anisotropy: f64,
}

impl ScatteringArgs {
    /// The parameters over the data's `value_range` (`None` at blending 0:
    /// none asked for).
    ///
    /// # Errors
    ///
    /// A value out of its range ([`Scattering::check`]), also at blending 0:
    /// a bad argument is refused whether or not it is used.
    pub fn scattering(&self, value_range: (f64, f64)) -> Result<Option<Scattering>> {
        let scattering = Scattering {
            blending: self.scatter_blending,
            reach: self.scatter_reach,
            anisotropy: self.scatter_anisotropy,
            headlight_ambient: [1.0; 3],
            value_range: [value_range.0, value_range.1],
            sample_distance: 0.0,
        };
        scattering.check()?;
        Ok((self.scatter_blending != 0.0).then_some(scattering))
    }
}
