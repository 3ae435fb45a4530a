//! The fuzzing seed corpus: one small valid file (a 5x4x3 volume, or a point
//! set) per reader and encoding, built here byte by byte so that the corpus
//! is reproducible (`cargo test --release --test fuzz_readers -- --ignored
//! write_seed_corpus` writes it to `fuzz/seeds/<target>/`).

use hybrid_octree::datasets::{generate_dims, Dataset};
use hybrid_octree::grid::ScalarType;
use hybrid_octree::io::write_vti;
use hybrid_octree::points::storage::encode;
use hybrid_octree::points::{generate, PointOptions, PointSelect};
use std::io::Write;

/// The readers, by the fuzz target names.
pub const TARGETS: [&str; 6] = ["vti", "vtk", "nifti", "tiff", "raw", "hopoints"];

/// A seed: the target it feeds, the file name (its extension picks the
/// format) and the bytes.
pub struct Seed {
    pub target: &'static str,
    pub name: &'static str,
    pub bytes: Vec<u8>,
}

const DIMS: [usize; 3] = [5, 4, 3];

/// The layout prefix of a raw seed: dims 5, 4, 3 (u16 each), type 2 (u16),
/// flags 0 (one component, little endian). See [`raw_layout`].
const RAW_U16_5X4X3: [u8; 8] = [5, 0, 4, 0, 3, 0, 2, 0];

#[path = "../../fuzz/raw_layout.rs"]
mod raw_layout;
pub use raw_layout::raw_layout;

const COUNT: usize = 60;

fn values() -> Vec<f32> {
    (0..COUNT).map(|i| (i as f32 * 0.37).sin() * 100.0).collect()
}

fn le(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Standard base64 with padding (the `.vti` writer's inline and appended encoding).
fn b64(bytes: &[u8]) -> String {
    use base64::Engine;
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn words(values: &[u64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A `.vti` with `file_attrs` on `VTKFile`, the array's `format` attributes
/// and text, and the appended section if any.
fn vti(file_attrs: &str, array_attrs: &str, inline: &str, appended: Option<(&str, Vec<u8>)>) -> Vec<u8> {
    let mut f = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\" {file_attrs}>\n<ImageData WholeExtent=\"0 4 0 3 0 2\" Origin=\"1 2 3\" \
         Spacing=\"0.5 1 2\" Direction=\"1 0 0 0 1 0 0 0 1\">\n<Piece Extent=\"0 4 0 3 0 2\">\n\
         <PointData Scalars=\"v\">\n<DataArray type=\"Float32\" Name=\"v\" {array_attrs}>{inline}</DataArray>\n\
         </PointData>\n</Piece>\n</ImageData>\n"
    )
    .into_bytes();
    if let Some((encoding, bytes)) = appended {
        f.extend(format!("<AppendedData encoding=\"{encoding}\">\n_").bytes());
        f.extend(bytes);
        f.extend(b"\n</AppendedData>\n");
    }
    f.extend(b"</VTKFile>\n");
    f
}

/// Compressed blocks of 64 bytes with their header.
fn blocks(compress: impl Fn(&[u8]) -> Vec<u8>) -> Vec<u8> {
    let data = le(&values());
    let blocks: Vec<Vec<u8>> = data.chunks(64).map(compress).collect();
    let last = (data.len() % 64) as u64;
    let mut head = vec![blocks.len() as u64, 64, last];
    head.extend(blocks.iter().map(|b| b.len() as u64));
    [words(&head), blocks.concat()].concat()
}

fn zlib(bytes: &[u8]) -> Vec<u8> {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes).unwrap();
    z.finish().unwrap()
}

fn xz(bytes: &[u8]) -> Vec<u8> {
    let mut z = xz2::write::XzEncoder::new(Vec::new(), 6);
    z.write_all(bytes).unwrap();
    z.finish().unwrap()
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut z = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes).unwrap();
    z.finish().unwrap()
}

/// A NIfTI-1 single file of `data` (`datatype`, `bitpix`) with scaling.
fn nifti(datatype: i16, bitpix: i16, data: &[u8], slope: f32) -> Vec<u8> {
    let mut h = vec![0u8; 352];
    h[0..4].copy_from_slice(&348i32.to_le_bytes());
    let dim: [i16; 8] = [3, 5, 4, 3, 1, 1, 1, 1];
    for (i, d) in dim.iter().enumerate() {
        h[40 + 2 * i..42 + 2 * i].copy_from_slice(&d.to_le_bytes());
    }
    h[70..72].copy_from_slice(&datatype.to_le_bytes());
    h[72..74].copy_from_slice(&bitpix.to_le_bytes());
    for (i, p) in [1.0f32, 0.5, 1.0, 2.0, 1.0, 1.0, 1.0, 1.0].iter().enumerate() {
        h[76 + 4 * i..80 + 4 * i].copy_from_slice(&p.to_le_bytes());
    }
    h[108..112].copy_from_slice(&352f32.to_le_bytes());
    h[112..116].copy_from_slice(&slope.to_le_bytes());
    h[252..254].copy_from_slice(&1i16.to_le_bytes());
    h[344..348].copy_from_slice(b"n+1\0");
    h.extend_from_slice(data);
    h
}

fn legacy_ascii() -> Vec<u8> {
    let text: Vec<String> = values().iter().map(|v| v.to_string()).collect();
    format!(
        "# vtk DataFile Version 3.0\nseed\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nORIGIN 1 2 3\n\
         SPACING 0.5 1 2\nPOINT_DATA 60\nSCALARS v float 1\nLOOKUP_TABLE default\n{}\n",
        text.join(" ")
    )
    .into_bytes()
}

fn legacy_binary() -> Vec<u8> {
    let mut f = b"# vtk DataFile Version 3.0\nseed\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\n\
                  ORIGIN 1 2 3\nSPACING 0.5 1 2\nPOINT_DATA 60\nFIELD FieldData 1\nids 1 2 int\n"
        .to_vec();
    f.extend([0u8, 0, 0, 1, 0, 0, 0, 2]);
    f.extend(b"\nSCALARS v short 1\nLOOKUP_TABLE default\n");
    f.extend((0..COUNT as i16).flat_map(|i| (i * 11 - 300).to_be_bytes()));
    f.extend(b"\nCELL_DATA 24\nSCALARS c unsigned_char\nLOOKUP_TABLE default\n");
    f.extend(0..24u8);
    f.push(b'\n');
    f
}

fn written_vti() -> Vec<u8> {
    // One file per call: the fuzz tests build the seeds on parallel threads.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("hybrid-octree-seed-{}-{call}.vti", std::process::id()));
    write_vti(&path, &generate_dims(Dataset::SheppLogan, DIMS, ScalarType::U16)).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    bytes
}

fn points() -> Vec<u8> {
    let v = generate_dims(Dataset::SheppLogan, [17, 17, 17], ScalarType::F32);
    let set = generate(&v.grid(None).unwrap(), &PointOptions::new(4, PointSelect::Threshold(0.05))).unwrap();
    let mut bytes = encode(&set);
    // Keep the seed small: the header and at most 40 points.
    let count = set.points.len().min(40);
    bytes.truncate(72 + 6 * count);
    bytes[64..72].copy_from_slice(&(count as u64).to_le_bytes());
    bytes
}

/// A multi-page TIFF of three 5x4 16-bit pages (the test values).
fn tiff_stack(compression: tiff::encoder::Compression) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut enc = tiff::encoder::TiffEncoder::new(&mut out).unwrap().with_compression(compression);
        for page in 0..3u16 {
            let plane: Vec<u16> = (0..20u16).map(|i| i * 7 + page * 300).collect();
            enc.write_image::<tiff::encoder::colortype::Gray16>(5, 4, &plane).unwrap();
        }
    }
    out.into_inner()
}

/// Every seed.
pub fn seeds() -> Vec<Seed> {
    let data = le(&values());
    let mut raw = words(&[data.len() as u64]);
    raw.extend(&data);
    let ascii: Vec<String> = values().iter().map(|v| v.to_string()).collect();
    let i16_data: Vec<u8> = (0..COUNT as i16).flat_map(|i| (i * 7 - 200).to_le_bytes()).collect();
    let appended = r#"format="appended" offset="0""#;
    let seed = |target, name, bytes| Seed { target, name, bytes };
    vec![
        seed("vti", "appended-raw.vti", vti("", appended, "", Some(("raw", raw.clone())))),
        seed("vti", "appended-base64.vti", vti("", appended, "", Some(("base64", b64(&raw).into_bytes())))),
        seed("vti", "inline-binary.vti", vti("", r#"format="binary""#, &b64(&raw), None)),
        seed("vti", "ascii.vti", vti("", r#"format="ascii""#, &ascii.join(" "), None)),
        seed(
            "vti",
            "zlib.vti",
            vti(r#"compressor="vtkZLibDataCompressor""#, appended, "", Some(("raw", blocks(zlib)))),
        ),
        seed(
            "vti",
            "lz4.vti",
            vti(r#"compressor="vtkLZ4DataCompressor""#, appended, "", Some(("raw", blocks(lz4_flex::block::compress)))),
        ),
        seed("vti", "lzma.vti", vti(r#"compressor="vtkLZMADataCompressor""#, appended, "", Some(("raw", blocks(xz))))),
        seed("vti", "written.vti", written_vti()),
        seed("vtk", "ascii.vtk", legacy_ascii()),
        seed("vtk", "binary.vtk", legacy_binary()),
        seed("nifti", "i16.nii", nifti(4, 16, &i16_data, 0.0)),
        seed("nifti", "scaled-f32.nii", nifti(16, 32, &data, 2.5)),
        seed("nifti", "i16.nii.gz", gzip(&nifti(4, 16, &i16_data, 0.0))),
        seed("tiff", "lzw-u16.tif", tiff_stack(tiff::encoder::Compression::Lzw)),
        seed("tiff", "plain-u16.tif", tiff_stack(tiff::encoder::Compression::Uncompressed)),
        seed("raw", "u16.raw", [RAW_U16_5X4X3.to_vec(), i16_data].concat()),
        seed("hopoints", "points.hop", points()),
    ]
}
