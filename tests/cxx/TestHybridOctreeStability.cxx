/**
 * Numerical stability of vtkHybridOctreeVolumeMapper under Xvfb: hard
 * images, each against VTK's own vtkGPUVolumeRayCastMapper (rays every
 * spacing) on the same scene. Metric: RMSE of the RGB channels in [0, 1]
 * over the 256x256 window.
 *
 *   constant:    a 33^3 image of one value (the octree is one two-texel
 *                brick; its slices must still span the cube): RMSE < 0.01.
 *   spacing:     the ball image at spacing 1e-6, with the opacity unit
 *                distance and the camera scaled alike, against the
 *                reference at spacing 1: RMSE < 0.01 (the same picture).
 *   direction:   the ball image with a direction matrix (30 degrees about z,
 *                then 20 about x): a VTK user expects it drawn where
 *                vtkImageData puts its points, so the reference is the same
 *                image with the identity direction inside a vtkVolume whose
 *                matrix is T(origin) D T(-origin): RMSE < 0.01.
 *   extreme:     f64 values of +-1e308 cannot be 32-bit float texels (VTK's
 *                own GPU mapper draws them as infinities): the mapper
 *                refuses with a vtkErrorMacro naming the float range and
 *                what to do, draws nothing, and then draws the ball mapped
 *                to [0, 1] like a fresh mapper (RMSE < 0.005).
 *   offset:      extreme with a 1e-3 range on a 1e9 offset, which 32-bit
 *                float texels round to noise: refused the same way, the
 *                message saying to subtract the offset.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkTransform.h"

#include <iostream>
#include <string>

namespace
{
using namespace MapperScene;

constexpr int N = 33;

/// A ball of radius 10 about the centre over a gentle x ramp, mapped to
/// [lo, hi] (t in [0, 1] gives lo (1 - t) + hi t, which does not overflow).
vtkNew<vtkImageData> Ball(double lo, double hi, double spacing, bool constant = false)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(N, N, N);
  image->SetSpacing(spacing, spacing, spacing);
  image->SetOrigin(-16.0 * spacing, -16.0 * spacing, -16.0 * spacing);
  vtkNew<vtkDoubleArray> values;
  values->SetName("ball");
  values->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const double r2 =
          (i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0);
        const double t = constant ? 0.5 : (r2 < 100.0 ? 0.8 : 0.0) + 0.2 * i / 32.0;
        values->SetValue(i + N * (j + N * k), lo * (1.0 - t) + hi * t);
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// One volume of `image` drawn by `mapper` on a MapperScene::Stage: a colour
/// ramp and an opacity of 0.02-0.08 a unit distance `scale` over `[lo, hi]`,
/// the camera looking at the origin from a distance scaled by `scale`.
struct BallStage : Stage
{
  BallStage(vtkVolumeMapper* mapper, vtkImageData* image, double lo, double hi, double scale)
  {
    mapper->SetInputData(image);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(lo, 0.1, 0.2, 0.9);
    color->AddRGBPoint(hi, 0.9, 0.6, 0.1);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(lo, 0.02);
    opacity->AddPoint(hi, 0.08);
    this->Property->SetScalarOpacityUnitDistance(scale);
    const double position[3] = { 50.0 * scale, 38.0 * scale, 66.0 * scale };
    this->Build(mapper, color, opacity, position);
  }
};

vtkNew<vtkGPUVolumeRayCastMapper> Reference()
{
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->AutoAdjustSampleDistancesOff();
  gpu->SetSampleDistance(1.0);
  gpu->SetUseJittering(0);
  return gpu;
}

vtkNew<vtkHybridOctreeVolumeMapper> Ours()
{
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  return mapper;
}

/// Draws both stages and checks the RMSE of their windows against `threshold`.
void Compare(Checker& check, const std::string& what, vtkHybridOctreeVolumeMapper* mapper,
  BallStage& ours, BallStage& theirs, double threshold)
{
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), what + ": the mapper drew:\n" + errors->AllErrors());
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  std::cout << what << ": bricks " << mapper->GetLastBricks() << ", slices "
            << mapper->GetLastSlices() << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse
            << " (threshold " << threshold << "), signal " << Signal(b) << "\n";
  check.Check(Signal(b) > 0.02, what + ": the reference shows the volume");
  check.Check(rmse < threshold, what + ": within the threshold of vtkGPUVolumeRayCastMapper");
  check.Check(NoGLError(ours.Window), what + ": no OpenGL error left behind");
}

int Constant()
{
  Checker check;
  vtkNew<vtkImageData> image = Ball(0.0, 1.0, 1.0, true);
  vtkNew<vtkHybridOctreeVolumeMapper> mapper = Ours();
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = Reference();
  // The colour and opacity points span [0, 1] around the one value 0.5.
  BallStage ours(mapper, image, 0.0, 1.0, 1.0);
  BallStage theirs(gpu, image, 0.0, 1.0, 1.0);
  Compare(check, "constant", mapper, ours, theirs, 0.01);
  check.Check(mapper->GetLastSlices() > 16, "the one brick is sliced across the cube");
  return check.Result();
}

int Spacing()
{
  Checker check;
  vtkNew<vtkImageData> tiny = Ball(0.0, 1.0, 1e-6);
  vtkNew<vtkImageData> unit = Ball(0.0, 1.0, 1.0);
  vtkNew<vtkHybridOctreeVolumeMapper> mapper = Ours();
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = Reference();
  BallStage ours(mapper, tiny, 0.0, 1.0, 1e-6);
  BallStage theirs(gpu, unit, 0.0, 1.0, 1.0);
  Compare(check, "spacing 1e-6", mapper, ours, theirs, 0.01);
  return check.Result();
}

int Direction()
{
  Checker check;
  vtkNew<vtkImageData> rotated = Ball(0.0, 1.0, 1.0);
  vtkNew<vtkImageData> plain = Ball(0.0, 1.0, 1.0);
  vtkNew<vtkTransform> rotation;
  rotation->RotateZ(30.0);
  rotation->RotateX(20.0);
  vtkNew<vtkMatrix3x3> direction;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      direction->SetElement(r, c, rotation->GetMatrix()->GetElement(r, c));
    }
  }
  rotated->SetDirectionMatrix(direction);
  vtkNew<vtkHybridOctreeVolumeMapper> mapper = Ours();
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = Reference();
  BallStage ours(mapper, rotated, 0.0, 1.0, 1.0);
  BallStage theirs(gpu, plain, 0.0, 1.0, 1.0);
  // Where vtkImageData puts point (i, j, k): origin + D (spacing * ijk), the
  // identity-direction image moved by T(origin) D T(-origin).
  const double* o = plain->GetOrigin();
  vtkNew<vtkTransform> model;
  model->Translate(o[0], o[1], o[2]);
  model->Concatenate(rotation);
  model->Translate(-o[0], -o[1], -o[2]);
  theirs.Volume->SetUserMatrix(model->GetMatrix());
  theirs.Renderer->ResetCameraClippingRange();
  Compare(check, "direction matrix", mapper, ours, theirs, 0.01);
  return check.Result();
}

int Extreme(bool offset)
{
  Checker check;
  vtkNew<vtkImageData> extreme = offset ? Ball(1e9, 1e9 + 1e-3, 1.0) : Ball(-1e308, 1e308, 1.0);
  vtkNew<vtkImageData> unit = Ball(0.0, 1.0, 1.0);
  vtkNew<vtkHybridOctreeVolumeMapper> mapper = Ours();
  vtkNew<vtkHybridOctreeVolumeMapper> unitMapper = Ours();
  BallStage ours(mapper, extreme, 0.0, 1.0, 1.0);
  BallStage theirs(unitMapper, unit, 0.0, 1.0, 1.0);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  std::cout << "extreme: errors\n" << errors->AllErrors();
  check.Check(!mapper->GetLastRenderOK(), "the mapper refuses what 32-bit float cannot hold");
  check.Check(errors->HasError("32-bit float") && errors->HasError("CompositeOnCPU") &&
      (!offset || errors->HasError("subtract the offset")),
    "the error names the float range and what to do");
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  // The same mapper then draws an image within the float range.
  errors->Clear();
  mapper->SetInputData(unit);
  ours.Window->Render();
  check.Check(
    mapper->GetLastRenderOK(), "and draws again once the data fits:\n" + errors->AllErrors());
  theirs.Window->Render();
  const double rmse = Rmse(Grab(ours.Window), Grab(theirs.Window));
  std::cout << "extreme: after the refusal, RGB RMSE against a fresh mapper " << rmse
            << " (threshold 0.005)\n";
  check.Check(rmse < 0.005, "the refusal left nothing behind");
  return check.Result();
}
} // namespace

int TestHybridOctreeStability(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "constant";
  if (scenario == "constant")
  {
    return Constant();
  }
  if (scenario == "spacing")
  {
    return Spacing();
  }
  if (scenario == "direction")
  {
    return Direction();
  }
  if (scenario == "extreme" || scenario == "offset")
  {
    return Extreme(scenario == "offset");
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
