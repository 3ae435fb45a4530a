//! The Volume Octree inside the store: its per-node ranges and nodal errors
//! as four 1D Zarr arrays of the group `hybrid_octree` (`min`, `max`:
//! float64 per node slot; `errors` E_p, `squared_errors` Q_p: float32, laid
//! out as in [`VolumeOctree`]), so that opening a store costs time in the
//! size of the octree, not of the data. The layout (dims, leaf size) is in
//! the root's `hybrid_octree` attribute; the error offsets follow from it.

use super::zarr::{open_array, read_all, zarr_error, Storage};
use crate::base::error::{Error, Result};
use crate::octree::layout::Layout;
use crate::octree::VolumeOctree;
use std::sync::Arc;
use zarrs::array::{data_type, ArrayBuilder, ArraySubset};
use zarrs::group::GroupBuilder;

/// The group holding the arrays.
pub const GROUP: &str = "/hybrid_octree";

/// Elements per chunk of the octree's arrays.
const CHUNK: u64 = 1 << 20;

/// Writes `octree`'s arrays under [`GROUP`].
pub fn write_octree(store: &Arc<Storage>, label: &str, octree: &VolumeOctree) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| zarr_error(label, "writing the octree", e);
    GroupBuilder::new().build(store.clone(), GROUP).map_err(|e| err(&e))?.store_metadata().map_err(|e| err(&e))?;
    for (name, values) in [("min", &octree.min), ("max", &octree.max)] {
        write_1d(store, label, name, (data_type::float64(), 0.0f64.to_ne_bytes().to_vec()), values)?;
    }
    for (name, values) in [("errors", &octree.errors), ("squared_errors", &octree.squared_errors)] {
        write_1d(store, label, name, (data_type::float32(), 0.0f32.to_ne_bytes().to_vec()), values)?;
    }
    Ok(())
}

/// Writes `values` as the 1D array `name` of [`GROUP`] of `data_type` (with its zero fill value).
fn write_1d<T: zarrs::array::Element>(
    store: &Arc<Storage>,
    label: &str,
    name: &str,
    (data_type, fill): (zarrs::array::DataType, Vec<u8>),
    values: &[T],
) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| zarr_error(label, "writing the octree", e);
    let n = values.len() as u64;
    let array = ArrayBuilder::new(vec![n], vec![CHUNK.min(n.max(1))], data_type, zarrs::array::FillValue::new(fill))
        .bytes_to_bytes_codecs(vec![super::zarr::zstd()])
        .build(store.clone(), &format!("{GROUP}/{name}"))
        .map_err(|e| err(&e))?;
    array.store_metadata().map_err(|e| err(&e))?;
    array.store_array_subset(&ArraySubset::new_with_ranges(std::slice::from_ref(&(0..n))), values).map_err(|e| err(&e))
}

/// Reads the octree of `layout` from [`GROUP`] and checks it: each array's
/// length against the layout before it is read, then every invariant of a
/// built octree ([`VolumeOctree::validate`]), so a damaged or forged store
/// is refused, not drawn.
pub fn read_octree(store: &Arc<Storage>, label: &str, layout: Layout) -> Result<VolumeOctree> {
    let slots = layout.node_slots();
    let error_offset = layout.error_offsets();
    let errors_len = error_offset[layout.levels()];
    let min: Vec<f64> = read_all(&open_array(store, label, &format!("{GROUP}/min"))?, label, slots)?;
    let max: Vec<f64> = read_all(&open_array(store, label, &format!("{GROUP}/max"))?, label, slots)?;
    let errors: Vec<f32> = read_all(&open_array(store, label, &format!("{GROUP}/errors"))?, label, errors_len)?;
    let squared: Vec<f32> =
        read_all(&open_array(store, label, &format!("{GROUP}/squared_errors"))?, label, errors_len)?;
    let octree = VolumeOctree::from_parts(layout, min, max, errors, squared, error_offset, 0.0);
    octree.validate().map_err(|why| Error::Format {
        path: label.to_string(),
        message: format!(
            "the stored Volume Octree is damaged ({why}): write the store again with `hybrid-octree convert`"
        ),
    })?;
    Ok(octree)
}
