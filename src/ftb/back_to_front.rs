//! Meagher's back-to-front display (the baseline): traverse the octree in
//! the back-to-front order of the view, and scan-convert every potentially
//! visible face of every black octant, each pixel overwritten by whatever is
//! painted later (nearer).

use super::binary_octree::{BinaryOctree, Colour, Node};
use super::display::Display;
use super::raster::{DepthImage, Paint, Projector};
use super::view::View;
use std::time::Instant;

/// The depth image of `octree` seen along `view` on a `size x size` image.
pub fn display(octree: &BinaryOctree, view: &View, size: usize) -> Display {
    display_into(octree, view, DepthImage::new(size))
}

/// [`display`] into `image` (cleared first; its size is the image size).
/// The time covers clearing, traversal and scan conversion.
pub fn display_into(octree: &BinaryOctree, view: &View, image: DepthImage) -> Display {
    let started = Instant::now();
    let mut projector = Projector::reusing(view, octree.side(), image);
    let order = view.btf_order();
    visit(octree, view, &order, &mut projector, octree.root(), [0; 3], octree.side());
    let ms = started.elapsed().as_secs_f64() * 1e3;
    Display { image: projector.image, counters: projector.counters, ms }
}

fn visit(
    octree: &BinaryOctree,
    view: &View,
    order: &[usize; 8],
    projector: &mut Projector,
    node: Node,
    origin: [usize; 3],
    size: usize,
) {
    match node.colour {
        Colour::White => {}
        Colour::Black => {
            projector.counters.black_visited += 1;
            for &axis in &view.axes {
                projector.face(origin, size, axis, view.high_face[axis], Paint::Overwrite);
            }
        }
        Colour::Gray => {
            projector.counters.gray_visited += 1;
            let half = size / 2;
            let octant = octree.gray_octant(node);
            for &oct in order {
                let o =
                    [origin[0] + half * (oct & 1), origin[1] + half * ((oct >> 1) & 1), origin[2] + half * (oct >> 2)];
                visit(octree, view, order, projector, BinaryOctree::suboctant(octant, oct), o, half);
            }
        }
    }
}
