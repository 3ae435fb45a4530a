//! Cropping and clipping planes through the bridge: the RegionDesc becomes
//! the selection's and the planner's region, the DrawList says what acts,
//! bad descriptions are refused with a message.

use super::render::region;
use super::test_support::{as_bytes, ball, ball_camera, ball_desc, build_volume_octree, no_region, select_desc};
use super::{RegionDesc, SelectDesc};

fn cropping(planes: [f64; 6]) -> RegionDesc {
    RegionDesc { cropping: true, cropping_planes: planes, cropping_flags: 0x2000, ..no_region() }
}

#[test]
fn no_op_cropping_and_planes_are_dropped_and_acting_ones_reported() {
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let select = |region: RegionDesc| h.select_bricks(&SelectDesc { region, ..select_desc(1 << 24) }).unwrap();
    let plain = select(no_region());
    let list = plain.draw_list(&h, &ball_camera(), 0.0).unwrap();
    assert_eq!((list.passes.as_str(), list.effects.as_str()), ("volume", ""));
    assert!(!list.region.cropping && list.region.clipping_planes.is_empty());
    // The whole box, a plane with the whole box on its kept side: nothing acts.
    let around = RegionDesc {
        clipping_planes: vec![-3.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        ..cropping([-3.0, 13.0, 2.0, 26.0, 5.0, 13.0])
    };
    let whole = select(around);
    assert_eq!(whole.selection.bricks, plain.selection.bricks);
    let list = whole.draw_list(&h, &ball_camera(), 0.0).unwrap();
    assert_eq!(list.effects, "");
    assert!(!list.region.cropping && list.region.clipping_planes.is_empty());
    // Half the box along x, and a plane cutting y: both act, fewer bricks.
    let plane = vec![0.0, 13.0, 0.0, 0.0, -1.0, 0.0];
    let cut = select(RegionDesc { clipping_planes: plane.clone(), ..cropping([-10.0, 4.5, 0.0, 30.0, 0.0, 20.0]) });
    let list = cut.draw_list(&h, &ball_camera(), 0.0).unwrap();
    assert_eq!((list.passes.as_str(), list.effects.as_str()), ("volume", "cropping,clipping"));
    assert_eq!((list.region.cropping_planes, list.region.clipping_planes), ([-10.0, 4.5, 0.0, 30.0, 0.0, 20.0], plane));
    assert!(cut.selection.skipped > plain.selection.skipped);
    assert!(cut.selection.texture_bytes < plain.selection.texture_bytes / 2);
}

#[test]
fn bad_regions_are_refused() {
    let err = |r: RegionDesc| region(&r).unwrap_err().to_string();
    assert_eq!(region(&no_region()).unwrap(), None);
    assert!(err(RegionDesc { clipping_planes: vec![0.0; 5], ..no_region() }).contains("6 per plane"));
    assert!(err(RegionDesc { clipping_planes: vec![0.0; 6], ..no_region() }).contains("length > 0"));
    assert!(err(cropping([0.0, 1.0, 0.0, f64::NAN, 0.0, 1.0])).contains("finite"));
    assert!(err(cropping([0.0, 1.0, 3.0, 1.0, 0.0, 1.0])).contains("y min 3 is above its max 1"));
    assert!(err(RegionDesc { cropping_flags: 1 << 28, ..cropping([0.0, 1.0, 0.0, 1.0, 0.0, 1.0]) })
        .contains("27 lowest bits"));
    let nine = RegionDesc { clipping_planes: [0.0, 0.0, 0.0, 1.0, 0.0, 0.0].repeat(9), ..no_region() };
    assert!(err(nine).contains("at most 8"));
    // Cropping off: its planes are not read.
    let off = RegionDesc { cropping: false, ..cropping([f64::NAN; 6]) };
    assert_eq!(region(&off).unwrap(), None);
    let d = ball();
    let h = build_volume_octree(as_bytes(&d), &ball_desc(), 4).unwrap();
    let e = h.select_bricks(&SelectDesc { region: cropping([1.0, 0.0, 0.0, 1.0, 0.0, 1.0]), ..select_desc(1 << 20) });
    assert!(e.unwrap_err().to_string().contains("x min 1 is above its max 0"));
}
