//! Shading through the bridge: the ShadingDesc becomes the planner's
//! lighting, the plan says "volume-shaded", the bordered texels are the
//! compositor's, bad descriptions are refused with a message.

use super::render::lighting;
use super::test_support::{as_bytes, ball, ball_camera, ball_desc, build_volume_octree, select_desc, BALL_N};
use super::{SelectDesc, ShadingDesc};
use crate::grid::Grid;
use crate::render::texture::bordered_position;
use crate::transfer::lighting::{Lighting, Lights, Material};

/// VTK's default lighting: a white headlight.
fn headlight(ambient: f64, diffuse: f64, specular: f64) -> ShadingDesc {
    ShadingDesc {
        shade: true,
        ambient,
        diffuse,
        specular,
        specular_power: 10.0,
        two_sided: true,
        headlight: true,
        light_directions: vec![0.0, 0.0, -1.0],
        light_ambient: vec![1.0; 3],
        light_diffuse: vec![1.0; 3],
        light_specular: vec![1.0; 3],
    }
}

#[test]
fn shading_desc_becomes_the_lighting() {
    assert_eq!(lighting(&ShadingDesc { shade: false, ..headlight(0.1, 0.7, 0.2) }).unwrap(), None);
    assert_eq!(lighting(&headlight(0.1, 0.7, 0.2)).unwrap(), Some(Lighting::headlight(Material::default())));
    let kit = ShadingDesc {
        headlight: false,
        light_directions: vec![0.0, 0.0, -1.0, 1.0, 0.0, 0.0],
        light_ambient: vec![0.0; 6],
        light_diffuse: vec![0.75; 6],
        light_specular: vec![0.75; 6],
        ..headlight(0.1, 0.7, 0.2)
    };
    let Some(Lighting { lights: Lights::Directional(lights), .. }) = lighting(&kit).unwrap() else { panic!() };
    assert_eq!((lights.len(), lights[1].direction), (2, [1.0, 0.0, 0.0]));
    let err = |d: ShadingDesc| lighting(&d).unwrap_err().to_string();
    assert!(err(ShadingDesc { light_diffuse: vec![1.0; 2], ..kit }).contains("3 of each per light"));
    assert!(
        err(ShadingDesc { light_directions: Vec::new(), ..headlight(0.1, 0.7, 0.2) }).contains("at least one light")
    );
    assert!(err(headlight(0.1, f64::NAN, 0.2)).contains("diffuse NaN"));
}

#[test]
fn plan_is_volume_shaded_and_textures_have_borders() {
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let plain = h.select_bricks(&select_desc(40_000)).unwrap();
    let bordered = h.select_bricks(&SelectDesc { gradient_border: true, ..select_desc(40_000) }).unwrap();
    // Border bytes count only when asked for.
    let bytes_of = |s: &super::render::SelectionHandle| s.selection.bricks.iter().map(|b| b.bytes).sum::<usize>();
    let b = plain.selection.bricks[0];
    assert_eq!(b.bytes, 4 * b.texels.iter().product::<usize>());
    let b = bordered.selection.bricks[0];
    assert_eq!(b.bytes, 4 * b.texels.iter().map(|n| n + 2).product::<usize>());
    assert!(bytes_of(&bordered) <= 40_000);
    assert_eq!(bordered.draw_list(&h, &ball_camera(), 0.0).unwrap().passes, "volume");
    bordered.set_shading(&headlight(0.1, 0.7, 0.2)).unwrap();
    assert_eq!(bordered.draw_list(&h, &ball_camera(), 0.0).unwrap().passes, "volume-shaded");
    bordered.set_shading(&headlight(1.0, 0.0, 0.0)).unwrap();
    assert_eq!(
        bordered.draw_list(&h, &ball_camera(), 0.0).unwrap().passes,
        "volume",
        "identity shading is not shading"
    );
    assert!(bordered.set_shading(&headlight(-1.0, 0.0, 0.0)).is_err());
    // Bordered texels: texel i at clamp(lo + (i - 1) stride, 0, dims - 1).
    let grid: Grid<'_> = super::grid::grid_of(as_bytes(&d), &ball_desc()).unwrap();
    for (i, b) in bordered.selection.bricks.iter().enumerate() {
        let n = b.texels.map(|n| n + 2);
        let mut texels = vec![0.0f32; n[0] * n[1] * n[2]];
        bordered.brick_texels_bordered(as_bytes(&d), &ball_desc(), i, &mut texels).unwrap();
        let at = |x: usize, y: usize, z: usize| d[x + BALL_N * (y + BALL_N * z)];
        for (k, j, ii) in [(0, 0, 0), (n[2] - 1, n[1] - 1, n[0] - 1), (1, n[1] / 2, n[0] - 2)] {
            let p = |a: usize, t: usize| bordered_position(b, grid.dims(), a, t);
            assert_eq!(texels[ii + n[0] * (j + n[1] * k)], at(p(0, ii), p(1, j), p(2, k)));
        }
        let mut short = vec![0.0f32; b.texels.iter().product()];
        let e = bordered.brick_texels_bordered(as_bytes(&d), &ball_desc(), i, &mut short).unwrap_err().to_string();
        assert!(e.contains("texels"), "{e}");
    }
}
