//! The shading options of a scene: vtkVolumeProperty's Shade, Ambient,
//! Diffuse, Specular and SpecularPower, under VTK's default headlight.

use clap::Args;
use hybrid_octree::transfer::lighting::{Lighting, Material};

/// Volume shading (VTK's model, a white headlight, two-sided).
#[derive(Args, Debug, Clone)]
pub struct ShadeArgs {
    /// Shade the volume by its gradient (ParaView's Shade).
    #[arg(long)]
    pub shade: bool,
    /// Ambient coefficient (with --shade).
    #[arg(long, default_value_t = 0.1, allow_negative_numbers = true)]
    pub ambient: f64,
    /// Diffuse coefficient (with --shade).
    #[arg(long, default_value_t = 0.7, allow_negative_numbers = true)]
    pub diffuse: f64,
    /// Specular coefficient (with --shade).
    #[arg(long, default_value_t = 0.2, allow_negative_numbers = true)]
    pub specular: f64,
    /// Specular power (with --shade).
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub specular_power: f64,
}

impl ShadeArgs {
    /// The lighting asked for, `None` without `--shade`.
    pub fn lighting(&self) -> Option<Lighting> {
        self.shade.then(|| {
            Lighting::headlight(Material {
                ambient: self.ambient,
                diffuse: self.diffuse,
                specular: self.specular,
                specular_power: self.specular_power,
            })
        })
    }
}
