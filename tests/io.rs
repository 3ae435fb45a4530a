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

/// Standard base64 with padding (the `.vti` writer's inline and appended encoding).
fn b64(bytes: &[u8]) -> String {
    use base64::Engine;
    base64::engine::general_purpose::STANDARD.encode(bytes)
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

// ---- hostile input: every bad file is a clear error, checked before allocating ----

/// The error of reading `bytes` as a file named `name` in memory.
fn bytes_error(name: &str, bytes: &[u8]) -> String {
    hybrid_octree::io::read_volume_bytes(name, bytes, &ReadOptions::default()).unwrap_err().to_string()
}

/// [`nifti_bytes`] with the voxel data at `vox_offset` (filler before them).
fn nifti_at(vox_offset: f32, data: &[u8]) -> Vec<u8> {
    let mut f = nifti_bytes([3, 4, 5], 4, 16, &[], 0.0, 0.0);
    f[108..112].copy_from_slice(&vox_offset.to_le_bytes());
    if (352.0..1e6).contains(&vox_offset) {
        f.resize(vox_offset as usize, 0xEE);
    }
    f.extend_from_slice(data);
    f
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(bytes).unwrap();
    gz.finish().unwrap()
}

#[test]
fn nifti_vox_offset_is_honoured_and_checked() {
    let (values, bytes) = i16_data();
    for file in [nifti_at(1024.0, &bytes), gzip(&nifti_at(1024.0, &bytes))] {
        let name = if file[0] == 0x1f { "far.nii.gz" } else { "far.nii" };
        let v = hybrid_octree::io::read_volume_bytes(name, &file, &ReadOptions::default()).unwrap();
        assert_eq!(v.samples, SampleBuf::I16(values.clone()), "{name}");
    }
    // An unset vox_offset (0) means 352, as nibabel reads it.
    let mut unset = nifti_at(352.0, &bytes);
    unset[108..112].copy_from_slice(&0f32.to_le_bytes());
    let v = hybrid_octree::io::read_volume_bytes("unset.nii", &unset, &ReadOptions::default()).unwrap();
    assert_eq!(v.samples, SampleBuf::I16(values.clone()), "vox_offset 0");
    for bad in [-1.0, f32::NAN, f32::INFINITY, 348.0, 1.0, 352.5] {
        let e = bytes_error("bad.nii", &nifti_at(bad, &bytes));
        assert!(e.contains("vox_offset") && e.contains("352"), "{bad}: {e}");
    }
    // Beyond the data: for .nii from the file size, for .nii.gz from what gzip can hold.
    let e = bytes_error("beyond.nii", &nifti_at(1e9, &bytes));
    assert!(e.contains("vox_offset") && e.contains("truncated"), "{e}");
    let e = bytes_error("beyond.nii.gz", &gzip(&nifti_at(1e9, &bytes)));
    assert!(e.contains("cannot inflate past"), "{e}");
}

#[test]
fn damaged_nifti_gz_is_refused_by_its_trailer() {
    let (_, bytes) = i16_data();
    let good = gzip(&nifti_bytes([3, 4, 5], 4, 16, &bytes, 0.0, 0.0));
    hybrid_octree::io::read_volume_bytes("ok.nii.gz", &good, &ReadOptions::default()).unwrap();
    let n = good.len();
    let mut crc = good.clone();
    crc[n - 8] ^= 1;
    let mut isize = good.clone();
    isize[n - 2] ^= 1;
    for (what, bad) in [("CRC", crc), ("ISIZE", isize)] {
        let e = bytes_error("bad.nii.gz", &bad);
        assert!(e.contains("corrupt"), "{what}: {e}");
    }
    // A flipped bit anywhere in the deflate data: an error, or (a padding
    // bit after the last block) the same volume; never a different picture.
    let volume = hybrid_octree::io::read_volume_bytes("ok.nii.gz", &good, &ReadOptions::default()).unwrap();
    let mut errors = 0;
    for i in 10..n - 8 {
        let mut bad = good.clone();
        bad[i] ^= 0x10;
        match hybrid_octree::io::read_volume_bytes("flip.nii.gz", &bad, &ReadOptions::default()) {
            Ok(v) => assert_eq!((v.samples, v.shape), (volume.samples.clone(), volume.shape), "flip at {i}"),
            Err(_) => errors += 1,
        }
    }
    assert!(errors * 10 >= (n - 18) * 9, "only {errors} of {} flips refused", n - 18);
}

#[test]
fn nifti_gz_inflation_stops_at_the_declared_size() {
    let (_, bytes) = i16_data();
    // 16 MiB of zeros after the declared voxels (compresses to ~16 KiB).
    let mut body = nifti_bytes([3, 4, 5], 4, 16, &bytes, 0.0, 0.0);
    body.resize(body.len() + (16 << 20), 0);
    let e = bytes_error("bomb.nii.gz", &gzip(&body));
    assert!(e.contains("follow the") && e.contains("does not describe"), "{e}");
    // A header declaring far more than this machine has: refused before reading.
    let mut huge = nifti_bytes([3, 4, 5], 64, 64, &[], 0.0, 0.0);
    for a in 1..=3 {
        huge[40 + 2 * a..42 + 2 * a].copy_from_slice(&30000i16.to_le_bytes());
    }
    huge.resize(huge.len() + (1 << 20), 0);
    let e = bytes_error("huge.nii", &huge);
    assert!(e.contains("truncated"), "{e}");
    let e = bytes_error("huge.nii.gz", &gzip(&huge));
    assert!(e.contains("cannot inflate past") || e.contains("of memory"), "{e}");
}

#[test]
fn nifti_bitpix_mismatch_has_a_nifti_message() {
    let (_, bytes) = i16_data();
    let e = bytes_error("bitpix.nii", &nifti_bytes([3, 4, 5], 4, 8, &bytes, 0.0, 0.0));
    assert!(e.contains("bitpix 8") && e.contains("datatype 4") && !e.contains("--dims"), "{e}");
}

#[test]
fn vti_bombs_are_refused_by_their_declared_sizes() {
    // 2048^3 Float32 in one ZLib block: the extent needs 32 GiB, refused before inflating.
    let attrs = r#"header_type="UInt64" compressor="vtkZLibDataCompressor""#;
    let block = zlib(&vec![0u8; 1 << 20]);
    let need = 4u64 << 30 << 3;
    let head = words(&[1, need, need, block.len() as u64], true, false);
    let file = String::from_utf8(vti_file(attrs, r#"format="appended" offset="0""#, "", None)).unwrap();
    let file = file.replace(EXTENT, "0 2047 0 2047 0 2047").into_bytes();
    let mut file = file[..file.len() - "</VTKFile>\n".len()].to_vec();
    file.extend(b"  <AppendedData encoding=\"raw\">\n   _");
    file.extend([head, block.clone()].concat());
    file.extend(b"\n  </AppendedData>\n</VTKFile>\n");
    let e = bytes_error("bomb.vti", &file);
    assert!(e.contains("needs 32.0 GiB of memory"), "{e}");
    // A block that inflates past its declared 32 bytes.
    let head = words(&[2, 32, 16, block.len() as u64, block.len() as u64], true, false);
    let raw = [head, block.clone(), block].concat();
    let e = bytes_error("inflates.vti", &vti_file(attrs, r#"format="appended" offset="0""#, "", Some(("raw", &raw))));
    assert!(e.contains("more than the 32 bytes its header declares"), "{e}");
}

#[test]
fn only_regular_files_are_read() {
    let zero = temp("zero.vti");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let e = message(read_volume(&zero, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&zero).unwrap();
    assert!(e.contains("a device, not a regular file"), "{e}");
    let fifo = temp("pipe.nii");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let e = message(read_volume(&fifo, &ReadOptions::default()).unwrap_err());
    std::fs::remove_file(&fifo).unwrap();
    assert!(e.contains("named pipe"), "{e}");
}

#[test]
fn echoed_file_text_is_cut_and_escaped() {
    let inline = b64(&uncompressed(true, false));
    let file = String::from_utf8(vti_file(UINT64_LE, r#"format="binary""#, &inline, None)).unwrap();
    let long = file.replace(r#"Spacing="0.5 2 4""#, &format!("Spacing=\"{}\"", "9".repeat(1 << 20)));
    let e = bytes_error("long.vti", long.as_bytes());
    assert!(e.len() < 400 && e.contains("Spacing") && e.contains("1048576 characters"), "{e}");
    let escape = file.replace(r#"Spacing="0.5 2 4""#, "Spacing=\"\x1b[2J\x1b]0;owned\x07\"");
    let e = bytes_error("escape.vti", escape.as_bytes());
    assert!(!e.contains('\x1b') && !e.contains('\x07') && e.contains("\\u{1b}[2J"), "{e}");
    let e = message(read_volume(&temp("evil\x1b[31m.vti"), &ReadOptions::default()).unwrap_err());
    assert!(!e.contains('\x1b') && e.contains("evil\\u{1b}[31m"), "{e}");
}

fn uncompressed_vti() -> Vec<u8> {
    vti_file(UINT64_LE, r#"format="appended" offset="0""#, "", Some(("raw", &uncompressed(true, false))))
}

#[test]
fn a_failed_write_says_write_and_other_extensions_are_refused() {
    let v = generate_dims(Dataset::Sphere, [3, 3, 3], ScalarType::U8);
    let e = write_vti(&temp("no-such-dir").join("x.vti"), &v).unwrap_err();
    assert!(matches!(e, Error::Write { .. }) && e.to_string().starts_with("cannot write"), "{e}");
    let path = temp("x.vtk");
    let e = write_vti(&path, &v).unwrap_err();
    assert!(e.to_string().contains(".vti") && !path.exists(), "{e}");
}

#[test]
fn extensions_are_case_insensitive() {
    let legacy = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n\
                  POINT_DATA 8\nSCALARS s float\n0 1 2 3 4 5 6 7\n";
    read_bytes("UPPER.VTK", legacy.as_bytes()).unwrap();
    let (values, bytes) = i16_data();
    let v = read_bytes("UPPER.NII.GZ", &gzip(&nifti_bytes([3, 4, 5], 4, 16, &bytes, 0.0, 0.0))).unwrap();
    assert_eq!(v.samples, SampleBuf::I16(values));
    check_test_image(&read_bytes("UPPER.Vti", &uncompressed_vti()).unwrap());
}

#[test]
fn legacy_ascii_takes_nan_and_inf_spellings() {
    let text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n\
                ORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 8\nSCALARS s double 1\nLOOKUP_TABLE default\n\
                nan NaN -nan inf -inf Infinity 1e3 -2.5\n";
    let v = read_bytes("nan.vtk", text.as_bytes()).unwrap();
    let SampleBuf::F64(s) = v.samples else { panic!("doubles") };
    assert!(s[..3].iter().all(|x| x.is_nan()), "{s:?}");
    assert_eq!(&s[3..], &[f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, 1e3, -2.5]);
}

#[test]
fn legacy_binary_and_other_attributes_are_read() {
    let mut f = b"# vtk DataFile Version 3.0\nbinary\nBINARY\nDATASET STRUCTURED_POINTS\nSPACING 1 1 2\n\
                  DIMENSIONS 2 2 2\nORIGIN 1 2 3\nPOINT_DATA 8\nVECTORS v float\n"
        .to_vec();
    f.extend((0..24).flat_map(|i| (i as f32).to_be_bytes()));
    f.extend(b"\nFIELD FieldData 1\nids 1 8 int\n");
    f.extend((0..8).flat_map(|i: i32| i.to_be_bytes()));
    f.extend(b"\nSCALARS s short 1\n"); // no LOOKUP_TABLE: the values follow at once
    f.extend((0..8).flat_map(|i: i16| (i * 3 + 10).to_be_bytes()));
    f.extend(b"\nCELL_DATA 1\nSCALARS c float\nLOOKUP_TABLE default\n");
    f.extend(1f32.to_be_bytes());
    let v = read_bytes("binary.vtk", &f).unwrap();
    assert_eq!((v.name.as_str(), v.components), ("s", 1));
    assert_eq!(v.samples, SampleBuf::I16((0..8).map(|i| i * 3 + 10).collect()));
    assert_eq!((v.shape.origin, v.shape.spacing), ([1.0, 2.0, 3.0], [1.0, 1.0, 2.0]));
    let e = bytes_error("short.vtk", &f[..f.len() - 60]);
    assert!(e.contains("truncated"), "{e}");
    let huge = String::from_utf8_lossy(&f).replace("DIMENSIONS 2 2 2", "DIMENSIONS 4000 4000 4000");
    let e = bytes_error("huge.vtk", huge.as_bytes());
    assert!(e.contains("POINT_DATA 8 does not match"), "{e}");
}

#[test]
fn nifti_vox_offset_near_the_float_maximum_is_beyond_the_file() {
    let (_, bytes) = i16_data();
    for name in ["max.nii", "max.nii.gz"] {
        let mut file = nifti_at(f32::MAX, &bytes);
        if name.ends_with(".gz") {
            file = gzip(&file);
        }
        let e = bytes_error(name, &file);
        // Refused up front by the data's end, which must not wrap around.
        let says = if name.ends_with(".gz") { "cannot inflate past" } else { "the file has 472 bytes" };
        assert!(e.contains("the header puts the voxel data at bytes") && e.contains(says), "{e}");
    }
}
