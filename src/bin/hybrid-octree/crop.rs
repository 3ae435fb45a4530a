//! The cropping and clipping options of a scene: VTK's
//! `vtkVolumeMapper::SetCroppingRegionPlanes` (the central box, VTK's
//! default flags) and `vtkAbstractMapper::AddClippingPlane`, world coordinates.

use clap::Args;
use hybrid_octree::plan::crop::{ClippingPlane, Cropping, KeptRegion};
use hybrid_octree::Result;

/// Cropping and clipping planes of the volume (not of the isosurface).
#[derive(Args, Debug, Clone, Default)]
pub struct CropArgs {
    /// Keep only the box XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX of the volume (world
    /// coordinates; VTK's cropping with its default subvolume flags).
    #[arg(long, value_parser = crop_box, allow_hyphen_values = true)]
    pub crop: Option<[f64; 6]>,
    /// Keep only the volume on the side of the plane OX,OY,OZ,NX,NY,NZ (a
    /// point and a normal, world coordinates) the normal points to;
    /// repeatable, up to 8 planes.
    #[arg(long, value_parser = clip_plane, allow_hyphen_values = true)]
    pub clip: Vec<ClippingPlane>,
}

impl CropArgs {
    /// The region asked for (world coordinates), `None` without `--crop` or `--clip`.
    pub fn region(&self) -> Result<Option<KeptRegion>> {
        if self.crop.is_none() && self.clip.is_empty() {
            return Ok(None);
        }
        KeptRegion::new(self.crop.map(Cropping::subvolume), &self.clip).map(Some)
    }
}

/// Six comma-separated numbers.
fn numbers<const N: usize>(s: &str, what: &str) -> std::result::Result<[f64; N], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| format!("'{s}' is not {what}: give {N} comma-separated numbers"))?;
    v.try_into().map_err(|v: Vec<f64>| format!("'{s}' has {} numbers: {what} needs {N}", v.len()))
}

fn crop_box(s: &str) -> std::result::Result<[f64; 6], String> {
    let planes = numbers::<6>(s, "XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX")?;
    Cropping::subvolume(planes).check().map_err(|e| e.to_string())?;
    Ok(planes)
}

fn clip_plane(s: &str) -> std::result::Result<ClippingPlane, String> {
    let [ox, oy, oz, nx, ny, nz] = numbers::<6>(s, "OX,OY,OZ,NX,NY,NZ")?;
    let plane = ClippingPlane { origin: [ox, oy, oz], normal: [nx, ny, nz] };
    plane.check().map_err(|e| e.to_string())?;
    Ok(plane)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_say_what_is_wrong() {
        assert!(crop_box("0,1,0,1,0").unwrap_err().contains("has 5 numbers"));
        assert!(crop_box("0,1,0,x,0,1").unwrap_err().contains("not XMIN"));
        assert!(crop_box("0,1,0,NaN,0,1").unwrap_err().contains("finite"));
        assert!(crop_box("0,1,2,1,0,1").unwrap_err().contains("y min 2 is above its max 1"));
        assert!(clip_plane("0,0,0,0,0,0").unwrap_err().contains("length > 0"));
        assert_eq!(clip_plane("1,2,3,0,0,-1").unwrap().normal, [0.0, 0.0, -1.0]);
        let args = CropArgs { crop: Some([0.0, 1.0, 0.0, 1.0, 0.0, 1.0]), clip: vec![] };
        assert_eq!(args.region().unwrap().unwrap().effects(), vec!["cropping"]);
        assert!(CropArgs::default().region().unwrap().is_none());
    }
}
