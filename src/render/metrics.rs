//! How far one picture is from another, both shown over
//! [`super::image::BACKGROUND`] (values in `[0, 1]`, peak 1):
//!
//! ```text
//! RMSE   = sqrt(mean over pixels and R, G, B of (a - b)^2)
//! PSNR   = 10 log10(1 / MSE) dB                      (+infinity when identical)
//! maxabs = max over pixels and R, G, B of |a - b|
//! SSIM   = mean over every 7x7 window (stride 1) of the luminance of
//!          (2 mu_a mu_b + C1) (2 s_ab + C2) / ((mu_a^2 + mu_b^2 + C1) (s_a^2 + s_b^2 + C2))
//!          C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1
//! ```
//!
//! (Wang, Bovik, Sheikh, Simoncelli 2004, with a uniform window; `mu` the
//! window means, `s^2` the variances and `s_ab` the covariance, population
//! normalisation). Pictures smaller than 7 pixels use one window as wide
//! (or high) as they are.

use super::image::{Image, BACKGROUND};
use crate::base::error::{Error, Result};

/// Differences between two pictures (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Metrics {
    /// Root mean square error over R, G, B.
    pub rmse: f64,
    /// Peak signal-to-noise ratio, dB (infinite for identical pictures).
    pub psnr: f64,
    /// Largest absolute difference of a channel.
    pub max_abs: f64,
    /// Mean structural similarity of the luminance, 1 for identical pictures.
    pub ssim: f64,
}

/// SSIM window width.
const WINDOW: usize = 7;
const C1: f64 = 0.01 * 0.01;
const C2: f64 = 0.03 * 0.03;

/// Compares `a` with `b` (the reference); an error when their sizes differ.
pub fn compare(a: &Image, b: &Image) -> Result<Metrics> {
    if (a.width, a.height) != (b.width, b.height) || a.rgba.len() != b.rgba.len() {
        return Err(Error::InvalidArgument(format!(
            "cannot compare a {}x{} picture with a {}x{} one: render both at the same size",
            a.width, a.height, b.width, b.height
        )));
    }
    if a.rgba.is_empty() {
        return Err(Error::InvalidArgument("cannot compare empty pictures".into()));
    }
    let (sa, sb) = (a.over(BACKGROUND), b.over(BACKGROUND));
    let (mut sum, mut max_abs) = (0.0f64, 0.0f64);
    for (p, q) in sa.iter().zip(&sb) {
        for k in 0..3 {
            let d = (p[k] - q[k]) as f64;
            sum += d * d;
            max_abs = max_abs.max(d.abs());
        }
    }
    let mse = sum / (3 * sa.len()) as f64;
    let psnr = if mse == 0.0 { f64::INFINITY } else { -10.0 * mse.log10() };
    let ssim = ssim(&a.luminance(BACKGROUND), &b.luminance(BACKGROUND), a.width, a.height);
    Ok(Metrics { rmse: mse.sqrt(), psnr, max_abs, ssim })
}

/// Mean SSIM of two `width x height` luminance pictures over 7x7 windows.
fn ssim(a: &[f64], b: &[f64], width: usize, height: usize) -> f64 {
    let (ww, wh) = (WINDOW.min(width), WINDOW.min(height));
    let n = (ww * wh) as f64;
    let (mut total, mut windows) = (0.0, 0usize);
    for y0 in 0..=height - wh {
        for x0 in 0..=width - ww {
            let pixels = || (y0..y0 + wh).flat_map(move |y| (x0..x0 + ww).map(move |x| x + width * y));
            let (ma, mb) = pixels().fold((0.0, 0.0), |(sa, sb), i| (sa + a[i], sb + b[i]));
            let (ma, mb) = (ma / n, mb / n);
            let (mut va, mut vb, mut cab) = (0.0, 0.0, 0.0);
            for i in pixels() {
                let (da, db) = (a[i] - ma, b[i] - mb);
                va += da * da;
                vb += db * db;
                cab += da * db;
            }
            let (va, vb, cab) = (va / n, vb / n, cab / n);
            total += (2.0 * ma * mb + C1) * (2.0 * cab + C2) / ((ma * ma + mb * mb + C1) * (va + vb + C2));
            windows += 1;
        }
    }
    total / windows as f64
}

/// The difference picture `gain |a - b|` per channel (both shown over
/// [`super::image::BACKGROUND`]), opaque: black where they agree.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for pictures of different sizes.
pub fn difference(a: &Image, b: &Image, gain: f32) -> Result<Image> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(Error::InvalidArgument(format!(
            "cannot difference a {}x{} picture with a {}x{} one: render both at the same size",
            a.width, a.height, b.width, b.height
        )));
    }
    let (sa, sb) = (a.over(super::image::BACKGROUND), b.over(super::image::BACKGROUND));
    let rgba = sa
        .iter()
        .zip(&sb)
        .map(|(p, q)| [0, 1, 2].map(|k| (gain * (p[k] - q[k]).abs()).min(1.0)))
        .map(|[r, g, b]| [r, g, b, 1.0])
        .collect();
    Ok(Image { width: a.width, height: a.height, rgba })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opaque(width: usize, height: usize, f: impl Fn(usize, usize) -> f32) -> Image {
        let mut img = Image::new(width, height);
        for y in 0..height {
            for x in 0..width {
                let v = f(x, y);
                img.rgba[x + width * y] = [v, v, v, 1.0];
            }
        }
        img
    }

    #[test]
    fn identical_pictures_are_perfect() {
        let a = opaque(20, 13, |x, y| ((x * 7 + y * 3) % 11) as f32 / 10.0);
        let m = compare(&a, &a).unwrap();
        assert_eq!((m.rmse, m.max_abs, m.ssim), (0.0, 0.0, 1.0));
        assert!(m.psnr.is_infinite() && m.psnr > 0.0);
        // Tiny pictures use one smaller window.
        let t = opaque(3, 2, |x, _| x as f32 / 3.0);
        assert_eq!(compare(&t, &t).unwrap().ssim, 1.0);
    }

    #[test]
    fn a_known_offset_gives_its_rmse_and_psnr() {
        let a = opaque(16, 16, |x, y| 0.2 + 0.5 * ((x + y) % 2) as f32);
        let b = opaque(16, 16, |x, y| 0.3 + 0.5 * ((x + y) % 2) as f32);
        let m = compare(&a, &b).unwrap();
        assert!((m.rmse - 0.1).abs() < 1e-6, "{m:?}");
        assert!((m.psnr - 20.0).abs() < 1e-4, "{m:?}");
        assert!((m.max_abs - 0.1).abs() < 1e-6);
        // A constant offset keeps the structure: only the luminance term drops.
        assert!(m.ssim < 1.0 && m.ssim > 0.9, "{m:?}");
        // Inverted structure is far from similar.
        let inverted = opaque(16, 16, |x, y| 0.7 - 0.5 * ((x + y) % 2) as f32);
        assert!(compare(&a, &inverted).unwrap().ssim < 0.0);
    }

    #[test]
    fn transparent_pixels_are_compared_over_the_background() {
        let clear = Image::new(4, 4);
        let bg = opaque(4, 4, |_, _| 0.0);
        let m = compare(&clear, &bg).unwrap();
        let expected = ((BACKGROUND.iter().map(|&c| (c * c) as f64).sum::<f64>()) / 3.0).sqrt();
        assert!((m.rmse - expected).abs() < 1e-6);
    }

    #[test]
    fn different_sizes_are_an_error() {
        let e = compare(&Image::new(4, 4), &Image::new(4, 5)).unwrap_err().to_string();
        assert!(e.contains("4x4") && e.contains("4x5") && e.contains("same size"), "{e}");
    }
}
