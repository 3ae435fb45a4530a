//! File readers and the `.vti` writer, through the public API.

use hybrid_octree::datasets::{generate_dims, Dataset};
use hybrid_octree::grid::{GridShape, ScalarType};
use hybrid_octree::io::{read_volume, write_vti, RawOptions, ReadOptions};
use hybrid_octree::volume::{SampleBuf, Volume};
use hybrid_octree::Error;
use std::io::Write;
use std::path::PathBuf;

/// A unique path in the temp folder (removed by the caller when done).
fn temp(name: &str) -> PathBuf {
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("hybrid-octree-io-{}-{n}-{name}", std::process::id()))
}

fn message(e: Error) -> String {
    assert!(matches!(e, Error::Format { .. }), "not a Format error: {e:?}");
    e.to_string()
}

fn round_trip(volume: &Volume) -> Volume {
    let path = temp("round.vti");
    write_vti(&path, volume).unwrap();
    let back = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    back
}

#[test]
fn vti_round_trips_every_common_type() {
    for ty in [ScalarType::U8, ScalarType::I16, ScalarType::F32, ScalarType::F64] {
        let mut v = generate_dims(Dataset::SheppLogan, [9, 6, 5], ty);
        v.shape.spacing = [0.5, 1.25, 2.0];
        v.shape.origin = [-3.0, 0.25, 10.0];
        let back = round_trip(&v);
        assert_eq!(back, v, "{ty:?}");
    }
}

#[test]
fn vti_keeps_multi_component_arrays() {
    let values: Vec<f32> = (0..2 * 3 * 4 * 3).map(|i| i as f32 * 0.5).collect();
    let v = Volume {
        samples: SampleBuf::F32(values),
        shape: GridShape { dims: [2, 3, 4], spacing: [1.0; 3], origin: [0.0; 3] },
        components: 3,
        name: "velocity".into(),
    };
    let back = round_trip(&v);
    assert_eq!(back, v);
    assert!(back.grid(None).is_err(), "three components need a choice");
    assert_eq!(back.grid(Some(2)).unwrap().value(1, 0, 0), 2.5);
}

#[test]
fn truncated_vti_is_an_error() {
    let v = generate_dims(Dataset::Sphere, [8, 8, 8], ScalarType::F32);
    let path = temp("truncated.vti");
    write_vti(&path, &v).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
    let e = message(read_volume(&path, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&path).unwrap();
    assert!(e.contains("truncated or corrupt"), "{e}");
}

#[test]
fn cell_only_vti_is_refused_with_a_reason() {
    let path = temp("cells.vti");
    std::fs::write(
        &path,
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
    <Piece Extent="0 1 0 1 0 1">
      <PointData></PointData>
      <CellData Scalars="density">
        <DataArray type="Float32" Name="density" format="ascii">1.5</DataArray>
      </CellData>
    </Piece>
  </ImageData>
</VTKFile>
"#,
    )
    .unwrap();
    let e = message(read_volume(&path, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&path).unwrap();
    assert!(e.contains("only cell data") && e.contains("point scalars"), "{e}");
}

#[test]
fn active_scalars_are_chosen_over_the_first_array() {
    let path = temp("active.vti");
    std::fs::write(
        &path,
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="1 2 3" Spacing="0.5 0.5 0.5">
    <Piece Extent="0 1 0 1 0 1">
      <PointData Scalars="b">
        <DataArray type="Int32" Name="a" format="ascii">0 0 0 0 0 0 0 0</DataArray>
        <DataArray type="UInt16" Name="b" format="ascii">1 2 3 4 5 6 7 8</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
"#,
    )
    .unwrap();
    let v = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(v.name, "b");
    assert_eq!(v.samples, SampleBuf::U16((1..=8).collect()));
    assert_eq!(v.shape.origin, [1.0, 2.0, 3.0]);
    assert_eq!(v.shape.spacing, [0.5; 3]);
}

/// A minimal NIfTI-1 single file: 348-byte header, 4 extension bytes, data.
fn nifti_bytes(dims: [u16; 3], datatype: i16, bitpix: i16, data: &[u8], slope: f32, inter: f32) -> Vec<u8> {
    let mut h = vec![0u8; 352];
    h[0..4].copy_from_slice(&348i32.to_le_bytes());
    let dim: [i16; 8] = [3, dims[0] as i16, dims[1] as i16, dims[2] as i16, 1, 1, 1, 1];
    for (i, d) in dim.iter().enumerate() {
        h[40 + 2 * i..42 + 2 * i].copy_from_slice(&d.to_le_bytes());
    }
    h[70..72].copy_from_slice(&datatype.to_le_bytes());
    h[72..74].copy_from_slice(&bitpix.to_le_bytes());
    let pixdim: [f32; 8] = [1.0, 0.5, 0.75, 2.0, 1.0, 1.0, 1.0, 1.0];
    for (i, p) in pixdim.iter().enumerate() {
        h[76 + 4 * i..80 + 4 * i].copy_from_slice(&p.to_le_bytes());
    }
    h[108..112].copy_from_slice(&352f32.to_le_bytes());
    h[112..116].copy_from_slice(&slope.to_le_bytes());
    h[116..120].copy_from_slice(&inter.to_le_bytes());
    h[252..254].copy_from_slice(&1i16.to_le_bytes()); // qform_code
    for (i, o) in [-10.0f32, 20.0, 30.5].iter().enumerate() {
        h[268 + 4 * i..272 + 4 * i].copy_from_slice(&o.to_le_bytes());
    }
    h[344..348].copy_from_slice(b"n+1\0");
    h.extend_from_slice(data);
    h
}

fn i16_data() -> (Vec<i16>, Vec<u8>) {
    let values: Vec<i16> = (0..3 * 4 * 5).map(|i| i * 37 - 1000).collect();
    let bytes = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    (values, bytes)
}

#[test]
fn nifti_reads_values_and_geometry() {
    let (values, bytes) = i16_data();
    let path = temp("head.nii");
    std::fs::write(&path, nifti_bytes([3, 4, 5], 4, 16, &bytes, 0.0, 0.0)).unwrap();
    let v = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(v.shape.dims, [3, 4, 5]);
    assert_eq!(v.shape.spacing, [0.5, 0.75, 2.0]);
    assert_eq!(v.shape.origin, [-10.0, 20.0, 30.5]);
    assert_eq!(v.samples, SampleBuf::I16(values));
}

#[test]
fn gzipped_nifti_reads_the_same() {
    let (values, bytes) = i16_data();
    let path = temp("head.nii.gz");
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&nifti_bytes([3, 4, 5], 4, 16, &bytes, 0.0, 0.0)).unwrap();
    std::fs::write(&path, gz.finish().unwrap()).unwrap();
    let v = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(v.samples, SampleBuf::I16(values));
    assert_eq!(v.name, path.file_name().unwrap().to_string_lossy().trim_end_matches(".nii.gz"));
}

#[test]
fn nifti_scaling_is_applied() {
    let bytes: Vec<u8> = (0u8..8).collect();
    let path = temp("scaled.nii");
    std::fs::write(&path, nifti_bytes([2, 2, 2], 2, 8, &bytes, 2.0, -1.0)).unwrap();
    let v = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(v.samples, SampleBuf::F32((0..8).map(|i| 2.0 * i as f32 - 1.0).collect()));
}

#[test]
fn truncated_nifti_is_an_error() {
    let (_, bytes) = i16_data();
    let path = temp("short.nii");
    std::fs::write(&path, nifti_bytes([3, 4, 5], 4, 16, &bytes[..50], 0.0, 0.0)).unwrap();
    let e = message(read_volume(&path, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&path).unwrap();
    assert!(e.contains("truncated or corrupt"), "{e}");
}

#[test]
fn raw_reads_with_layout_and_checks_the_size() {
    let values: Vec<u16> = (0..4 * 3 * 2).collect();
    let path = temp("volume.raw");
    std::fs::write(&path, values.iter().flat_map(|v| v.to_be_bytes()).collect::<Vec<u8>>()).unwrap();
    let mut raw = RawOptions::new([4, 3, 2], ScalarType::U16);
    raw.big_endian = true;
    raw.spacing = [0.1, 0.2, 0.3];
    let v = read_volume(&path, &ReadOptions { raw: Some(raw.clone()) }).unwrap();
    assert_eq!(v.samples, SampleBuf::U16(values));
    assert_eq!(v.shape.spacing, [0.1, 0.2, 0.3]);

    raw.dims = [4, 3, 3];
    let e = message(read_volume(&path, &ReadOptions { raw: Some(raw) }).unwrap_err());
    assert!(e.contains("has 48 bytes") && e.contains("need 72 bytes") && e.contains("--dims"), "{e}");

    let e = message(read_volume(&path, &ReadOptions::default()).unwrap_err());
    assert!(e.contains("--dims") && e.contains("--type"), "{e}");
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn missing_file_and_unknown_extension_are_explained() {
    let e = message(read_volume(&temp("absent.vti"), &ReadOptions::default()).unwrap_err());
    assert!(e.contains("does not exist"), "{e}");
    let path = temp("volume.xyz");
    std::fs::write(&path, [0u8; 8]).unwrap();
    let e = message(read_volume(&path, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&path).unwrap();
    assert!(e.contains(".vti") && e.contains(".nii.gz") && e.contains("--dims"), "{e}");
}

#[test]
fn legacy_structured_points_are_read() {
    let path = temp("legacy.vtk");
    std::fs::write(
        &path,
        "# vtk DataFile Version 3.0\nlegacy test\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n\
         ORIGIN 1 2 3\nSPACING 0.5 0.5 2\nPOINT_DATA 8\nSCALARS density float 1\nLOOKUP_TABLE default\n\
         0 1 2 3 4 5 6 7\n",
    )
    .unwrap();
    let v = read_volume(&path, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(v.name, "density");
    assert_eq!(v.shape.dims, [2, 2, 2]);
    assert_eq!(v.shape.origin, [1.0, 2.0, 3.0]);
    assert_eq!(v.shape.spacing, [0.5, 0.5, 2.0]);
    assert_eq!(v.samples, SampleBuf::F32((0..8).map(|i| i as f32).collect()));
}

// ---- .vti files in every encoding vtkXMLImageDataWriter produces, written byte by byte ----

/// The test image: 3 x 2 x 2 points, extent `1 3 0 1 -1 0`, so the first
/// point sits at `Origin + (1, 0, -1) * Spacing`.
const EXTENT: &str = "1 3 0 1 -1 0";
fn vti_values() -> Vec<f32> {
    (0..12).map(|i| i as f32 * 1.5 - 4.0).collect()
}

/// Standard base64 with padding.
fn b64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for i in 0..4 {
            s.push(if i <= c.len() { A[(n >> (18 - 6 * i) & 63) as usize] as char } else { '=' });
        }
    }
    s
}

/// Header words of `header_type` (8 or 4 bytes) in the given byte order.
fn words(values: &[u64], u64_words: bool, big: bool) -> Vec<u8> {
    let mut out = Vec::new();
    for &v in values {
        match (u64_words, big) {
            (true, false) => out.extend(v.to_le_bytes()),
            (true, true) => out.extend(v.to_be_bytes()),
            (false, false) => out.extend((v as u32).to_le_bytes()),
            (false, true) => out.extend((v as u32).to_be_bytes()),
        }
    }
    out
}

fn f32_bytes(values: &[f32], big: bool) -> Vec<u8> {
    values.iter().flat_map(|v| if big { v.to_be_bytes() } else { v.to_le_bytes() }).collect()
}

/// A `.vti` file like VTK writes it. `file_attrs` go on `VTKFile`,
/// `array_attrs` on the one point `DataArray` (whose text is `inline`);
/// `appended` is `(encoding, bytes after the '_')`.
fn vti_file(file_attrs: &str, array_attrs: &str, inline: &str, appended: Option<(&str, &[u8])>) -> Vec<u8> {
    let mut f = format!(
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" {file_attrs}>
  <ImageData WholeExtent="{EXTENT}" Origin="10 20 30" Spacing="0.5 2 4" Direction="1 0 0 0 1 0 0 0 1">
    <Piece Extent="{EXTENT}">
      <PointData Scalars="density">
        <DataArray type="Float32" Name="density" {array_attrs}>
          <InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
            <Value index="0">1</Value>
          </InformationKey>
          {inline}
        </DataArray>
      </PointData>
      <CellData>
      </CellData>
    </Piece>
  </ImageData>
"#
    )
    .into_bytes();
    if let Some((encoding, bytes)) = appended {
        f.extend(format!("  <AppendedData encoding=\"{encoding}\">\n   _").bytes());
        f.extend_from_slice(bytes);
        f.extend(b"\n  </AppendedData>\n");
    }
    f.extend(b"</VTKFile>\n");
    f
}

fn read_bytes(name: &str, bytes: &[u8]) -> hybrid_octree::Result<Volume> {
    let path = temp(name);
    std::fs::write(&path, bytes).unwrap();
    let result = read_volume(&path, &ReadOptions::default());
    std::fs::remove_file(&path).unwrap();
    result
}

fn check_test_image(v: &Volume) {
    assert_eq!(v.name, "density");
    assert_eq!(v.shape.dims, [3, 2, 2]);
    assert_eq!(v.shape.spacing, [0.5, 2.0, 4.0]);
    assert_eq!(v.shape.origin, [10.5, 20.0, 26.0]);
    assert_eq!(v.components, 1);
    assert_eq!(v.samples, SampleBuf::F32(vti_values()));
}

/// Uncompressed binary: `[nbytes]` then the values.
fn uncompressed(u64_words: bool, big: bool) -> Vec<u8> {
    let data = f32_bytes(&vti_values(), big);
    let mut out = words(&[data.len() as u64], u64_words, big);
    out.extend(data);
    out
}

/// Compressed binary: `[nblocks, block_size, last_size, csizes..]` and the
/// blocks, with 32-byte blocks (48 bytes: one full block, one of 16).
fn compressed(compress: impl Fn(&[u8]) -> Vec<u8>, u64_words: bool, big: bool) -> (Vec<u8>, Vec<u8>) {
    let data = f32_bytes(&vti_values(), big);
    let blocks: Vec<Vec<u8>> = data.chunks(32).map(compress).collect();
    let mut head = vec![blocks.len() as u64, 32, 16];
    head.extend(blocks.iter().map(|b| b.len() as u64));
    (words(&head, u64_words, big), blocks.concat())
}

fn zlib(bytes: &[u8]) -> Vec<u8> {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes).unwrap();
    z.finish().unwrap()
}

const UINT64_LE: &str = r#"byte_order="LittleEndian" header_type="UInt64""#;

#[test]
fn vti_appended_raw_with_uint64_header() {
    let v = read_bytes(
        "raw64.vti",
        &vti_file(UINT64_LE, r#"format="appended" offset="0""#, "", Some(("raw", &uncompressed(true, false)))),
    )
    .unwrap();
    check_test_image(&v);
}

#[test]
fn vti_appended_raw_with_uint32_header_big_endian_and_default_header_type() {
    let attrs = r#"format="appended" offset="0""#;
    let v = read_bytes(
        "raw32be.vti",
        &vti_file(
            r#"byte_order="BigEndian" header_type="UInt32""#,
            attrs,
            "",
            Some(("raw", &uncompressed(false, true))),
        ),
    )
    .unwrap();
    check_test_image(&v);
    // header_type absent (version 0.1 files): UInt32.
    let v = read_bytes(
        "raw32.vti",
        &vti_file(r#"byte_order="LittleEndian""#, attrs, "", Some(("raw", &uncompressed(false, false)))),
    )
    .unwrap();
    check_test_image(&v);
}

#[test]
fn vti_appended_raw_at_an_offset_behind_another_array() {
    // Another (cell) array's bytes come first; the point array is at offset 52.
    let mut appended = uncompressed(false, false);
    assert_eq!(appended.len(), 52);
    appended.extend(uncompressed(false, false));
    let v = read_bytes("offset.vti", &vti_file("", r#"format="appended" offset="52""#, "", Some(("raw", &appended))))
        .unwrap();
    check_test_image(&v);
}

#[test]
fn vti_appended_base64() {
    let attrs = r#"format="appended" offset="0""#;
    // As one base64 run (how VTK encodes an uncompressed header and data) ...
    let text = b64(&uncompressed(true, false));
    check_test_image(
        &read_bytes("b64.vti", &vti_file(UINT64_LE, attrs, "", Some(("base64", text.as_bytes())))).unwrap(),
    );
    // ... and as two separately padded runs (UInt32 header: "xxxxxx==" then the data).
    let data = f32_bytes(&vti_values(), false);
    let text = b64(&words(&[48], false, false)) + &b64(&data);
    assert!(text[..8].ends_with("=="));
    check_test_image(&read_bytes("b64s.vti", &vti_file("", attrs, "", Some(("base64", text.as_bytes())))).unwrap());
}

#[test]
fn vti_inline_binary() {
    let text = b64(&uncompressed(true, false));
    // Whitespace inside base64 text is skipped.
    let text = format!("{}\n          {}", &text[..16], &text[16..]);
    let v = read_bytes("binary.vti", &vti_file(UINT64_LE, r#"format="binary""#, &text, None)).unwrap();
    check_test_image(&v);
}

#[test]
fn vti_ascii() {
    let text: Vec<String> = vti_values().iter().map(|v| v.to_string()).collect();
    let v = read_bytes("ascii.vti", &vti_file("", r#"format="ascii""#, &text.join(" "), None)).unwrap();
    check_test_image(&v);
}

#[test]
fn vti_zlib_compressed_appended_raw_and_base64_and_inline() {
    let zattrs =
        |header: &str| format!(r#"byte_order="{header}" header_type="UInt64" compressor="vtkZLibDataCompressor""#);
    let appended = r#"format="appended" offset="0""#;
    for big in [false, true] {
        let order = if big { "BigEndian" } else { "LittleEndian" };
        let (head, blocks) = compressed(zlib, true, big);
        let raw = [head.clone(), blocks.clone()].concat();
        check_test_image(
            &read_bytes("zraw.vti", &vti_file(&zattrs(order), appended, "", Some(("raw", &raw)))).unwrap(),
        );
        // VTK base64-encodes the compression header and the blocks separately.
        let text = b64(&head) + &b64(&blocks);
        check_test_image(
            &read_bytes("zb64.vti", &vti_file(&zattrs(order), appended, "", Some(("base64", text.as_bytes()))))
                .unwrap(),
        );
        check_test_image(
            &read_bytes("zbin.vti", &vti_file(&zattrs(order), r#"format="binary""#, &text, None)).unwrap(),
        );
    }
    // UInt32 header words.
    let (head, blocks) = compressed(zlib, false, false);
    let attrs = r#"header_type="UInt32" compressor="vtkZLibDataCompressor""#;
    check_test_image(
        &read_bytes("z32.vti", &vti_file(attrs, appended, "", Some(("raw", &[head, blocks].concat())))).unwrap(),
    );
}

#[test]
fn vti_lz4_and_lzma_compressed() {
    let appended = r#"format="appended" offset="0""#;
    let (head, blocks) = compressed(lz4_flex::block::compress, true, false);
    let attrs = r#"header_type="UInt64" compressor="vtkLZ4DataCompressor""#;
    check_test_image(
        &read_bytes("lz4.vti", &vti_file(attrs, appended, "", Some(("raw", &[head, blocks].concat())))).unwrap(),
    );
    let xz = |b: &[u8]| {
        let mut e = xz2::write::XzEncoder::new(Vec::new(), 6);
        e.write_all(b).unwrap();
        e.finish().unwrap()
    };
    let (head, blocks) = compressed(xz, false, true);
    let attrs = r#"byte_order="BigEndian" compressor="vtkLZMADataCompressor""#;
    check_test_image(
        &read_bytes("xz.vti", &vti_file(attrs, appended, "", Some(("raw", &[head, blocks].concat())))).unwrap(),
    );
}

#[test]
fn vti_without_direction_and_with_other_types_and_components() {
    let path_bytes = br#"<VTKFile type="ImageData" byte_order="LittleEndian">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
    <Piece Extent="0 1 0 1 0 1">
      <PointData>
        <DataArray type="Int8" Name="pair" NumberOfComponents="2" format="ascii">-1 2 -3 4 -5 6 -7 8 -9 10 -11 12 -13 14 -15 16</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>"#;
    let v = read_bytes("int8.vti", path_bytes).unwrap();
    assert_eq!(v.components, 2);
    assert_eq!(v.samples, SampleBuf::I8((1..=16).map(|i| if i % 2 == 1 { -i } else { i }).collect()));
    for (ty, expect) in [
        ("UInt8", SampleBuf::U8(vec![7; 8])),
        ("Int16", SampleBuf::I16(vec![7; 8])),
        ("UInt16", SampleBuf::U16(vec![7; 8])),
        ("Int32", SampleBuf::I32(vec![7; 8])),
        ("UInt32", SampleBuf::U32(vec![7; 8])),
        ("Float64", SampleBuf::F64(vec![7.0; 8])),
    ] {
        let text = String::from_utf8_lossy(path_bytes)
            .replace(r#"type="Int8""#, &format!(r#"type="{ty}""#))
            .replace(r#"NumberOfComponents="2" "#, "")
            .replace("-1 2 -3 4 -5 6 -7 8 -9 10 -11 12 -13 14 -15 16", "7 7 7 7 7 7 7 7");
        assert_eq!(read_bytes("types.vti", text.as_bytes()).unwrap().samples, expect, "{ty}");
    }
}

fn vti_error(name: &str, bytes: &[u8]) -> String {
    message(read_bytes(name, bytes).unwrap_err())
}

#[test]
fn malformed_vti_files_are_explained() {
    let appended = r#"format="appended" offset="0""#;
    let raw = uncompressed(true, false);

    // Truncated appended block: the file ends inside the data.
    let mut f = vti_file(UINT64_LE, appended, "", Some(("raw", &raw)));
    let cut = f.len() - raw.len() - 30;
    f.truncate(cut + 20);
    let e = vti_error("cut.vti", &f);
    assert!(e.contains("end early") && e.contains("truncated or corrupt"), "{e}");

    // Size mismatch: the header claims 40 bytes where 48 are needed.
    let mut short = words(&[40], true, false);
    short.extend(&raw[8..]);
    let e = vti_error("size.vti", &vti_file(UINT64_LE, appended, "", Some(("raw", &short))));
    assert!(e.contains("holds 40 bytes") && e.contains("need 48"), "{e}");

    // Bad base64.
    let mut text = b64(&raw);
    text.replace_range(20..21, "*");
    let e = vti_error("bad64.vti", &vti_file(UINT64_LE, r#"format="binary""#, &text, None));
    assert!(e.contains("bad base64 character '*'"), "{e}");

    // Base64 cut inside a group.
    let text = b64(&raw);
    let e = vti_error("cut64.vti", &vti_file(UINT64_LE, r#"format="binary""#, &text[..text.len() - 6], None));
    assert!(e.contains("truncated"), "{e}");

    // Missing Piece.
    let f = br#"<VTKFile type="ImageData"><ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1"></ImageData></VTKFile>"#;
    assert!(vti_error("nopiece.vti", f).contains("no <Piece>"));

    // No '_' marker, and an offset past the end.
    let f = vti_file(UINT64_LE, appended, "", Some(("raw", &raw)));
    let f = String::from_utf8_lossy(&f).replace("   _", "   ").into_bytes();
    assert!(vti_error("nomark.vti", &f).contains("'_' marker"));
    let e = vti_error("far.vti", &vti_file(UINT64_LE, r#"format="appended" offset="9999""#, "", Some(("raw", &raw))));
    assert!(e.contains("past the end"), "{e}");

    // Ascii with too few values, or a non-number.
    assert!(vti_error("few.vti", &vti_file("", r#"format="ascii""#, "1 2 3", None)).contains("holds 3 values"));
    assert!(vti_error("nan.vti", &vti_file("", r#"format="ascii""#, "1 2 x", None)).contains("'x'"));

    // Corrupt and inconsistent compressed data.
    let zattrs = r#"header_type="UInt64" compressor="vtkZLibDataCompressor""#;
    let (head, mut blocks) = compressed(zlib, true, false);
    blocks[4] ^= 0x55;
    let e = vti_error("zbad.vti", &vti_file(zattrs, appended, "", Some(("raw", &[head.clone(), blocks].concat()))));
    assert!(e.contains("does not decompress"), "{e}");
    let huge = words(&[u64::MAX / 4, 32, 16], true, false);
    let e = vti_error("zhuge.vti", &vti_file(zattrs, appended, "", Some(("raw", &huge))));
    assert!(e.contains("need 48 bytes"), "{e}");
    let lying = words(&[1, 48, 0, 1 << 40], true, false);
    let e = vti_error("zlie.vti", &vti_file(zattrs, appended, "", Some(("raw", &lying))));
    assert!(e.contains("end early"), "{e}");

    // Unsupported settings name what to do.
    let e =
        vti_error("zstd.vti", &vti_file(r#"compressor="vtkZstdDataCompressor""#, appended, "", Some(("raw", &raw))));
    assert!(e.contains("vtkZstdDataCompressor") && e.contains("uncompressed"), "{e}");
    let f =
        String::from_utf8_lossy(&vti_file(UINT64_LE, appended, "", Some(("raw", &raw)))).replace("Float32", "Int64");
    assert!(vti_error("i64.vti", f.as_bytes()).contains("Int64"));
    let f = String::from_utf8_lossy(&vti_file(UINT64_LE, appended, "", Some(("raw", &raw))))
        .replace("1 0 0 0 1 0 0 0 1", "0 1 0 1 0 0 0 0 1");
    assert!(vti_error("rot.vti", f.as_bytes()).contains("Direction"));
    let f = String::from_utf8_lossy(&vti_file(UINT64_LE, appended, "", Some(("raw", &raw))))
        .replace("ImageData", "PolyData");
    let e = vti_error("poly.vti", f.as_bytes());
    assert!(e.contains("PolyData") && e.contains("Resample To Image"), "{e}");
}

#[test]
fn damaged_vti_files_never_panic() {
    let appended = r#"format="appended" offset="0""#;
    let zattrs = r#"header_type="UInt32" compressor="vtkZLibDataCompressor""#;
    let (head, blocks) = compressed(zlib, false, false);
    let (lhead, lblocks) = compressed(lz4_flex::block::compress, true, false);
    let files = [
        vti_file(UINT64_LE, appended, "", Some(("raw", &uncompressed(true, false)))),
        vti_file(UINT64_LE, r#"format="binary""#, &b64(&uncompressed(true, false)), None),
        vti_file(zattrs, appended, "", Some(("raw", &[head.clone(), blocks.clone()].concat()))),
        vti_file(zattrs, appended, "", Some(("base64", (b64(&head) + &b64(&blocks)).as_bytes()))),
        vti_file(
            r#"compressor="vtkLZ4DataCompressor" header_type="UInt64""#,
            appended,
            "",
            Some(("raw", &[lhead, lblocks].concat())),
        ),
    ];
    let path = temp("damaged.vti");
    for file in &files {
        // Every truncation from the point array on, and a flipped byte at every such position.
        let start = file.windows(10).position(|w| w == b"<DataArray").unwrap();
        for i in start..file.len() {
            for damaged in [file[..i].to_vec(), {
                let mut f = file.clone();
                f[i] ^= 0xA5;
                f
            }] {
                std::fs::write(&path, &damaged).unwrap();
                match std::panic::catch_unwind(|| read_volume(&path, &ReadOptions::default())) {
                    Ok(Ok(_)) => {}
                    Ok(Err(e)) => assert!(matches!(e, Error::Format { .. }), "{e:?}"),
                    Err(_) => panic!("panic on a damaged file (byte {i})"),
                }
            }
        }
    }
    std::fs::remove_file(&path).unwrap();
}
