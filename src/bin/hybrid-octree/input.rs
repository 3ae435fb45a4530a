//! The input arguments every subcommand shares: a built-in dataset or a file.

use clap::Args;
use hybrid_octree::datasets::generate::{check_generate, DatasetPlanes};
use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::grid::{Grid, ScalarType};
use hybrid_octree::io::tiff_stack::TiffStack;
use hybrid_octree::io::{read_volume, FileKind, RawOptions, ReadOptions};
use hybrid_octree::store::Store;
use hybrid_octree::volume::Volume;
use hybrid_octree::{Error, Result};
use std::path::{Path, PathBuf};

/// Where the volume comes from.
#[derive(Args, Debug, Clone)]
pub struct InputArgs {
    /// Built-in dataset: shepp-logan, marschner-lobb, sphere, ramp, constant, vessels, wavelet.
    #[arg(long, conflicts_with = "file", required_unless_present = "file")]
    pub dataset: Option<String>,
    /// Samples per axis of the built-in dataset.
    #[arg(long, default_value_t = 128)]
    pub size: usize,
    /// Scalar type: of the generated dataset, or of a raw file (u8, i8, u16, i16, u32, i32, f32, f64).
    #[arg(long = "type")]
    pub scalar_type: Option<String>,
    /// Volume file: .vti, .vtk, .nii, .nii.gz, a TIFF stack (.tif/.tiff, or a folder of TIFF slices),
    /// raw (.raw/.bin, with --dims and --type), or an OME-Zarr image folder (.ome.zarr, .zarr).
    #[arg(long)]
    pub file: Option<PathBuf>,
    /// Raw file dimensions X,Y,Z (makes the file be read as raw).
    #[arg(long, value_parser = triple::<usize>, requires = "file")]
    pub dims: Option<[usize; 3]>,
    /// Spacing X,Y,Z of a raw file or a TIFF stack (whose own calibration, ImageJ's, it replaces).
    #[arg(long, value_parser = triple::<f64>, requires = "file", allow_hyphen_values = true)]
    pub spacing: Option<[f64; 3]>,
    /// Raw file origin X,Y,Z.
    #[arg(long, value_parser = triple::<f64>, requires = "dims", allow_hyphen_values = true)]
    pub origin: Option<[f64; 3]>,
    /// Raw file values per point.
    #[arg(long, default_value_t = 1, requires = "dims")]
    pub components: usize,
    /// Raw file multi-byte values are big endian.
    #[arg(long, requires = "dims")]
    pub big_endian: bool,
    /// Component of a multi-component array to use.
    #[arg(long)]
    pub component: Option<usize>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Checks `--size N` of a built-in dataset before generating it: at least
/// 2, and `N^3` values of `scalar_type` within the memory this process may use.
pub fn check_size(size: usize, scalar_type: ScalarType) -> Result<()> {
    if size < 2 {
        return Err(Error::InvalidArgument(format!("--size {size} is too small: use at least 2")));
    }
    check_generate([size; 3], scalar_type).map(drop)
}

/// Parses `X,Y,Z` (clap value parser).
pub fn triple<T: std::str::FromStr + Copy + Default>(s: &str) -> std::result::Result<[T; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected three comma-separated values X,Y,Z, got '{s}'"));
    }
    let mut out = [T::default(); 3];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p.parse().map_err(|_| format!("'{p}' is not a valid number in '{s}'"))?;
    }
    Ok(out)
}

impl InputArgs {
    /// The scalar type given with `--type`, or `default`.
    pub fn scalar_type_or(&self, default: ScalarType) -> Result<ScalarType> {
        self.scalar_type.as_deref().map_or(Ok(default), ScalarType::parse)
    }

    /// The OME-Zarr store `--file` names (a folder, or a name ending in
    /// `.zarr`), opened; `None` for any other input.
    pub fn store(&self) -> Result<Option<Store>> {
        match &self.file {
            Some(path) if is_store(path) && self.dims.is_none() => {
                let store = Store::open(path)?;
                for w in &store.warnings {
                    eprintln!("warning: {w}");
                }
                Ok(Some(store))
            }
            _ => Ok(None),
        }
    }

    /// The TIFF stack `--file` names (a `.tif`/`.tiff` file, or a folder
    /// that is not an OME-Zarr image), opened with `--spacing` applied;
    /// `None` for any other input.
    pub fn tiff_stack(&self) -> Result<Option<TiffStack>> {
        match &self.file {
            Some(path)
                if self.dims.is_none()
                    && !is_store(path)
                    && (path.is_dir() || FileKind::of(&path.to_string_lossy()) == Some(FileKind::Tiff)) =>
            {
                let mut stack = TiffStack::open(path)?;
                if let Some(spacing) = self.spacing {
                    stack.shape.spacing = spacing;
                }
                Ok(Some(stack))
            }
            _ => Ok(None),
        }
    }

    /// Generates or reads the volume (a store's full resolution read whole).
    pub fn load(&self) -> Result<Volume> {
        if let Some(store) = self.store()? {
            return store.read_volume();
        }
        if let Some(path) = &self.file {
            let raw = match &self.dims {
                Some(dims) => {
                    let scalar_type =
                        self.scalar_type.as_deref().map(ScalarType::parse).transpose()?.ok_or_else(|| {
                            Error::InvalidArgument(
                                "a raw file needs its scalar type: add --type (e.g. --type u8)".into(),
                            )
                        })?;
                    let mut raw = RawOptions::new(*dims, scalar_type);
                    raw.spacing = self.spacing.unwrap_or([1.0; 3]);
                    raw.origin = self.origin.unwrap_or([0.0; 3]);
                    raw.components = self.components;
                    raw.big_endian = self.big_endian;
                    Some(raw)
                }
                None => None,
            };
            let mut volume = read_volume(path, &ReadOptions { raw: raw.clone() })?;
            if let (None, Some(spacing)) = (&raw, self.spacing) {
                if !(path.is_dir() || FileKind::of(&path.to_string_lossy()) == Some(FileKind::Tiff)) {
                    return Err(Error::InvalidArgument(
                        "--spacing sets the spacing of a raw file (with --dims) or a TIFF stack; this file's header \
                         gives its own"
                            .into(),
                    ));
                }
                volume.shape.spacing = spacing;
            }
            return Ok(volume);
        }
        let name = self
            .dataset
            .as_deref()
            .ok_or_else(|| Error::InvalidArgument("give an input: --dataset NAME --size N, or --file PATH".into()))?;
        let dataset = Dataset::parse(name)?;
        let scalar_type = self.scalar_type_or(ScalarType::F32)?;
        check_size(self.size, scalar_type)?;
        Ok(generate(dataset, self.size, scalar_type))
    }

    /// The built-in dataset `--dataset` names as a plane source (generated
    /// plane by plane when read, never whole); `None` for a file.
    pub fn dataset_planes(&self) -> Result<Option<DatasetPlanes>> {
        let (None, Some(name)) = (&self.file, &self.dataset) else {
            return Ok(None);
        };
        let dataset = Dataset::parse(name)?;
        let scalar_type = self.scalar_type_or(ScalarType::F32)?;
        if self.size < 2 {
            return Err(Error::InvalidArgument(format!("--size {} is too small: use at least 2", self.size)));
        }
        Ok(Some(DatasetPlanes { dataset, dims: [self.size; 3], scalar_type }))
    }

    /// A short name of the input: the file name, or the dataset and size.
    pub fn describe(&self) -> String {
        match (&self.file, &self.dataset) {
            (Some(path), _) => {
                path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into())
            }
            (None, Some(d)) => format!("{d} {}^3", self.size),
            (None, None) => "input".into(),
        }
    }

    /// The grid of the chosen component.
    pub fn grid<'v>(&self, volume: &'v Volume) -> Result<Grid<'v>> {
        volume.grid(self.component)
    }
}

/// True for an OME-Zarr image: a path ending in `.zarr` (any case), or a
/// folder with Zarr metadata (`zarr.json`, `.zgroup`, `.zattrs`). Any other
/// folder is a stack of TIFF slices.
pub fn is_store(path: &Path) -> bool {
    path.to_string_lossy().to_ascii_lowercase().trim_end_matches('/').ends_with(".zarr")
        || (path.is_dir() && ["zarr.json", ".zgroup", ".zattrs"].iter().any(|m| path.join(m).is_file()))
}
