//! Rendering from an OME-Zarr store equals rendering in core: the
//! Shepp-Logan phantom and Marschner-Lobb (odd sizes, so levels end in a
//! clamped plane) written as a store, its stored octree selected under
//! budgets that leave bricks at strides 1 to 8, each brick's texels read
//! from the store's level of its stride (with the gradient border when
//! shaded) and composited by the CPU compositor: the picture is the in-core
//! picture bit for bit (RMSE 0), plain and shaded, in every texel format.

use hybrid_octree::camera::Camera;
use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::grid::ScalarType;
use hybrid_octree::octree::{BuildOptions, VolumeOctree};
use hybrid_octree::plan::texel_format::{TexelEncoding, TexelFormat};
use hybrid_octree::plan::{draw_list, Scene};
use hybrid_octree::render::compositor::composite_textures;
use hybrid_octree::render::texture::read::upload_read;
use hybrid_octree::render::texture::upload;
use hybrid_octree::render::transfer::TransferFunction;
use hybrid_octree::select::{select, SelectOptions};
use hybrid_octree::store::{write_store, Store, WriteOptions};
use hybrid_octree::transfer::lighting::{Lighting, Material};

#[test]
fn a_store_draws_the_in_core_picture() {
    for (dataset, size, ty) in
        [(Dataset::SheppLogan, 45, ScalarType::U8), (Dataset::MarschnerLobb, 37, ScalarType::F32)]
    {
        let volume = generate(dataset, size, ty);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        let path = std::env::temp_dir().join(format!("ho-store-render-{}-{size}.ome.zarr", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        write_store(&path, &grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
        let store = Store::open(&path).unwrap();
        let stored = store.octree().unwrap().unwrap();
        assert_eq!(stored, octree);
        let (min, max) = stored.value_range();
        let tf = TransferFunction::ramp(min, max);
        let shape = store.shape;
        let camera =
            Camera::around(shape.world([0.0; 3]), shape.world(shape.dims.map(|d| (d - 1) as f64)), 30.0, 20.0, false)
                .unwrap();
        let lighting = Lighting::headlight(Material::default());
        let read =
            |b: &hybrid_octree::select::Brick, border: usize| store.read_texels(b.stride, b.lo, b.texels, border);
        for shaded in [false, true] {
            let full: usize = 3 * size * size * size * 4;
            let mut strides = std::collections::BTreeSet::new();
            for budget in [full / 200, full / 40, full / 8, full] {
                let options = SelectOptions { gradient_border: shaded, ..SelectOptions::new(budget, 0.0) };
                let selection = select(&stored, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
                strides.extend(selection.bricks.iter().map(|b| b.stride));
                let scene = Scene { shading: shaded.then_some(&lighting), ..Scene::volume(Default::default()) };
                for format in [TexelFormat::Auto, TexelFormat::Unorm8, TexelFormat::Float16] {
                    let mut list = draw_list(&stored, &shape, &selection, &camera, &scene, None).unwrap();
                    list.texel = TexelEncoding::resolve(format, ty, (min, max), 0).unwrap();
                    let in_core = composite_textures(&upload(&grid, &list).unwrap(), &list, &tf, 96, 96, None).unwrap();
                    let textures = upload_read(&shape, &list, read).unwrap();
                    assert_eq!(textures.bytes(), upload(&grid, &list).unwrap().bytes());
                    let from_store = composite_textures(&textures, &list, &tf, 96, 96, None).unwrap();
                    assert!(
                        in_core == from_store,
                        "{dataset:?} shaded {shaded} budget {budget} {format:?}: the store's picture differs"
                    );
                }
            }
            assert!(strides.len() >= 3, "{dataset:?}: budgets should leave several strides, got {strides:?}");
        }
        let _ = std::fs::remove_dir_all(&path);
    }
}
