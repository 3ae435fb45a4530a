//! Gradient opacity through the bridge: VTK's points (magnitudes per mean
//! voxel spacing) become the planner's function, the DrawList carries its
//! effects and table, the selection counts the gradient border only for a
//! function that varies and hides everything for one that is 0 everywhere,
//! bad points are refused with a message.

use super::test_support::{as_bytes, ball, ball_camera, ball_desc, build_volume_octree, select_desc};
use super::SelectDesc;

#[test]
fn selection_borders_only_a_varying_function_and_hides_under_zero() {
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let with = |points: Vec<f64>| {
        h.select_bricks(&SelectDesc { gradient_opacity_points: points, ..select_desc(40_000) }).unwrap()
    };
    let border = |s: &super::render::SelectionHandle| {
        let b = s.selection.bricks[0];
        b.bytes == 4 * b.texels.iter().map(|n| n + 2).product::<usize>()
    };
    assert!(!border(&with(Vec::new())));
    assert!(!border(&with(vec![0.0, 0.5, 3.0, 0.5])), "a constant needs no gradient");
    assert!(border(&with(vec![0.0, 0.0, 0.2, 1.0])), "a varying function counts the border");
    let hidden = with(vec![0.0, 0.0, 9.0, 0.0]);
    assert!(hidden.selection.bricks.is_empty() && hidden.summary().unwrap().skipped > 0);
    let err = |points: Vec<f64>| {
        h.select_bricks(&SelectDesc { gradient_opacity_points: points, ..select_desc(40_000) }).unwrap_err().to_string()
    };
    assert!(err(vec![0.0, 1.0, 2.0]).contains("pairs"));
    assert!(err(vec![0.0, 2.0]).contains("[0, 1]"));
    assert!(err(vec![1.0, 0.5, 0.0, 0.5]).contains("increasing magnitude order"));
    assert!(err(vec![f64::NAN, 0.5]).contains("finite"));
}

#[test]
fn draw_lists_carry_the_effects_and_the_table() {
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let s = h.select_bricks(&SelectDesc { gradient_border: true, ..select_desc(40_000) }).unwrap();
    let list = || s.draw_list(&h, &ball_camera(), 0.0).unwrap();
    let plain = list();
    assert_eq!((plain.effects.as_str(), plain.gradients, plain.opacity_scale), ("", false, 1.0));
    assert!(plain.gradient_opacity_table.is_empty());

    s.set_gradient_opacity(&[0.0, 1.0, 3.0, 1.0]).unwrap();
    let one = list();
    assert_eq!((one.effects.as_str(), one.gradients), ("", false), "1 everywhere is no effect");

    s.set_gradient_opacity(&[0.0, 0.5]).unwrap();
    let half = list();
    assert_eq!((half.effects.as_str(), half.gradients, half.opacity_scale), ("opacity-scale", false, 0.5));

    // VTK's magnitudes per mean spacing (here 1) clamped at a quarter of the
    // value range: the table ends there, holding the function's value.
    s.set_gradient_opacity(&[0.0, 0.0, 0.2, 1.0]).unwrap();
    let varying = list();
    assert_eq!((varying.effects.as_str(), varying.gradients), ("gradient-opacity", true));
    let (lo, hi) = h.volume().value_range();
    assert!((varying.gradient_opacity_end - 0.25 * (hi - lo)).abs() < 1e-12, "{}", varying.gradient_opacity_end);
    let t = &varying.gradient_opacity_table;
    assert_eq!((t.len(), t[0], t[t.len() - 1]), (4096, 0.0, 1.0));
    let k = (0.1 / varying.gradient_opacity_end * 4095.0).round() as usize;
    assert!((t[k] - 0.5).abs() < 1e-3, "{}", t[k]);
    assert_eq!(varying.passes, "volume");

    s.set_gradient_opacity(&[]).unwrap();
    assert_eq!(list().effects, "");
    let e = s.set_gradient_opacity(&[0.0, -0.5]).unwrap_err().to_string();
    assert!(e.contains("gradient opacity") && e.contains("[0, 1]"), "{e}");
}
