//! The z-planes the streaming build holds: a few whole planes of the
//! volume in their native type, found by a z -> slot table, read by the
//! leaf kernel through [`Lattice`] as if they were the whole grid.

use super::lattice::Lattice;
use crate::data::grid::Sample;

/// No slot: the plane is not held.
const ABSENT: u32 = u32::MAX;

/// Whole z-planes of a grid of `dims` samples, each in one slot.
#[derive(Debug)]
pub struct PlaneStack<T: Sample> {
    dims: [usize; 3],
    plane: usize,
    data: Vec<T>,
    slot_of: Vec<u32>,
    free: Vec<u32>,
}

impl<T: Sample> PlaneStack<T> {
    /// An empty stack for a grid of `dims` samples (no plane allocated yet).
    pub fn new(dims: [usize; 3]) -> PlaneStack<T> {
        PlaneStack {
            dims,
            plane: dims[0] * dims[1],
            data: Vec::new(),
            slot_of: vec![ABSENT; dims[2]],
            free: Vec::new(),
        }
    }

    /// True when plane `z` is held.
    pub fn holds(&self, z: usize) -> bool {
        self.slot_of[z] != ABSENT
    }

    /// The planes held, in z order.
    pub fn held(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.dims[2]).filter(|&z| self.holds(z))
    }

    /// Planes the stack has room for without growing.
    pub fn slots(&self) -> usize {
        self.data.len() / self.plane.max(1)
    }

    /// Drops every plane not in `keep`.
    pub fn keep_only(&mut self, keep: &[usize]) {
        for z in 0..self.dims[2] {
            let slot = self.slot_of[z];
            if slot != ABSENT && !keep.contains(&z) {
                self.free.push(slot);
                self.slot_of[z] = ABSENT;
            }
        }
    }

    /// Holds `values` (one plane, `nx * ny` values) as plane `z`, in a free
    /// slot or a new one.
    pub fn insert(&mut self, z: usize, values: &[T]) {
        debug_assert_eq!(values.len(), self.plane);
        let slot = match self.slot_of[z] {
            ABSENT => match self.free.pop() {
                Some(s) => s,
                None => {
                    self.data.extend_from_slice(values);
                    self.slot_of[z] = (self.data.len() / self.plane - 1) as u32;
                    return;
                }
            },
            s => s,
        };
        let at = slot as usize * self.plane;
        self.data[at..at + self.plane].copy_from_slice(values);
        self.slot_of[z] = slot;
    }

    /// Plane `z` (x fastest). Panics when it is not held (a caller bug).
    pub fn plane(&self, z: usize) -> &[T] {
        let slot = self.slot_of[z];
        assert!(slot != ABSENT, "plane {z} is not held");
        &self.data[slot as usize * self.plane..(slot as usize + 1) * self.plane]
    }
}

impl<T: Sample> Lattice for PlaneStack<T> {
    #[inline(always)]
    fn dims(&self) -> [usize; 3] {
        self.dims
    }
    #[inline(always)]
    fn at(&self, i: usize, j: usize, k: usize) -> f64 {
        self.data[self.slot_of[k] as usize * self.plane + i + self.dims[0] * j].to_f64()
    }
    #[inline]
    fn row_into(&self, i0: usize, i1: usize, j: usize, k: usize, out: &mut Vec<f64>) {
        out.clear();
        let base = self.slot_of[k] as usize * self.plane + self.dims[0] * j;
        out.extend(self.data[base + i0..=base + i1].iter().map(|v| v.to_f64()));
    }
    #[inline(always)]
    fn prefetch_row(&self, _i0: usize, _i1: usize, _j: usize, _k: usize) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_are_found_by_z_and_slots_are_reused() {
        let mut s = PlaneStack::<u8>::new([2, 2, 5]);
        s.insert(3, &[1, 2, 3, 4]);
        s.insert(0, &[5, 6, 7, 8]);
        assert_eq!((s.at(1, 1, 3), s.at(0, 1, 0)), (4.0, 7.0));
        s.keep_only(&[0, 4]);
        assert!(!s.holds(3) && s.holds(0));
        s.insert(4, &[9, 9, 9, 1]);
        assert_eq!(s.slots(), 2);
        let mut row = Vec::new();
        s.row_into(0, 1, 1, 4, &mut row);
        assert_eq!(row, [9.0, 1.0]);
        assert_eq!(s.held().collect::<Vec<_>>(), [0, 4]);
    }
}
