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
    let f64s = [("min", &octree.min), ("max", &octree.max)];
    for (name, values) in f64s {
        let array = ArrayBuilder::new(
            vec![values.len() as u64],
            vec![CHUNK.min(values.len().max(1) as u64)],
            data_type::float64(),
            0.0f64,
        )
        .bytes_to_bytes_codecs(vec![super::zarr::zstd()])
        .build(store.clone(), &format!("{GROUP}/{name}"))
        .map_err(|e| err(&e))?;
        array.store_metadata().map_err(|e| err(&e))?;
        array
            .store_array_subset(
                &ArraySubset::new_with_ranges(std::slice::from_ref(&(0..values.len() as u64))),
                values.as_slice(),
            )
            .map_err(|e| err(&e))?;
    }
    let f32s = [("errors", &octree.errors), ("squared_errors", &octree.squared_errors)];
    for (name, values) in f32s {
        let array = ArrayBuilder::new(
            vec![values.len() as u64],
            vec![CHUNK.min(values.len().max(1) as u64)],
            data_type::float32(),
            0.0f32,
        )
        .bytes_to_bytes_codecs(vec![super::zarr::zstd()])
        .build(store.clone(), &format!("{GROUP}/{name}"))
        .map_err(|e| err(&e))?;
        array.store_metadata().map_err(|e| err(&e))?;
        array
            .store_array_subset(
                &ArraySubset::new_with_ranges(std::slice::from_ref(&(0..values.len() as u64))),
                values.as_slice(),
            )
            .map_err(|e| err(&e))?;
    }
    Ok(())
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
