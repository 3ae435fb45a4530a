//! The texel format of the brick textures: how many bytes a texel costs the
//! texture budget, and what it does to the values it holds.
//!
//! A texture budget buys the most picture when a texel costs what the data
//! need: an 8-bit scan uploads as 8-bit texels (GL's R8, as VTK's GPU ray
//! caster does), a 16-bit one as R16, and wider data as R32F, or, by
//! choice, as R16F, R16 or R8 at the price of their quantization error.
//!
//! Every format stores a code `t` that the renderers decode with one scale
//! and bias, the same in the CPU compositor and in the brick shader:
//!
//! ```text
//! value = bias + scale * t          t in [0, 1] (normalized: R8, R16; R16F holds t itself)
//! ```
//!
//! - Integer data whose whole type range fits the format's levels
//!   (`u8`, `i8` in R8 or R16; `u16`, `i16` in R16) map the type range onto
//!   `[0, 1]`: `t = (v - type_min) / (type_max - type_min)`, exact (no
//!   quantization error), so `bias = type_min`, `scale = type_max - type_min`.
//! - Other data quantized to R8 or R16 map their finite range `[lo, hi]` onto
//!   the `L = 2^bits - 1` levels, `q = round((v - lo) / (hi - lo) L)`, `t = q / L`:
//!   `bias = lo`, `scale = hi - lo`, an error of at most `(hi - lo) / (2 L)`.
//! - R16F holds `t = (v - lo) / (hi - lo)` rounded to a half float (11
//!   significant bits, by way of an `f32`): at most `(hi - lo) (2^-12 + 2^-24)` off.
//! - R32F holds the value itself (`scale = 1`, `bias = 0`): exact for every
//!   type but `u32`/`i32` beyond `2^24` and `f64`, which round to 24
//!   significant bits, at most `max(|lo|, |hi|) 2^-24` off.
//!
//! The quantization error, normalised by the data range, is added to every
//! brick's nodal error (`E_p + e_q`): the selection and the reported error
//! know what a narrow format costs.

use crate::base::error::{Error, Result};
use crate::data::grid::ScalarType;

/// The texel format asked for (`TexelFormat` on the VTK mapper, `--texel-format` in the CLI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum TexelFormat {
    /// The data's own width: `u8`/`i8` as Unorm8, `u16`/`i16` as Unorm16, the rest as Float32.
    #[default]
    Auto,
    /// 32-bit float texels (R32F).
    Float32,
    /// 16-bit float texels (R16F) of the value normalized to the data range.
    Float16,
    /// 16-bit normalized texels (R16).
    Unorm16,
    /// 8-bit normalized texels (R8).
    Unorm8,
}

impl TexelFormat {
    /// Every format, in the order of their VTK setting values (0 ..= 4).
    pub const ALL: [TexelFormat; 5] =
        [TexelFormat::Auto, TexelFormat::Float32, TexelFormat::Float16, TexelFormat::Unorm16, TexelFormat::Unorm8];

    /// The name used by the CLI and in reports.
    pub fn name(self) -> &'static str {
        match self {
            TexelFormat::Auto => "auto",
            TexelFormat::Float32 => "float32",
            TexelFormat::Float16 => "float16",
            TexelFormat::Unorm16 => "unorm16",
            TexelFormat::Unorm8 => "unorm8",
        }
    }

    /// Parses a [`Self::name`].
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] naming the formats, for any other name.
    pub fn parse(name: &str) -> Result<TexelFormat> {
        TexelFormat::ALL.into_iter().find(|f| f.name() == name.to_ascii_lowercase()).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "unknown texel format '{name}': use one of auto, float32, float16, unorm16, unorm8"
            ))
        })
    }

    /// The format of VTK setting value `v` (0 Auto, 1 Float32, 2 Float16, 3 Unorm16, 4 Unorm8).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for another value.
    pub fn from_vtk(v: i32) -> Result<TexelFormat> {
        usize::try_from(v).ok().and_then(|i| TexelFormat::ALL.get(i).copied()).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "texel format {v}: give 0 (auto), 1 (float32), 2 (float16), 3 (unorm16) or 4 (unorm8)"
            ))
        })
    }

    /// Bytes of one texel of one field (Auto: not resolved, 4).
    pub fn bytes(self) -> usize {
        match self {
            TexelFormat::Auto | TexelFormat::Float32 => 4,
            TexelFormat::Float16 | TexelFormat::Unorm16 => 2,
            TexelFormat::Unorm8 => 1,
        }
    }

    /// The levels `L = 2^bits - 1` of a normalized format (0 for the float formats).
    pub fn levels(self) -> u32 {
        match self {
            TexelFormat::Unorm8 => 255,
            TexelFormat::Unorm16 => 65535,
            _ => 0,
        }
    }
}

/// A resolved texel format and its decoding `value = bias + scale * t`
/// (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TexelEncoding {
    /// The format, never [`TexelFormat::Auto`].
    pub format: TexelFormat,
    /// `scale` of the decoding.
    pub scale: f64,
    /// `bias` of the decoding.
    pub bias: f64,
    /// True when the type range maps onto the levels (integer data, no quantization error).
    pub exact_integers: bool,
    /// The largest `|decode(encode(v)) - v|` over the data, in data units.
    pub error: f64,
}

/// Float32 texels holding the values, no error counted.
impl Default for TexelEncoding {
    fn default() -> TexelEncoding {
        TexelEncoding::float32(ScalarType::F32, (0.0, 0.0))
    }
}

impl TexelEncoding {
    /// 32-bit float texels holding the values themselves (what every brick
    /// held before formats were chosen; the two fields of dependent components).
    pub fn float32(scalar: ScalarType, range: (f64, f64)) -> TexelEncoding {
        let wide = matches!(scalar, ScalarType::F64 | ScalarType::U32 | ScalarType::I32);
        let error = if wide { range.0.abs().max(range.1.abs()) * f64::powi(2.0, -24) } else { 0.0 };
        TexelEncoding { format: TexelFormat::Float32, scale: 1.0, bias: 0.0, exact_integers: false, error }
    }

    /// The encoding of `requested` for data of type `scalar` whose finite
    /// values span `range` (`(lo, hi)`, `lo <= hi`; NaN when there are none)
    /// and that hold `nan_samples` NaN samples.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when a normalized format is asked for data
    /// holding NaN samples (no level means "no data": choose Float16 or Float32).
    pub fn resolve(
        requested: TexelFormat,
        scalar: ScalarType,
        range: (f64, f64),
        nan_samples: usize,
    ) -> Result<TexelEncoding> {
        let format = match requested {
            TexelFormat::Auto => match scalar {
                ScalarType::U8 | ScalarType::I8 => TexelFormat::Unorm8,
                ScalarType::U16 | ScalarType::I16 => TexelFormat::Unorm16,
                _ => TexelFormat::Float32,
            },
            f => f,
        };
        if format == TexelFormat::Float32 {
            return Ok(TexelEncoding::float32(scalar, range));
        }
        if format.levels() > 0 && nan_samples > 0 {
            return Err(Error::InvalidArgument(format!(
                "{} texels cannot hold the {nan_samples} NaN (no data) samples of this volume: choose the \
                 float16 or float32 texel format (or auto)",
                format.name()
            )));
        }
        let (lo, hi) = if range.0.is_finite() && range.1.is_finite() { range } else { (0.0, 0.0) };
        if let Some((type_min, type_max)) = integer_type_range(scalar).filter(|(a, b)| b - a <= format.levels() as f64)
        {
            let scale = type_max - type_min;
            return Ok(TexelEncoding { format, scale, bias: type_min, exact_integers: true, error: 0.0 });
        }
        let scale = hi - lo;
        let error = match format {
            // Half an f16 ulp below 1, and the f32 the conversion rounds through.
            TexelFormat::Float16 => scale * (f64::powi(2.0, -12) + f64::powi(2.0, -24)),
            _ => scale / (2.0 * format.levels() as f64),
        };
        Ok(TexelEncoding { format, scale, bias: lo, exact_integers: false, error })
    }

    /// Bytes of one texel.
    pub fn bytes(&self) -> usize {
        self.format.bytes()
    }

    /// The quantization error normalised by a data range of `range` (what is
    /// added to the nodal errors, which are normalised the same way).
    pub fn normalized_error(&self, range: (f64, f64)) -> f64 {
        let span = range.1 - range.0;
        if span > 0.0 && span.is_finite() {
            self.error / span
        } else {
            0.0
        }
    }

    /// The code of `v` (see the module documentation): the level `q` of a
    /// normalized format (`t = q / L`), the half float's bits of R16F, the
    /// value as `f32` bits of R32F. NaN stays NaN in the float formats.
    #[inline]
    pub fn encode(&self, v: f64) -> u32 {
        match self.format {
            TexelFormat::Unorm8 | TexelFormat::Unorm16 => {
                let levels = self.format.levels() as f64;
                let t = if self.scale > 0.0 { (v - self.bias) / self.scale } else { 0.0 };
                (t * levels).round().clamp(0.0, levels) as u32
            }
            TexelFormat::Float16 => {
                let t = if self.scale > 0.0 { (v - self.bias) / self.scale } else { 0.0 };
                u32::from(half::f16::from_f64(t).to_bits())
            }
            TexelFormat::Auto | TexelFormat::Float32 => (v as f32).to_bits(),
        }
    }

    /// The normalized (or float) texel `t` of a code, what a GPU's texture read returns.
    #[inline]
    pub fn texel(&self, code: u32) -> f64 {
        match self.format {
            TexelFormat::Unorm8 | TexelFormat::Unorm16 => code as f64 / self.format.levels() as f64,
            TexelFormat::Float16 => half::f16::from_bits(code as u16).to_f64(),
            TexelFormat::Auto | TexelFormat::Float32 => f32::from_bits(code) as f64,
        }
    }

    /// The value a code decodes to: `bias + scale * t` (exactly the value for
    /// [`Self::exact_integers`] and Float32).
    #[inline]
    pub fn decode(&self, code: u32) -> f64 {
        match self.format {
            TexelFormat::Auto | TexelFormat::Float32 => f32::from_bits(code) as f64,
            // (scale q) / L: exact for the exact integers (scale q is a multiple of L).
            TexelFormat::Unorm8 | TexelFormat::Unorm16 => {
                self.bias + self.scale * code as f64 / self.format.levels() as f64
            }
            TexelFormat::Float16 => self.bias + self.scale * self.texel(code),
        }
    }
}

/// `(type_min, type_max)` of the 8- and 16-bit integer types.
fn integer_type_range(scalar: ScalarType) -> Option<(f64, f64)> {
    match scalar {
        ScalarType::U8 => Some((0.0, 255.0)),
        ScalarType::I8 => Some((-128.0, 127.0)),
        ScalarType::U16 => Some((0.0, 65535.0)),
        ScalarType::I16 => Some((-32768.0, 32767.0)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_takes_the_data_width() {
        let r = |s| TexelEncoding::resolve(TexelFormat::Auto, s, (0.0, 100.0), 0).unwrap();
        assert_eq!(r(ScalarType::U8).format, TexelFormat::Unorm8);
        assert_eq!(r(ScalarType::I8).format, TexelFormat::Unorm8);
        assert_eq!(r(ScalarType::U16).format, TexelFormat::Unorm16);
        assert_eq!(r(ScalarType::I16).format, TexelFormat::Unorm16);
        for s in [ScalarType::U32, ScalarType::I32, ScalarType::F32, ScalarType::F64] {
            assert_eq!(r(s).format, TexelFormat::Float32);
        }
        assert_eq!(r(ScalarType::U8).bytes(), 1);
        assert_eq!(r(ScalarType::I16).bytes(), 2);
    }

    /// Integer data in a format at least as wide as their type decode to
    /// themselves, every value of the type.
    #[test]
    fn integers_in_their_width_are_exact() {
        let cases = [
            (ScalarType::U8, TexelFormat::Unorm8, 0, 255),
            (ScalarType::I8, TexelFormat::Unorm8, -128, 127),
            (ScalarType::U8, TexelFormat::Unorm16, 0, 255),
            (ScalarType::I8, TexelFormat::Unorm16, -128, 127),
            (ScalarType::U16, TexelFormat::Unorm16, 0, 65535),
            (ScalarType::I16, TexelFormat::Unorm16, -32768, 32767),
        ];
        for (s, f, lo, hi) in cases {
            let e = TexelEncoding::resolve(f, s, (lo as f64 + 3.0, hi as f64 - 5.0), 0).unwrap();
            assert!(e.exact_integers && e.error == 0.0, "{s:?} {f:?}");
            for v in lo..=hi {
                assert_eq!(e.decode(e.encode(v as f64)), v as f64, "{s:?} {f:?} {v}");
                // What the shader computes from the normalized texel, in f32.
                let gl = (e.texel(e.encode(v as f64)) as f32).mul_add(e.scale as f32, e.bias as f32);
                assert!((gl as f64 - v as f64).abs() <= 1e-6 * (hi - lo) as f64, "{s:?} {f:?} {v}: {gl}");
            }
        }
    }

    /// Quantized data stay within the stated error, an f64 reference taken.
    #[test]
    fn quantization_error_is_bounded() {
        let range = (-3.7e3, 1.25e4);
        for f in [TexelFormat::Unorm8, TexelFormat::Unorm16, TexelFormat::Float16] {
            for s in [ScalarType::F32, ScalarType::F64, ScalarType::I32, ScalarType::U16] {
                if s == ScalarType::U16 && f != TexelFormat::Unorm8 && f != TexelFormat::Float16 {
                    continue;
                }
                let e = TexelEncoding::resolve(f, s, range, 0).unwrap();
                assert!(!e.exact_integers && e.error > 0.0);
                let mut largest: f64 = 0.0;
                for i in 0..=10_007 {
                    let v = range.0 + (range.1 - range.0) * i as f64 / 10_007.0;
                    largest = largest.max((e.decode(e.encode(v)) - v).abs());
                }
                assert!(largest <= e.error * (1.0 + 1e-9), "{f:?} {s:?}: {largest} > {}", e.error);
                assert!(largest >= 0.25 * e.error, "{f:?} {s:?}: the bound is loose ({largest} vs {})", e.error);
            }
        }
        // Narrower formats cost more.
        let err = |f| TexelEncoding::resolve(f, ScalarType::F32, range, 0).unwrap().normalized_error(range);
        assert!(err(TexelFormat::Unorm8) > err(TexelFormat::Float16));
        assert!(err(TexelFormat::Float16) > err(TexelFormat::Unorm16));
        assert_eq!(err(TexelFormat::Float32), 0.0);
        assert!((err(TexelFormat::Unorm8) - 1.0 / 510.0).abs() < 1e-12);
    }

    /// Extremes: a constant volume, values beyond f32, NaN samples.
    #[test]
    fn hard_cases() {
        // Constant: every value decodes to the constant.
        let e = TexelEncoding::resolve(TexelFormat::Unorm8, ScalarType::F32, (7.5, 7.5), 0).unwrap();
        assert_eq!(e.decode(e.encode(7.5)), 7.5);
        assert_eq!(e.normalized_error((7.5, 7.5)), 0.0);
        // Huge f64 values: Unorm16 is within its bound where f32 values would overflow.
        let range = (-1e300, 1e300);
        let e = TexelEncoding::resolve(TexelFormat::Unorm16, ScalarType::F64, range, 0).unwrap();
        assert!((e.decode(e.encode(0.5e300)) - 0.5e300).abs() <= e.error);
        // NaN samples: refused by normalized formats, kept by the float ones.
        let msg = TexelEncoding::resolve(TexelFormat::Unorm8, ScalarType::F32, (0.0, 1.0), 3).unwrap_err().to_string();
        assert!(msg.contains("NaN") && msg.contains("float16"), "{msg}");
        let e = TexelEncoding::resolve(TexelFormat::Float16, ScalarType::F32, (0.0, 1.0), 3).unwrap();
        assert!(e.decode(e.encode(f64::NAN)).is_nan());
        let e = TexelEncoding::resolve(TexelFormat::Auto, ScalarType::F32, (0.0, 1.0), 3).unwrap();
        assert!(e.decode(e.encode(f64::NAN)).is_nan());
        // Out-of-range values (the image changed) clamp to the end levels, never wrap.
        let e = TexelEncoding::resolve(TexelFormat::Unorm8, ScalarType::F32, (0.0, 1.0), 0).unwrap();
        assert_eq!(e.encode(5.0), 255);
        assert_eq!(e.encode(-5.0), 0);
    }

    #[test]
    fn names_and_vtk_values() {
        for (i, f) in TexelFormat::ALL.into_iter().enumerate() {
            assert_eq!(TexelFormat::parse(f.name()).unwrap(), f);
            assert_eq!(TexelFormat::from_vtk(i as i32).unwrap(), f);
        }
        assert!(TexelFormat::parse("r8").unwrap_err().to_string().contains("unorm8"));
        assert!(TexelFormat::from_vtk(5).is_err());
        assert!(TexelFormat::from_vtk(-1).is_err());
    }
}
