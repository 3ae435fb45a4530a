//! Texel formats in the compositor: integer data in a format of their
//! width draw exactly the picture of 32-bit float texels, at a quarter or
//! half of the bytes, shaded or not; quantized float data cost the error
//! their format states, and narrower formats cost more.

use super::*;
use crate::plan::texel_format::{TexelEncoding, TexelFormat};
use crate::render::texture::upload;
use crate::transfer::lighting::{Lighting, Material};

/// `list` with the texels of `format` resolved for `grid`.
fn with_format(mut list: DrawList, grid: &Grid<'_>, format: TexelFormat) -> DrawList {
    let (lo, hi) = VolumeOctree::build(grid, &BuildOptions { leaf_size: 8 }).unwrap().value_range();
    list.texel = TexelEncoding::resolve(format, grid.samples().scalar_type(), (lo, hi), grid.nan_count()).unwrap();
    list
}

/// Bricks at strides 1, 2 and 4 over a 33^3 grid.
fn mixed_bricks() -> Vec<Brick> {
    vec![
        brick(0, [0, 0, 0], [16, 16, 32], 4),
        brick(1, [16, 0, 0], [32, 16, 32], 2),
        brick(2, [0, 16, 0], [16, 32, 32], 1),
        brick(3, [16, 16, 0], [32, 32, 32], 2),
    ]
}

/// u8 and i16 data in unorm8 / unorm16 (the `auto` format) and in the wider
/// unorm16: the same picture as float32 texels, unshaded and shaded (the
/// gradient reads codes times the decoding's step), bit for bit up to the
/// decoding's rounding (measured max RMSE 0), at 1/4 and 1/2 of the bytes.
#[test]
fn integers_in_their_width_draw_the_float_picture() {
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, true).unwrap();
    let lighting = Lighting::headlight(Material::default());
    for (scalar, bytes) in [(ScalarType::U8, 1), (ScalarType::I16, 2)] {
        let volume = generate(Dataset::Sphere, 33, scalar);
        let grid = volume.grid(None).unwrap();
        let (lo, hi) = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap().value_range();
        let tf = TransferFunction::new(
            vec![(lo, [1.0, 0.9, 0.6]), (hi, [0.3, 0.5, 1.0])],
            vec![(lo, 0.0), (lo + 0.4 * (hi - lo), 0.08), (hi, 0.02)],
        )
        .unwrap();
        for shade in [false, true] {
            let mut list = draw_list(grid.shape(), &camera, &mixed_bricks(), SurfacePass::None);
            if shade {
                list.plan.shading = true;
                list.lighting = Some(lighting.in_world(&list.camera));
            }
            let float = with_format(list.clone(), &grid, TexelFormat::Float32);
            let auto = with_format(list.clone(), &grid, TexelFormat::Auto);
            let wide = with_format(list, &grid, TexelFormat::Unorm16);
            assert!(auto.texel.exact_integers && wide.texel.exact_integers);
            let t_float = upload(&grid, &float).unwrap().bytes();
            assert_eq!(upload(&grid, &auto).unwrap().bytes() * 4, t_float * bytes);
            let truth = composite(&grid, &float, &tf, 48, 48, None).unwrap();
            for list in [&auto, &wide] {
                let image = composite(&grid, list, &tf, 48, 48, None).unwrap();
                let m = compare(&image, &truth).unwrap();
                eprintln!("{scalar:?} {:?} shaded {shade}: {m:?}", list.texel.format);
                assert!(m.rmse <= 1e-6, "{scalar:?} {:?} shaded {shade}: {m:?}", list.texel.format);
            }
        }
    }
}

/// Marschner-Lobb (f32) in unorm16, float16 and unorm8 against float32
/// texels: each picture moves by less than its quantization error allows
/// (the picture of a transfer function of slope at most 1 / range moves at
/// most by the normalised error per sample; measured RMSE 4e-7 / 1.1e-5 /
/// 1.3e-4 against bounds 5e-6, 1e-4, 1.5e-3), narrower formats move it
/// more, and the bytes halve and quarter.
#[test]
fn quantized_floats_cost_their_stated_error() {
    let volume = generate(Dataset::MarschnerLobb, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let (lo, hi) = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap().value_range();
    let tf = TransferFunction::ramp(lo, hi);
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, false).unwrap();
    let list = draw_list(grid.shape(), &camera, &mixed_bricks(), SurfacePass::None);
    let float = with_format(list.clone(), &grid, TexelFormat::Float32);
    let truth = composite(&grid, &float, &tf, 48, 48, None).unwrap();
    let bytes = upload(&grid, &float).unwrap().bytes();
    let mut last = 0.0;
    for (format, bound) in [(TexelFormat::Unorm16, 5e-6), (TexelFormat::Float16, 1e-4), (TexelFormat::Unorm8, 1.5e-3)] {
        let l = with_format(list.clone(), &grid, format);
        assert!(!l.texel.exact_integers && l.texel.error > 0.0);
        assert_eq!(upload(&grid, &l).unwrap().bytes() * 4, bytes * format.bytes());
        let m = compare(&composite(&grid, &l, &tf, 48, 48, None).unwrap(), &truth).unwrap();
        eprintln!("{format:?}: {m:?} (normalised error {})", l.texel.normalized_error((lo, hi)));
        assert!(m.rmse > 0.0 && m.rmse <= bound, "{format:?}: {m:?}");
        if format != TexelFormat::Float16 {
            assert!(m.rmse > last, "{format:?} should cost more than the wider format");
            last = m.rmse;
        }
    }
}
