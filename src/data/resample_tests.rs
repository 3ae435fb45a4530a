use super::*;
use crate::data::grid::GridShape;

/// The test pattern of the VTK runs below, x fastest.
fn pattern(dims: [usize; 3], f: impl Fn(usize, usize, usize) -> f64) -> Vec<f64> {
    let mut v = Vec::new();
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                v.push(f(i, j, k));
            }
        }
    }
    v
}

fn bytes(i: usize, j: usize, k: usize) -> f64 {
    ((i * 37 + j * i * 11 + k * 53 + (i * j * k) % 17) % 256) as f64
}

fn u8_of(v: &[f64]) -> Vec<u8> {
    v.iter().map(|&x| x as u8).collect()
}

// Expected values: VTK 9.2 (ParaView 5.11's pvpython), vtkImageResample with
// SetInterpolationModeToCubic() and SetAxisMagnificationFactor(a, f) on an
// image of the same dims, spacing, origin and values.

/// dims 7x6x5, spacing (0.5, 1, 2), origin (1, 2, 3), factors (0.7, 0.8, 0.5):
/// VTK gives dims 5x5x3, spacing (0.7142857142857143, 1.25, 4), origin kept;
/// z (input index 2 k) is plain subsampling.
#[test]
fn u8_image_matches_vtk_image_resample() {
    let dims = [7, 6, 5];
    let data = u8_of(&pattern(dims, bytes));
    let shape = GridShape { dims, spacing: [0.5, 1.0, 2.0], origin: [1.0, 2.0, 3.0] };
    let grid = Grid::new(Samples::U8(&data), shape, 1, None).unwrap();
    let out = resample_cubic(&grid, [0.7, 0.8, 0.5]).unwrap();
    assert_eq!(out.shape.dims, [5, 5, 3]);
    assert_eq!(out.shape.spacing, [0.7142857142857143, 1.25, 4.0]);
    assert_eq!(out.shape.origin, [1.0, 2.0, 3.0]);
    let vtk: Vec<u8> = vec![
        0, 53, 106, 159, 214, 0, 73, 145, 216, 72, 0, 92, 191, 104, 109, 0, 111, 254, 54, 211, 0, 145, 32, 146, 82,
        106, 159, 212, 203, 57, 106, 199, 12, 64, 160, 106, 160, 52, 146, 135, 106, 122, 77, 150, 59, 106, 139, 123,
        190, 130, 212, 160, 59, 115, 170, 212, 6, 113, 175, 204, 212, 42, 143, 193, 57, 212, 66, 202, 73, 162, 212, 74,
        241, 89, 237,
    ];
    assert_eq!(out.samples, SampleBuf::U8(vtk));
}

/// dims 9x8x7 at unit spacing, factor 0.7394 on every axis (a smart
/// mapper's ratio): VTK gives 6x6x5 at spacing 1.352447930754666.
#[test]
fn u8_image_at_a_smart_mapper_ratio_matches_vtk() {
    let dims = [9, 8, 7];
    let data = u8_of(&pattern(dims, bytes));
    let grid = Grid::scalar(Samples::U8(&data), dims).unwrap();
    let out = resample_cubic(&grid, [0.7394; 3]).unwrap();
    assert_eq!(out.shape.dims, [6, 6, 5]);
    assert_eq!(out.shape.spacing, [1.352447930754666; 3]);
    let vtk: Vec<u8> = vec![
        0, 50, 100, 150, 213, 43, 0, 70, 140, 218, 117, 86, 0, 90, 195, 72, 94, 225, 0, 111, 233, 69, 195, 81, 0, 142,
        55, 133, 90, 151, 0, 162, 112, 190, 83, 82, 72, 121, 179, 229, 108, 58, 72, 153, 166, 133, 83, 171, 72, 155,
        77, 87, 190, 80, 72, 172, 75, 161, 92, 113, 72, 173, 109, 189, 69, 151, 72, 153, 135, 33, 156, 108, 143, 208,
        106, 100, 78, 138, 143, 172, 31, 100, 167, 186, 143, 177, 68, 156, 69, 77, 143, 190, 100, 236, 54, 220, 143,
        44, 185, 44, 140, 87, 143, 81, 92, 93, 155, 152, 206, 175, 50, 109, 160, 202, 206, 0, 112, 184, 159, 75, 206,
        38, 143, 248, 41, 196, 206, 63, 207, 28, 171, 46, 206, 82, 157, 104, 205, 141, 206, 113, 77, 161, 69, 227, 15,
        71, 134, 184, 204, 40, 15, 114, 195, 141, 25, 135, 15, 138, 189, 75, 151, 195, 15, 162, 51, 121, 190, 103, 15,
        174, 90, 175, 83, 160, 15, 166, 127, 151, 131, 91,
    ];
    assert_eq!(out.samples, SampleBuf::U8(vtk));
}

/// A linear ramp is resampled exactly wherever the four taps of every axis
/// lie inside the grid (Catmull-Rom reproduces linear data), at the
/// positions VTK's fixed-point floor rounds to 2^-16; at the border the
/// clamped taps bend it, as in VTK (values from the same VTK run).
#[test]
fn linear_ramp_is_exact_inside_and_bent_as_vtk_at_the_border() {
    let dims = [9, 8, 7];
    let ramp = |x: f64, y: f64, z: f64| 0.5 * x - 2.0 * y + 3.0 * z + 1.0;
    let data: Vec<f32> =
        pattern(dims, |i, j, k| ramp(i as f64, j as f64, k as f64)).iter().map(|&v| v as f32).collect();
    let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
    let out = resample_cubic(&grid, [0.7394; 3]).unwrap();
    let SampleBuf::F32(v) = &out.samples else { panic!("f32 in, f32 out") };
    let [mx, my, mz] = out.shape.dims;
    assert_eq!([mx, my, mz], [6, 6, 5]);
    let scale = 1.352447930754666;
    let mut inside = 0;
    for k in 0..mz {
        for j in 0..my {
            for i in 0..mx {
                let x = [i, j, k].map(|n| n as f64 * scale);
                let interior = (0..3).all(|a| x[a].floor() >= 1.0 && x[a].floor() + 2.0 <= (dims[a] - 1) as f64);
                if interior {
                    inside += 1;
                    let got = v[i + mx * (j + my * k)] as f64;
                    assert!((got - ramp(x[0], x[1], x[2])).abs() < 1e-4, "({i},{j},{k}): {got}");
                }
            }
        }
    }
    assert!(inside >= 8, "{inside} interior samples");
    // VTK's values at the border, bit for bit.
    for (index, vtk) in [
        (0, 1.0f64),
        (1, 1.6762237548828125),
        (30, -12.662616729736328),
        (35, -9.281497955322266),
        (144, 17.37803840637207),
        (179, 7.096541404724121),
    ] {
        assert_eq!(f64::from(v[index]), vtk, "sample {index}");
    }
}

/// Factor 1 keeps every sample (one tap); the cubic's overshoot at a step
/// is clamped to the type's range; bad factors are refused by name.
#[test]
fn identity_clamping_and_refusals() {
    let dims = [5, 4, 3];
    let data: Vec<i16> =
        pattern(dims, |i, _, _| if i < 2 { -32768.0 } else { 32767.0 }).iter().map(|&v| v as i16).collect();
    let grid = Grid::scalar(Samples::I16(&data), dims).unwrap();
    let same = resample_cubic(&grid, [1.0; 3]).unwrap();
    assert_eq!(same.samples, SampleBuf::I16(data.clone()));
    // x = 2 * 4/3: taps MIN, MAX, MAX, MAX at t = 2/3, MAX + (t/2 (1 - t)^2) 65535 > MAX.
    let step = resample_cubic(&grid, [0.75, 1.0, 1.0]).unwrap();
    assert_eq!(step.shape.dims, [4, 4, 3]);
    let SampleBuf::I16(v) = &step.samples else { panic!("i16 in, i16 out") };
    for row in v.chunks(4) {
        assert_eq!(row[0], i16::MIN);
        assert!(row[1] > i16::MIN && row[1] < i16::MAX, "{row:?}");
        assert_eq!(row[2], i16::MAX);
        assert_eq!(row[3], i16::MAX);
    }
    for (factors, needle) in [
        ([0.0, 1.0, 1.0], "finite number > 0"),
        ([f64::NAN, 1.0, 1.0], "finite number > 0"),
        ([1.0, 1.0, 0.4], "at least 2"),
    ] {
        let e = resample_cubic(&grid, factors).unwrap_err().to_string();
        assert!(e.contains(needle), "{factors:?}: {e}");
    }
}

/// The output does not depend on the number of threads.
#[test]
fn deterministic_across_thread_counts() {
    let dims = [33, 30, 28];
    let data: Vec<f32> =
        pattern(dims, |i, j, k| ((i * 7 + j * 13 + k * 29) % 31) as f64 * 0.37).iter().map(|&v| v as f32).collect();
    let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| resample_cubic(&grid, [0.61, 0.7, 0.83]).unwrap())
    };
    assert_eq!(run(1), run(3));
}
