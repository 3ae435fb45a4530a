//! VTK's Wavelet: the field of `vtkRTAnalyticSource` (ParaView's *Wavelet*
//! source) with its default parameters, over a whole extent centred on the
//! origin, mapped affinely to `[0, 1]`. Detail everywhere: a Gaussian plus a
//! sine along each axis, so no brick of it is trilinear.
//!
//! With `c = 0.5 - t` per axis (VTK: `(Center - index) / (extent width)`),
//!
//! ```text
//! W(t) = 255 exp(-2 (c_x^2 + c_y^2 + c_z^2))        (Maximum 255, StandardDeviation 0.5)
//!      + 10 sin(60 c_x) + 18 sin(30 c_y) + 5 cos(40 c_z)   (X/Y/Z Mag and Freq)
//! f(t) = (W(t) - LO) / (HI - LO),  LO = 255 exp(-1.5) - 33,  HI = 255 + 33
//! ```
//!
//! `LO` and `HI` bound `W` (the Gaussian lies in `[255 e^-1.5, 255]` and the
//! sines add at most 33 either way), so `f` is in `[0, 1]`.

/// Lower bound of `W`: the Gaussian's smallest value less the sines' amplitudes.
pub fn lo() -> f64 {
    255.0 * (-1.5f64).exp() - 33.0
}

/// Upper bound of `W`.
pub const HI: f64 = 255.0 + 33.0;

/// VTK's `RTData` at box-normalised `t` (before the map to `[0, 1]`).
pub fn rt_data(t: [f64; 3]) -> f64 {
    let [x, y, z] = t.map(|t| 0.5 - t);
    let sum = x * x + y * y + z * z;
    255.0 * (-sum * 2.0).exp() + 10.0 * (60.0 * x).sin() + 18.0 * (30.0 * y).sin() + 5.0 * (40.0 * z).cos()
}

/// The Wavelet at box-normalised `t`, in `[0, 1]`.
pub fn value(t: [f64; 3]) -> f64 {
    (rt_data(t) - lo()) / (HI - lo())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_vtk_at_known_points() {
        // The centre: 255 + 0 + 0 + 5 cos(0).
        assert!((rt_data([0.5; 3]) - 260.0).abs() < 1e-12);
        // VTK's default 21^3 Wavelet spans about [37.35, 276.83]: inside [LO, HI].
        let n = 21;
        let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let v = rt_data([i, j, k].map(|c| c as f64 / (n - 1) as f64));
                    (a, b) = (a.min(v), b.max(v));
                }
            }
        }
        assert!((a - 37.35).abs() < 0.01 && (b - 276.83).abs() < 0.01, "{a} {b}");
        assert!(lo() <= a && b <= HI);
    }
}
