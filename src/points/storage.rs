//! The point file (paper 3, section 3.3): "one byte each for x, y, z,
//! normal, error, and original function value" on grids up to 256^3 (6 bytes
//! a point), 16-bit coordinates beyond (9 bytes).
//!
//! Layout, little-endian:
//!
//! ```text
//! magic        8 bytes  "HOPOINTS"
//! version      u32      1
//! coord bytes  u32      1 (every axis <= 256 samples) or 2
//! dims         3 x u32  samples per axis of the grid
//! factor       u32      low-resolution factor (2, 4 or 8)
//! value range  2 x f64  min, max: value = min + q / 255 (max - min)
//! error scale  f64      error = q / 127 * scale
//! overestimate f64      the low-resolution volume's bound (infinite: plain subsampling)
//! count        u64      points
//! points       count x (x, y, z: coord bytes each; normal u8; error i8; value u8)
//! ```
//!
//! Reading checks every field and the exact length, so a truncated or
//! corrupt file is an error naming what is wrong, never a wrong picture.

use super::set::{Point, PointSet};
use crate::base::error::{Error, Result};
use crate::base::limits::escape_controls;
use crate::io::source::{display_path, read_regular_file, regular_file_len};
use std::path::Path;

const MAGIC: &[u8; 8] = b"HOPOINTS";
const VERSION: u32 = 1;
const HEADER: usize = 8 + 4 + 4 + 12 + 4 + 16 + 8 + 8 + 8;

/// The file's bytes for `set`.
pub fn encode(set: &PointSet) -> Vec<u8> {
    let coord = set.point_bytes() / 3 - 1;
    let mut out = Vec::with_capacity(HEADER + set.bytes());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&(coord as u32).to_le_bytes());
    for n in set.dims {
        out.extend_from_slice(&(n as u32).to_le_bytes());
    }
    out.extend_from_slice(&(set.factor as u32).to_le_bytes());
    for v in [set.value_range[0], set.value_range[1], set.error_scale, set.max_overestimate] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&(set.points.len() as u64).to_le_bytes());
    for p in &set.points {
        for c in p.ijk {
            out.extend_from_slice(&c.to_le_bytes()[..coord]);
        }
        out.extend_from_slice(&[p.normal, p.error as u8, p.value]);
    }
    out
}

/// The point set in `bytes` (a file's contents; `path`, fit to print, names
/// it in errors).
pub fn decode(bytes: &[u8], path: &str) -> Result<PointSet> {
    let bad = |message: String| Error::Format { path: path.to_string(), message };
    if bytes.len() < HEADER {
        return Err(bad(format!(
            "the file is {} bytes, shorter than the {HEADER}-byte header of a point file: it is truncated or not a point file",
            bytes.len()
        )));
    }
    if &bytes[..8] != MAGIC {
        return Err(bad("not a Hybrid Octree point file (no HOPOINTS signature)".into()));
    }
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let f64_at = |at: usize| f64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
    let version = u32_at(8);
    if version != VERSION {
        return Err(bad(format!(
            "point file version {version} is not supported (this build reads version {VERSION}): regenerate the points"
        )));
    }
    let coord = u32_at(12) as usize;
    let dims = [u32_at(16), u32_at(20), u32_at(24)].map(|n| n as usize);
    let factor = u32_at(28) as usize;
    let (lo, hi, error_scale, max_overestimate) = (f64_at(32), f64_at(40), f64_at(48), f64_at(56));
    let count = u64::from_le_bytes(bytes[64..72].try_into().expect("8 bytes"));
    if dims.iter().any(|&n| !(2..=1 << 16).contains(&n)) {
        return Err(bad(format!(
            "grid dimensions {dims:?} are out of range (2 to 65,536 per axis): the header is corrupt"
        )));
    }
    let needed = if dims.iter().all(|&n| n <= 256) { 1 } else { 2 };
    if coord != needed {
        return Err(bad(format!(
            "{coord}-byte coordinates for a {}x{}x{} grid (expected {needed}): the header is corrupt",
            dims[0], dims[1], dims[2]
        )));
    }
    if ![2, 4, 8].contains(&factor) {
        return Err(bad(format!("low-resolution factor {factor} is not 2, 4 or 8: the header is corrupt")));
    }
    if !(lo.is_finite() && hi.is_finite() && lo <= hi && error_scale.is_finite() && error_scale >= 0.0) {
        return Err(bad(format!(
            "value range [{lo}, {hi}] or error scale {error_scale} is not finite and ordered: the header is corrupt"
        )));
    }
    if max_overestimate.is_nan() || max_overestimate < 0.0 {
        return Err(bad(format!("overestimation bound {max_overestimate} is negative or NaN: the header is corrupt")));
    }
    let record = 3 * coord + 3;
    let body = bytes.len() - HEADER;
    if u64::try_from(body / record).ok() != Some(count) || !body.is_multiple_of(record) {
        return Err(bad(format!(
            "the header says {count} points of {record} bytes, but {body} bytes follow: the file is truncated or corrupt"
        )));
    }
    let mut points = Vec::with_capacity(body / record);
    for (n, r) in bytes[HEADER..].chunks_exact(record).enumerate() {
        let ijk: [u16; 3] = std::array::from_fn(|a| {
            if coord == 1 {
                u16::from(r[a])
            } else {
                u16::from_le_bytes([r[2 * a], r[2 * a + 1]])
            }
        });
        if (0..3).any(|a| usize::from(ijk[a]) >= dims[a]) {
            return Err(bad(format!("point {n} at {ijk:?} lies outside the {dims:?} grid: the file is corrupt")));
        }
        let q = &r[3 * coord..];
        points.push(Point { ijk, normal: q[0], error: q[1] as i8, value: q[2] });
    }
    Ok(PointSet { dims, factor, value_range: [lo, hi], error_scale, max_overestimate, points })
}

/// Writes `set` to `path`.
pub fn write_points(set: &PointSet, path: &Path) -> Result<()> {
    std::fs::write(path, encode(set)).map_err(|e| Error::Write { path: display_path(path), message: e.to_string() })
}

/// Reads the point file at `path`: a regular file (a pipe or a device is
/// refused), read up to its size, then [`decode`]d.
pub fn read_points(path: &Path) -> Result<PointSet> {
    let label = display_path(path);
    let len = regular_file_len(path, &label)?;
    decode(&read_regular_file(path, &label, len)?, &label)
}

/// The point set in the bytes of a point file named `file_name` (in errors):
/// the in-memory form of [`read_points`].
pub fn from_bytes(bytes: &[u8], file_name: &str) -> Result<PointSet> {
    decode(bytes, &escape_controls(file_name))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate as dataset, Dataset};
    use crate::points::{generate, PointOptions, PointSelect};

    fn sample(size: usize) -> PointSet {
        let v = dataset(Dataset::SheppLogan, size, ScalarType::F32);
        generate(&v.grid(None).unwrap(), &PointOptions::new(4, PointSelect::Threshold(0.05))).unwrap()
    }

    #[test]
    fn round_trips_bit_for_bit_with_six_bytes_a_point() {
        let set = sample(33);
        assert_eq!(set.point_bytes(), 6);
        let bytes = encode(&set);
        assert_eq!(bytes.len(), HEADER + 6 * set.points.len());
        assert_eq!(decode(&bytes, "t").unwrap(), set);
        let dir = std::env::temp_dir().join(format!("ho-points-{}.hop", std::process::id()));
        write_points(&set, &dir).unwrap();
        assert_eq!(read_points(&dir).unwrap(), set);
        std::fs::remove_file(&dir).ok();
    }

    #[test]
    fn large_grids_take_sixteen_bit_coordinates() {
        let mut set = sample(17);
        set.dims = [300, 17, 17];
        set.points[0].ijk[0] = 299;
        assert_eq!(set.point_bytes(), 9);
        assert_eq!(decode(&encode(&set), "t").unwrap(), set);
    }

    #[test]
    fn truncated_and_corrupt_files_are_clear_errors() {
        let set = sample(33);
        let good = encode(&set);
        let check = |bytes: &[u8], says: &str| {
            let e = decode(bytes, "p.hop").unwrap_err().to_string();
            assert!(e.contains(says) && e.contains("p.hop"), "{e}");
        };
        check(&good[..good.len() - 1], "truncated");
        check(&good[..10], "header");
        let mut b = good.clone();
        b[0] = b'X';
        check(&b, "HOPOINTS");
        let mut b = good.clone();
        b[8] = 2;
        check(&b, "version 2");
        let mut b = good.clone();
        b[28] = 3;
        check(&b, "factor 3");
        let mut b = good.clone();
        b[HEADER] = 200; // x of the first point beyond a 33-sample axis
        check(&b, "outside");
        let mut b = good.clone();
        b.push(0);
        check(&b, "corrupt");
    }
}
