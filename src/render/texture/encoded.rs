//! A brick's texels in a texel format ([`TexelEncoding`]): what a GPU
//! executor uploads (R8, R16, R16F or R32F) and the values they decode to,
//! the same codes the CPU compositor's textures hold.

use super::{pool, texel_count, texel_values};
use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridVisitor, Sample, TypedGrid};
use crate::plan::select::Brick;
use crate::plan::texel_format::{TexelEncoding, TexelFormat};
use crate::plan::BlendMode;

/// Bytes of one texel in the staging buffer of [`brick_texels_encoded_into`]:
/// 1 (unorm8), 2 (unorm16), 4 (float16, as the f32 value of each half
/// float, which GL converts into R16F exactly; float32).
pub fn staging_bytes(format: TexelFormat) -> usize {
    match format {
        TexelFormat::Unorm8 => 1,
        TexelFormat::Unorm16 => 2,
        TexelFormat::Float16 | TexelFormat::Float32 | TexelFormat::Auto => 4,
    }
}

/// `brick`'s texels of a picture of blend mode `mode` (peak-keeping texels
/// for a coarse MIP or MinIP brick, as the CPU textures), with `border`
/// texels per side (0 or 1), encoded by `enc`: `decoded` gets the value of
/// each (`bias + scale t`, as `f32`), `encoded` its GPU bytes
/// ([`staging_bytes`] each, native endian), texels x fastest.
///
/// # Errors
///
/// [`Error::InvalidArgument`] if the brick is not a brick of this grid, or
/// a buffer does not hold the brick's texel count.
pub fn brick_texels_encoded_into(
    grid: &Grid<'_>,
    brick: &Brick,
    (border, mode): (usize, BlendMode),
    enc: &TexelEncoding,
    decoded: &mut [f32],
    encoded: &mut [u8],
) -> Result<()> {
    texel_count(grid, brick)?;
    let count = brick.texels.iter().map(|n| n + 2 * border).product::<usize>();
    let width = staging_bytes(enc.format);
    if decoded.len() != count || encoded.len() != count * width {
        return Err(Error::InvalidArgument(format!(
            "buffers of {} values and {} bytes for brick (node {}) of {count} {} texels ({} bytes)",
            decoded.len(),
            encoded.len(),
            brick.node.0,
            enc.format.name(),
            count * width
        )));
    }
    struct Codes<'b>(&'b Brick, usize, BlendMode, TexelEncoding);
    impl GridVisitor for Codes<'_> {
        type Output = Option<Vec<u32>>;
        fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> Option<Vec<u32>> {
            let Codes(brick, border, mode, enc) = self;
            let code = |v: f64| Some(enc.encode(v));
            if mode.is_extremum() && brick.stride > 1 && border == 0 {
                pool::pooled_values(&g, brick, mode == BlendMode::Mip, code)
            } else {
                texel_values(&g, brick, border, code)
            }
        }
    }
    let codes = grid.visit(Codes(brick, border, mode, *enc)).unwrap_or_default();
    for ((c, d), e) in codes.iter().zip(decoded.iter_mut()).zip(encoded.chunks_exact_mut(width)) {
        *d = enc.decode(*c) as f32;
        match enc.format {
            TexelFormat::Unorm8 => e[0] = *c as u8,
            TexelFormat::Unorm16 => e.copy_from_slice(&(*c as u16).to_ne_bytes()),
            TexelFormat::Float16 => e.copy_from_slice(&(enc.texel(*c) as f32).to_ne_bytes()),
            TexelFormat::Float32 | TexelFormat::Auto => e.copy_from_slice(&c.to_ne_bytes()),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Samples, ScalarType};
    use crate::plan::texel_format::TexelFormat;

    /// The GPU bytes decode, as a texture read and the shader's
    /// `bias + scale t` do, to the decoded values, and those are the CPU
    /// textures' values; u8 data in unorm8 upload themselves.
    #[test]
    fn gpu_bytes_decode_to_the_cpu_values() {
        let data: Vec<f32> = (0..9 * 9 * 9).map(|i| ((i * 7919) % 101) as f32 * 0.37 - 5.0).collect();
        let g = Grid::scalar(Samples::F32(&data), [9, 9, 9]).unwrap();
        let b = crate::plan::select::test_brick(0, [0, 2, 0], [8, 8, 6], 2);
        for format in [TexelFormat::Unorm8, TexelFormat::Unorm16, TexelFormat::Float16, TexelFormat::Float32] {
            let enc = TexelEncoding::resolve(format, ScalarType::F32, (-5.0, 32.0), 0).unwrap();
            for (border, mode) in [(0, BlendMode::Composite), (1, BlendMode::Composite), (0, BlendMode::Mip)] {
                let count = b.texels.iter().map(|n| n + 2 * border).product::<usize>();
                let (mut d, mut e) = (vec![0.0f32; count], vec![0u8; count * staging_bytes(format)]);
                brick_texels_encoded_into(&g, &b, (border, mode), &enc, &mut d, &mut e).unwrap();
                for (i, v) in d.iter().enumerate() {
                    let w = staging_bytes(format);
                    let raw = &e[i * w..(i + 1) * w];
                    let t = match format {
                        TexelFormat::Unorm8 => raw[0] as f64 / 255.0,
                        TexelFormat::Unorm16 => u16::from_ne_bytes([raw[0], raw[1]]) as f64 / 65535.0,
                        _ => f32::from_ne_bytes([raw[0], raw[1], raw[2], raw[3]]) as f64,
                    };
                    let value = if format == TexelFormat::Float32 { t } else { enc.bias + enc.scale * t };
                    assert!((value - *v as f64).abs() <= 1e-5 * 37.0, "{format:?} texel {i}: {value} vs {v}");
                }
                let mut short = vec![0.0f32; count - 1];
                assert!(brick_texels_encoded_into(&g, &b, (border, mode), &enc, &mut short, &mut e).is_err());
            }
        }
        let bytes: Vec<u8> = (0..125).map(|i| (i * 2) as u8).collect();
        let g = Grid::scalar(Samples::U8(&bytes), [5, 5, 5]).unwrap();
        let enc = TexelEncoding::resolve(TexelFormat::Auto, ScalarType::U8, (0.0, 248.0), 0).unwrap();
        let b = crate::plan::select::test_brick(0, [0; 3], [4; 3], 1);
        let (mut d, mut e) = (vec![0.0f32; 125], vec![0u8; 125]);
        brick_texels_encoded_into(&g, &b, (0, BlendMode::Composite), &enc, &mut d, &mut e).unwrap();
        assert_eq!(e, bytes);
        assert!(d.iter().zip(&bytes).all(|(d, b)| *d == *b as f32));
    }
}
