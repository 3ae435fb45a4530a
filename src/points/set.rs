//! The stored points: [`Point`] (quantised as in the file) and [`PointSet`]
//! (the points of one grid, with what dequantises them).

/// One stored point (quantised as in the file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Point {
    /// Grid sample of the point.
    pub ijk: [u16; 3],
    /// Index into [`super::normals::table`] of the original data's gradient direction.
    pub normal: u8,
    /// Error `f - T_f` at the point, `error / 127 * error_scale` in data units.
    pub error: i8,
    /// Original value, `value_min + value / 255 * (value_max - value_min)`.
    pub value: u8,
}

/// The points of one grid and low-resolution factor, with what dequantises them.
#[derive(Debug, Clone, PartialEq)]
pub struct PointSet {
    /// Samples per axis of the grid the points were taken from.
    pub dims: [usize; 3],
    /// Low-resolution factor `f` (2, 4 or 8): the volume they complete is T_f.
    pub factor: usize,
    /// Data range the values are quantised over.
    pub value_range: [f64; 2],
    /// Largest `|error|` among the points: the error of `error = +-127`.
    pub error_scale: f64,
    /// The optimized representation's bound on how much the low-resolution
    /// volume overestimates (data units, [`super::lowres`]); infinite: plain subsampling.
    pub max_overestimate: f64,
    /// The points, in grid order (x fastest).
    pub points: Vec<Point>,
}

impl PointSet {
    /// Bytes per stored point: 6 with 8-bit coordinates (every axis at most
    /// 256 samples), 9 with 16-bit ones.
    pub fn point_bytes(&self) -> usize {
        if self.dims.iter().all(|&n| n <= 256) {
            6
        } else {
            9
        }
    }

    /// Bytes of all points as stored (without the file header).
    pub fn bytes(&self) -> usize {
        self.points.len() * self.point_bytes()
    }

    /// The original value of `p`, dequantised.
    pub fn value(&self, p: &Point) -> f64 {
        let [lo, hi] = self.value_range;
        lo + f64::from(p.value) / 255.0 * (hi - lo)
    }

    /// The error of `p` in data units, dequantised.
    pub fn error(&self, p: &Point) -> f64 {
        f64::from(p.error) / 127.0 * self.error_scale
    }
}
