//! Volumetric scattering through the bridge: the plan names it only with
//! shading and a blending above 0, the frame description and the shadow
//! volume's texels, bad values refused.

use super::test_support::{as_bytes, ball, ball_camera, ball_desc, build_volume_octree, select_desc, BALL_N};
use super::{ScatteringDesc, SelectDesc, ShadingDesc};
use crate::render::scattering::SHADOW_VOLUME_MAX_DIM;

fn headlight() -> ShadingDesc {
    ShadingDesc {
        shade: true,
        ambient: 0.1,
        diffuse: 0.7,
        specular: 0.2,
        specular_power: 10.0,
        two_sided: true,
        headlight: true,
        light_directions: vec![0.0, 0.0, -1.0],
        light_ambient: vec![1.0; 3],
        light_diffuse: vec![1.0; 3],
        light_specular: vec![1.0; 3],
    }
}

fn desc(blending: f64) -> ScatteringDesc {
    ScatteringDesc { blending, reach: 0.5, anisotropy: 0.2, headlight_ambient: [1.0; 3], sample_distance: 0.0 }
}

#[test]
fn scattering_is_planned_with_shading_and_a_blending() {
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let s = h.select_bricks(&SelectDesc { gradient_border: true, ..select_desc(1 << 22) }).unwrap();
    let effects = || s.draw_list(&h, &ball_camera(), 0.0).unwrap().effects;
    s.set_scattering(&desc(1.0)).unwrap();
    assert_eq!(effects(), "", "no Shade: no scattering");
    s.set_shading(&headlight()).unwrap();
    assert_eq!(effects(), "shading,volume-scattering");
    assert!(s.draw_list(&h, &ball_camera(), 0.0).unwrap().gradients);
    s.set_scattering(&desc(0.0)).unwrap();
    assert_eq!(effects(), "shading");
    let e = s.set_scattering(&desc(2.5)).unwrap_err().to_string();
    assert!(e.contains("blending 2.5"), "{e}");
    let e = s.set_scattering(&ScatteringDesc { reach: -0.1, ..desc(1.0) }).unwrap_err().to_string();
    assert!(e.contains("reach"), "{e}");

    s.set_scattering(&desc(1.0)).unwrap();
    let f = s.scattering_frame().unwrap();
    assert_eq!(f.shadow_dims, [BALL_N.min(SHADOW_VOLUME_MAX_DIM); 3]);
    assert!(f.extent > 0.0 && f.extent < 1.74 && f.blending == 1.0 && f.max_steps > 0);
    let n: usize = f.shadow_dims.iter().product();
    let mut texels = vec![0.0f32; n];
    s.shadow_volume_texels(as_bytes(&d), &ball_desc(), &mut texels).unwrap();
    assert_eq!(texels[0], d[0]);
    assert_eq!(texels[n - 1], d[d.len() - 1]);
    let mut short = vec![0.0f32; n - 1];
    assert!(s.shadow_volume_texels(as_bytes(&d), &ball_desc(), &mut short).is_err());

    // The CPU compositor's picture changes with the scattering.
    let tf_colors = [0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.8, 0.6];
    let tf_opacities = [0.0, 0.0, 1.0, 0.3];
    let picture = |blending: f64| {
        s.set_scattering(&desc(blending)).unwrap();
        let mut rgba = vec![0.0f32; 4 * 24 * 24];
        s.composite(
            &h,
            &ball_camera(),
            as_bytes(&d),
            &ball_desc(),
            &tf_colors,
            &tf_opacities,
            false,
            &[0.0; 4],
            24,
            24,
            &mut rgba,
        )
        .unwrap();
        rgba
    };
    let (plain, scattered) = (picture(0.0), picture(2.0));
    let moved = plain.iter().zip(&scattered).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
    assert!(moved > 0.01, "scattering changed the picture by {moved}");
}
