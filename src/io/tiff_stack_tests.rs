use super::*;
use tiff::encoder::colortype::{Gray16, Gray32Float, Gray8, RGB8};
use tiff::encoder::compression::DeflateLevel;
use tiff::encoder::{Compression, Rational, TiffEncoder};

/// A fresh, empty folder under the system's temporary folder.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hybrid-octree-tiff-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Value of sample (x, y, z) of the test volumes: distinct on every axis.
fn value(x: usize, y: usize, z: usize) -> u16 {
    (x + 7 * y + 61 * z) as u16
}

fn plane16(w: usize, h: usize, z: usize) -> Vec<u16> {
    (0..w * h).map(|i| value(i % w, i / w, z)).collect()
}

fn write_slice16(path: &Path, w: usize, h: usize, z: usize, compression: Compression) {
    let file = std::fs::File::create(path).unwrap();
    let mut enc = TiffEncoder::new(file).unwrap().with_compression(compression);
    enc.write_image::<Gray16>(w as u32, h as u32, &plane16(w, h, z)).unwrap();
}

#[test]
fn a_folder_of_slices_is_read_in_natural_order() {
    let dir = folder("natural");
    let (w, h, n) = (13, 9, 21);
    for z in 0..n {
        // Unpadded numbers: "s10" sorts after "s9" only in natural order.
        write_slice16(&dir.join(format!("s{}.TIF", z + 1)), w, h, z, Compression::Uncompressed);
    }
    std::fs::write(dir.join("._s1.tif"), b"macOS metadata, not a slice").unwrap();
    std::fs::write(dir.join("notes.txt"), b"not a slice").unwrap();
    let stack = TiffStack::open(&dir).unwrap();
    assert_eq!(stack.dims, [w, h, n]);
    assert_eq!(stack.scalar_type, ScalarType::U16);
    assert_eq!(stack.shape.spacing, [1.0; 3]);
    let volume = stack.read_volume().unwrap();
    let expected: Vec<u16> = (0..n).flat_map(|z| plane16(w, h, z)).collect();
    assert_eq!(volume.samples, SampleBuf::U16(expected.clone()));
    // A range across several runs of pages.
    let part = stack.read_planes(3..20).unwrap();
    assert_eq!(part, SampleBuf::U16(expected[3 * w * h..20 * w * h].to_vec()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_multi_page_imagej_stack_keeps_its_calibration() {
    let dir = folder("imagej");
    let path = dir.join("cells.ome.tif");
    let (w, h, n) = (17, 5, 40);
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut enc = TiffEncoder::new(file).unwrap().with_compression(Compression::Lzw);
        for z in 0..n {
            let plane: Vec<u8> = plane16(w, h, z).iter().map(|&v| v as u8).collect();
            let mut image = enc.new_image::<Gray8>(w as u32, h as u32).unwrap();
            if z == 0 {
                let description =
                    format!("ImageJ=1.54f\nimages={n}\nslices={n}\nunit=micron\nspacing=2.5\nloop=false\n");
                image.encoder().write_tag(Tag::ImageDescription, description.as_str()).unwrap();
            }
            // 4 pixels per micron in x, 2 in y.
            image.x_resolution(Rational { n: 4, d: 1 });
            image.y_resolution(Rational { n: 2, d: 1 });
            image.write_data(&plane).unwrap();
        }
    }
    let stack = TiffStack::open(&path).unwrap();
    assert_eq!(stack.dims, [w, h, n]);
    assert_eq!(stack.shape.spacing, [0.25, 0.5, 2.5]);
    assert_eq!(stack.name, "cells");
    let expected: Vec<u8> = (0..n).flat_map(|z| plane16(w, h, z)).map(|v| v as u8).collect();
    assert_eq!(stack.read_volume().unwrap().samples, SampleBuf::U8(expected.clone()));
    assert_eq!(stack.read_planes(17..35).unwrap(), SampleBuf::U8(expected[17 * w * h..35 * w * h].to_vec()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn float_slices_compressed_with_deflate_keep_their_bits() {
    let dir = folder("float");
    let (w, h) = (6, 4);
    let planes: Vec<Vec<f32>> = (0..3)
        .map(|z| (0..w * h).map(|i| if i == 5 { f32::NAN } else { -1.5e30 + (i * z) as f32 }).collect())
        .collect();
    for (z, plane) in planes.iter().enumerate() {
        let file = std::fs::File::create(dir.join(format!("f_{z:03}.tiff"))).unwrap();
        let mut enc = TiffEncoder::new(file).unwrap().with_compression(Compression::Deflate(DeflateLevel::Balanced));
        enc.write_image::<Gray32Float>(w as u32, h as u32, plane).unwrap();
    }
    let volume = TiffStack::open(&dir).unwrap().read_volume().unwrap();
    let SampleBuf::F32(got) = volume.samples else { panic!("f32 slices read as {:?}", volume.samples.scalar_type()) };
    let want: Vec<f32> = planes.concat();
    assert_eq!(
        got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        want.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The message of `TiffStack::open(path)`'s error (the test fails if it opens).
fn open_error(path: &Path) -> String {
    match TiffStack::open(path) {
        Ok(s) => panic!("{} opened as {:?}", path.display(), s.dims),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_stacks_are_refused_with_what_to_do() {
    let dir = folder("bad");
    assert!(open_error(&dir).contains("holds no .tif/.tiff slices"), "{}", open_error(&dir));

    // A slice of another size.
    write_slice16(&dir.join("a1.tif"), 8, 8, 0, Compression::Uncompressed);
    write_slice16(&dir.join("a2.tif"), 8, 7, 1, Compression::Uncompressed);
    let e = open_error(&dir);
    assert!(e.contains("a2.tif") && e.contains("8x7") && e.contains("one size and sample type"), "{e}");
    std::fs::remove_file(dir.join("a2.tif")).unwrap();

    // A colour slice.
    let file = std::fs::File::create(dir.join("a3.tif")).unwrap();
    TiffEncoder::new(file).unwrap().write_image::<RGB8>(8, 8, &[0u8; 8 * 8 * 3]).unwrap();
    let e = open_error(&dir);
    assert!(e.contains("a3.tif") && e.contains("grayscale"), "{e}");
    std::fs::remove_file(dir.join("a3.tif")).unwrap();

    // Not a TIFF.
    std::fs::write(dir.join("a4.tif"), b"PK\x03\x04 a zip file").unwrap();
    let e = open_error(&dir);
    assert!(e.contains("a4.tif") && e.contains("not a TIFF file"), "{e}");
    std::fs::remove_file(dir.join("a4.tif")).unwrap();

    // A hyperstack of two channels.
    let path = dir.join("hyper.tif");
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut enc = TiffEncoder::new(file).unwrap();
        for c in 0..2 {
            let mut image = enc.new_image::<Gray16>(8, 8).unwrap();
            if c == 0 {
                image.encoder().write_tag(Tag::ImageDescription, "ImageJ=1.54f\nimages=2\nchannels=2\n").unwrap();
            }
            image.write_data(&plane16(8, 8, c)).unwrap();
        }
    }
    let e = open_error(&path);
    assert!(e.contains("hyperstack with 2 channels"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn damaged_files_are_errors_never_panics() {
    let dir = folder("damaged");
    let path = dir.join("stack.tif");
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut enc = TiffEncoder::new(file).unwrap().with_compression(Compression::Lzw);
        for z in 0..6 {
            enc.write_image::<Gray16>(32, 32, &plane16(32, 32, z)).unwrap();
        }
    }
    let whole = std::fs::read(&path).unwrap();
    // Every truncation and a sweep of flipped bytes: open and read fail or succeed, never panic.
    for cut in (0..whole.len()).step_by(97) {
        std::fs::write(&path, &whole[..cut]).unwrap();
        if let Ok(stack) = TiffStack::open(&path) {
            let _ = stack.read_volume();
        }
    }
    for at in (8..whole.len()).step_by(53) {
        let mut bytes = whole.clone();
        bytes[at] ^= 0xA5;
        std::fs::write(&path, &bytes).unwrap();
        if let Ok(stack) = TiffStack::open(&path) {
            let _ = stack.read_volume();
        }
    }
    // The file shrinks between opening and reading: an error naming it.
    std::fs::write(&path, &whole).unwrap();
    let stack = TiffStack::open(&path).unwrap();
    std::fs::write(&path, &whole[..whole.len() / 2]).unwrap();
    let e = stack.read_volume().unwrap_err().to_string();
    assert!(e.contains("stack.tif"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn natural_order_compares_numbers_by_value() {
    let mut names = vec!["img10.tif", "img9.tif", "img010b.tif", "img1.tif", "Img2.tif", "img02.tif"];
    names.sort_by_key(|n| natural_key(n));
    assert_eq!(names, ["Img2.tif", "img1.tif", "img02.tif", "img9.tif", "img10.tif", "img010b.tif"]);
}
