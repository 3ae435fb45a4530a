//! The project's few words of `zarrs`: the storage, the codec, opening an
//! array, reading one whole, and scalar types by name.

use crate::base::error::{Error, Result};
use crate::base::limits::escape_controls;
use crate::data::grid::{Sample, ScalarType};
use std::sync::Arc;
use zarrs::array::data_type::{
    Float32DataType, Float64DataType, Int16DataType, Int32DataType, Int8DataType, UInt16DataType, UInt32DataType,
    UInt8DataType,
};
use zarrs::array::{codec::ZstdCodec, Array, ArraySubset, BytesToBytesCodecTraits, DataType, ElementOwned};

/// The storage a store lives on: a folder.
pub type Storage = zarrs::filesystem::FilesystemStore;

/// The chunk codec of arrays written here: zstd at level 3, no checksum
/// (the shard index carries a crc32c).
pub fn zstd() -> Arc<dyn BytesToBytesCodecTraits> {
    Arc::new(ZstdCodec::new(3, false))
}

/// `Error::Format` for a failure of `zarrs` while `doing` something to the store `label`.
pub fn zarr_error(label: &str, doing: &str, e: &dyn std::fmt::Display) -> Error {
    Error::Format { path: label.to_string(), message: escape_controls(&format!("{doing}: {e}")) }
}

/// Opens the array at `path` of the store.
pub fn open_array(store: &Arc<Storage>, label: &str, path: &str) -> Result<Array<Storage>> {
    Array::open(store.clone(), path).map_err(|e| zarr_error(label, &format!("opening array '{path}'"), &e))
}

/// Every element of the 1D `array`, which must hold `expected` of type `T`
/// (checked before anything is read).
pub fn read_all<T: ElementOwned>(array: &Array<Storage>, label: &str, expected: usize) -> Result<Vec<T>> {
    if array.shape() != [expected as u64] {
        return Err(Error::Format {
            path: label.to_string(),
            message: format!(
                "array '{}' has shape {:?}, the octree's layout needs [{expected}]: write the store again \
                 with `hybrid-octree convert`",
                escape_controls(array.path().as_str()),
                array.shape()
            ),
        });
    }
    array
        .retrieve_array_subset::<Vec<T>>(&ArraySubset::new_with_ranges(std::slice::from_ref(&(0..expected as u64))))
        .map_err(|e| zarr_error(label, &format!("reading '{}'", array.path().as_str()), &e))
}

/// The Zarr data type of a scalar type.
pub fn data_type_of(t: ScalarType) -> DataType {
    use zarrs::array::data_type as d;
    match t {
        ScalarType::U8 => d::uint8(),
        ScalarType::I8 => d::int8(),
        ScalarType::U16 => d::uint16(),
        ScalarType::I16 => d::int16(),
        ScalarType::U32 => d::uint32(),
        ScalarType::I32 => d::int32(),
        ScalarType::F32 => d::float32(),
        ScalarType::F64 => d::float64(),
    }
}

/// The scalar type of a Zarr data type, or the error naming what is supported.
pub fn scalar_type_of(label: &str, t: &DataType) -> Result<ScalarType> {
    let types = [
        (t.is::<UInt8DataType>(), ScalarType::U8),
        (t.is::<Int8DataType>(), ScalarType::I8),
        (t.is::<UInt16DataType>(), ScalarType::U16),
        (t.is::<Int16DataType>(), ScalarType::I16),
        (t.is::<UInt32DataType>(), ScalarType::U32),
        (t.is::<Int32DataType>(), ScalarType::I32),
        (t.is::<Float32DataType>(), ScalarType::F32),
        (t.is::<Float64DataType>(), ScalarType::F64),
    ];
    types.into_iter().find(|(is, _)| *is).map(|(_, s)| s).ok_or_else(|| Error::Format {
        path: label.to_string(),
        message: format!(
            "the image's data type {} is not supported: use uint8, int8, uint16, int16, uint32, int32, \
             float32 or float64",
            escape_controls(&format!("{t:?}"))
        ),
    })
}

/// The bytes of `values` in native order: a view, not a copy.
pub fn bytes_of<T: Sample>(values: &[T]) -> &[u8] {
    // SAFETY: `Sample` is implemented only for plain number types (no
    // padding, every bit pattern valid); the byte slice covers exactly the
    // values and borrows them for its lifetime.
    unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }
}

/// `$read` (an expression whose element type is inferred from its use)
/// evaluated as a `Vec` of the samples of `$ty`, wrapped in its
/// [`crate::data::volume::SampleBuf`] variant; `?` inside returns early.
macro_rules! typed_samples {
    ($ty:expr, $read:expr) => {
        match $ty {
            $crate::data::grid::ScalarType::U8 => $crate::data::volume::SampleBuf::U8($read),
            $crate::data::grid::ScalarType::I8 => $crate::data::volume::SampleBuf::I8($read),
            $crate::data::grid::ScalarType::U16 => $crate::data::volume::SampleBuf::U16($read),
            $crate::data::grid::ScalarType::I16 => $crate::data::volume::SampleBuf::I16($read),
            $crate::data::grid::ScalarType::U32 => $crate::data::volume::SampleBuf::U32($read),
            $crate::data::grid::ScalarType::I32 => $crate::data::volume::SampleBuf::I32($read),
            $crate::data::grid::ScalarType::F32 => $crate::data::volume::SampleBuf::F32($read),
            $crate::data::grid::ScalarType::F64 => $crate::data::volume::SampleBuf::F64($read),
        }
    };
}
pub(super) use typed_samples;
