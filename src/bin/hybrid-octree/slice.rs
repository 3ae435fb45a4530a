//! The Slice blend mode's plane of a scene (VTK's `SLICE_BLEND` with
//! `vtkVolumeProperty::SetSliceFunction(vtkPlane)`), world coordinates.

use clap::Args;
use hybrid_octree::plan::{BlendMode, SlicePlane};
use hybrid_octree::{Error, Result};

/// The plane `--blend slice` draws the volume on.
#[derive(Args, Debug, Clone, Default)]
pub struct SliceArgs {
    /// A point X,Y,Z of the slice plane (world coordinates; default the
    /// centre of the volume's box).
    #[arg(long, value_parser = point, allow_hyphen_values = true)]
    pub slice_origin: Option<[f64; 3]>,
    /// The slice plane's normal X,Y,Z (any length above 0); required by `--blend slice`.
    #[arg(long, value_parser = point, allow_hyphen_values = true)]
    pub slice_normal: Option<[f64; 3]>,
}

impl SliceArgs {
    /// The plane under `mode` for a volume of box `[lo, hi]`: `Some` under
    /// Slice, `None` under the other modes.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when Slice has no `--slice-normal`, the
    /// plane is not finite or its normal is 0, or the options come with another mode.
    pub fn plane(&self, mode: BlendMode, lo: [f64; 3], hi: [f64; 3]) -> Result<Option<SlicePlane>> {
        match (mode, self.slice_normal) {
            (BlendMode::Slice, Some(normal)) => {
                let centre = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
                SlicePlane::new(self.slice_origin.unwrap_or(centre), normal).map(Some)
            }
            (BlendMode::Slice, None) => Err(Error::InvalidArgument(
                "--blend slice draws the volume on a plane: give its --slice-normal X,Y,Z (and --slice-origin X,Y,Z, \
                 default the volume's centre)"
                    .into(),
            )),
            _ if self.slice_normal.is_some() || self.slice_origin.is_some() => Err(Error::InvalidArgument(
                "--slice-origin and --slice-normal are for --blend slice: add it, or leave them out".into(),
            )),
            _ => Ok(None),
        }
    }
}

/// Three comma-separated numbers.
fn point(s: &str) -> std::result::Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| format!("'{s}' is not X,Y,Z: give 3 comma-separated numbers"))?;
    let v: [f64; 3] = v.try_into().map_err(|v: Vec<f64>| format!("'{s}' has {} numbers: X,Y,Z needs 3", v.len()))?;
    if v.iter().any(|x| !x.is_finite()) {
        return Err(format!("'{s}': give finite numbers"));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_from_the_options() {
        let args = SliceArgs { slice_origin: None, slice_normal: Some([0.0, 1.0, 1.0]) };
        let p = args.plane(BlendMode::Slice, [0.0; 3], [2.0, 4.0, 6.0]).unwrap().unwrap();
        assert_eq!((p.origin, p.normal), ([1.0, 2.0, 3.0], [0.0, 1.0, 1.0]));
        assert!(args
            .plane(BlendMode::Composite, [0.0; 3], [1.0; 3])
            .unwrap_err()
            .to_string()
            .contains("--blend slice"));
        let none = SliceArgs::default();
        assert!(none.plane(BlendMode::Slice, [0.0; 3], [1.0; 3]).unwrap_err().to_string().contains("--slice-normal"));
        assert_eq!(none.plane(BlendMode::Mip, [0.0; 3], [1.0; 3]).unwrap(), None);
        let zero = SliceArgs { slice_origin: None, slice_normal: Some([0.0; 3]) };
        assert!(zero.plane(BlendMode::Slice, [0.0; 3], [1.0; 3]).unwrap_err().to_string().contains("non-zero"));
        assert!(point("1,2").unwrap_err().contains("has 2 numbers"));
        assert!(point("1,x,2").unwrap_err().contains("not X,Y,Z"));
        assert!(point("1,nan,2").unwrap_err().contains("finite"));
        assert_eq!(point(" -1, 2.5,3").unwrap(), [-1.0, 2.5, 3.0]);
    }
}
