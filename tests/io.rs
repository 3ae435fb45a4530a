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
