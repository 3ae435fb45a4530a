//! The one error type of the crate.
//!
//! Every message names the problem and what the user can do about it, because
//! the same text reaches a ParaView user through `vtkErrorMacro` and a shell
//! user through the CLI.

use std::fmt;

/// Everything that can go wrong in the Hybrid Octree library.
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)] // variants and fields are named by what they hold
pub enum Error {
    /// An axis has fewer than two samples: there is no cell to build a node from.
    DimsTooSmall { dims: [usize; 3] },
    /// `dims[0] * dims[1] * dims[2] * components` does not fit in `usize`.
    DimsOverflow { dims: [usize; 3], components: usize },
    /// The sample buffer does not hold `dims` x `components` values.
    LengthMismatch { expected: usize, actual: usize },
    /// A multi-component array was given without choosing a component.
    ComponentRequired { components: usize },
    /// The chosen component does not exist.
    ComponentOutOfRange { component: usize, components: usize },
    /// The array has zero components.
    NoComponents,
    /// Infinite samples (NaN is "no data", not an error); `first` is the
    /// linear point index `i + nx*(j + ny*k)` of the first infinity.
    NonFinite { count: usize, first: usize, first_ijk: [usize; 3] },
    /// Every one of the `count` samples is NaN: there is nothing to build from.
    NoData { count: usize },
    /// Spacing must be finite and positive, origin finite.
    BadGeometry { what: String },
    /// The leaf brick size must be a power of two between 2 and 256.
    BadLeafSize { leaf_size: usize },
    /// A byte buffer is not aligned for its scalar type.
    Misaligned { type_name: &'static str },
    /// The caller stopped a long build (a VTK abort, Ctrl-C).
    Cancelled,
    /// A malformed or unsupported input file.
    Format { path: String, message: String },
    /// An output file that could not be written.
    Write { path: String, message: String },
    /// Any other bad argument, with its explanation.
    InvalidArgument(String),
    /// A bug: a panic caught at the bridge. Reported instead of aborting the host.
    Internal(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::DimsTooSmall { dims } => write!(
                f,
                "image dimensions {}x{}x{} are too small: the Hybrid Octree needs at least 2 samples on every axis \
                 (a 2D or 1-wide image has no cells); use a 3D image or resample it",
                dims[0], dims[1], dims[2]
            ),
            Error::DimsOverflow { dims, components } => write!(
                f,
                "image dimensions {}x{}x{} with {} component(s) overflow the addressable sample count; \
                 crop or subsample the image",
                dims[0], dims[1], dims[2], components
            ),
            Error::LengthMismatch { expected, actual } => write!(
                f,
                "the scalar array holds {actual} values but the image dimensions need {expected}; \
                 check the dimensions (--dims) and scalar type (--type) against the data"
            ),
            Error::ComponentRequired { components } => write!(
                f,
                "the scalar array has {components} components; choose one with the component option \
                 (CLI --component, filter SetComponent / ParaView 'Component'), 0 to {}",
                components - 1
            ),
            Error::ComponentOutOfRange { component, components } => write!(
                f,
                "component {component} does not exist: the scalar array has {components} component(s), \
                 choose 0 to {}",
                components.saturating_sub(1)
            ),
            Error::NoComponents => write!(f, "the scalar array has zero components; give an array with values"),
            Error::NonFinite { count, first, first_ijk } => write!(
                f,
                "the volume has {count} infinite sample(s), the first at point index {first} \
                 (i={}, j={}, k={}); replace them with finite values, or with NaN for \"no data\" \
                 (for example with ParaView's Calculator or numpy.nan_to_num), before building the Hybrid Octree",
                first_ijk[0], first_ijk[1], first_ijk[2]
            ),
            Error::NoData { count } => write!(
                f,
                "no data: all {count} samples are NaN (NaN means \"no data\"); there is nothing to build or draw"
            ),
            Error::BadGeometry { what } => write!(f, "invalid image geometry: {what}"),
            Error::BadLeafSize { leaf_size } => write!(
                f,
                "leaf brick size {leaf_size} is not allowed: use a power of two from 2 to 256 (default 16)"
            ),
            Error::Misaligned { type_name } => write!(
                f,
                "the scalar buffer is not aligned for {type_name}; pass a properly allocated array"
            ),
            Error::Cancelled => write!(f, "the Hybrid Octree build was cancelled; nothing was produced"),
            Error::Format { path, message } => write!(f, "cannot read '{path}': {message}"),
            Error::Write { path, message } => write!(f, "cannot write '{path}': {message}"),
            Error::InvalidArgument(message) => write!(f, "{message}"),
            Error::Internal(message) => write!(
                f,
                "internal error in the Hybrid Octree library ({message}); please report it with the input that caused it"
            ),
        }
    }
}

impl std::error::Error for Error {}

/// Result with the crate's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;
