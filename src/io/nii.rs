//! NIfTI-1 (`.nii`, `.nii.gz`) through the `nifti` crate: one 3D volume.
//!
//! Geometry: spacing `pixdim[1..=3]`, origin the qform offset
//! `(qoffset_x, qoffset_y, qoffset_z)` when `qform_code > 0`, else the sform
//! translation `(srow_x[3], srow_y[3], srow_z[3])` when `sform_code > 0`,
//! else 0. Rotations and the RAS orientation are not applied: the volume is
//! in voxel order, as VTK image data. When `scl_slope` is set (not 0, and not
//! the identity 1, 0) the stored values are rescaled,
//! `v = scl_slope * stored + scl_inter`, into `f32` (`f64` data stays `f64`).

use super::read::format_error;
use crate::error::Result;
use crate::grid::GridShape;
use crate::volume::{SampleBuf, Volume};
use nifti::{DataElement, NiftiObject, NiftiType, ReaderOptions};
use std::path::Path;

/// Reads a `.nii` or `.nii.gz` file.
pub fn read_nifti(path: &Path) -> Result<Volume> {
    let object = ReaderOptions::new().read_file(path).map_err(|e| {
        format_error(path, format!("not a readable NIfTI-1 file ({e}); the file may be truncated or corrupt"))
    })?;
    let header = object.header().clone();
    let ndim = header.dim[0] as usize;
    if !(1..=7).contains(&ndim) {
        return Err(format_error(path, format!("invalid NIfTI dim[0] = {ndim}; the header is corrupt")));
    }
    let dims = [1, 2, 3].map(|a| if a <= ndim { (header.dim[a] as usize).max(1) } else { 1 });
    let extra: usize = (4..=ndim).map(|a| (header.dim[a] as usize).max(1)).product();
    if extra > 1 {
        return Err(format_error(
            path,
            format!(
                "the image has {ndim} dimensions with {extra} volumes; the Hybrid Octree takes one 3D volume \
                 (extract one first, e.g. fslroi or nibabel)"
            ),
        ));
    }
    let spacing = [1, 2, 3].map(|a| f64::from(header.pixdim[a]).abs());
    let origin = if header.qform_code > 0 {
        [header.quatern_x, header.quatern_y, header.quatern_z].map(f64::from)
    } else if header.sform_code > 0 {
        [header.srow_x[3], header.srow_y[3], header.srow_z[3]].map(f64::from)
    } else {
        [0.0; 3]
    };
    let datatype = header.data_type().map_err(|e| format_error(path, format!("unknown NIfTI datatype: {e}")))?;
    let raw = object.into_volume();
    let samples = typed(path, raw, datatype)?;
    let samples = rescale(samples, header.scl_slope, header.scl_inter);
    let shape = GridShape { dims, spacing, origin };
    shape.check(1).map_err(|e| format_error(path, e.to_string()))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().trim_end_matches(".gz").trim_end_matches(".nii").to_string())
        .unwrap_or_else(|| "scalars".into());
    Ok(Volume { samples, shape, components: 1, name })
}

fn typed(path: &Path, volume: nifti::InMemNiftiVolume, datatype: NiftiType) -> Result<SampleBuf> {
    fn get<T: DataElement>(path: &Path, v: nifti::InMemNiftiVolume) -> Result<Vec<T>> {
        v.into_nifti_typed_data::<T>()
            .map_err(|e| format_error(path, format!("cannot decode the voxel data ({e}); the file may be corrupt")))
    }
    Ok(match datatype {
        NiftiType::Uint8 => SampleBuf::U8(get(path, volume)?),
        NiftiType::Int8 => SampleBuf::I8(get(path, volume)?),
        NiftiType::Uint16 => SampleBuf::U16(get(path, volume)?),
        NiftiType::Int16 => SampleBuf::I16(get(path, volume)?),
        NiftiType::Uint32 => SampleBuf::U32(get(path, volume)?),
        NiftiType::Int32 => SampleBuf::I32(get(path, volume)?),
        NiftiType::Float32 => SampleBuf::F32(get(path, volume)?),
        NiftiType::Float64 => SampleBuf::F64(get(path, volume)?),
        other => {
            return Err(format_error(
                path,
                format!(
                    "NIfTI datatype {other:?} is not supported; convert the image to an 8/16/32-bit integer \
                     or float type"
                ),
            ))
        }
    })
}

/// Applies `v = slope * stored + inter` unless the scaling is absent (slope 0)
/// or the identity.
fn rescale(samples: SampleBuf, slope: f32, inter: f32) -> SampleBuf {
    if slope == 0.0 || !slope.is_finite() || !inter.is_finite() || (slope == 1.0 && inter == 0.0) {
        return samples;
    }
    if let SampleBuf::F64(v) = samples {
        let (s, i) = (f64::from(slope), f64::from(inter));
        return SampleBuf::F64(v.into_iter().map(|x| s * x + i).collect());
    }
    let (s, i) = (f64::from(slope), f64::from(inter));
    let values: Vec<f32> = (0..samples.len()).map(|n| (s * sample_f64(&samples, n) + i) as f32).collect();
    SampleBuf::F32(values)
}

fn sample_f64(samples: &SampleBuf, n: usize) -> f64 {
    match samples {
        SampleBuf::U8(v) => f64::from(v[n]),
        SampleBuf::I8(v) => f64::from(v[n]),
        SampleBuf::U16(v) => f64::from(v[n]),
        SampleBuf::I16(v) => f64::from(v[n]),
        SampleBuf::U32(v) => f64::from(v[n]),
        SampleBuf::I32(v) => f64::from(v[n]),
        SampleBuf::F32(v) => f64::from(v[n]),
        SampleBuf::F64(v) => v[n],
    }
}
