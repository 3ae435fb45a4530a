/**
 * The Slice blend mode (vtkVolumeMapper::SLICE_BLEND with a vtkPlane as
 * vtkVolumeProperty's SliceFunction) in vtkHybridOctreeVolumeMapper, on the
 * wavelet scene of the mapper tests, an oblique plane through it, an
 * opacity above 0 over the whole range (the slice shows everywhere).
 *
 *   cpu:         mixed strides (0.03 MB), unshaded then shaded: the plan is
 *                "volume-slice" ("volume-slice-shaded"), the GL picture
 *                within RMSE 0.005 of the CPU compositor on the same
 *                DrawList (measured 0.0016 both), no warning, mixed strides
 *                (an estimated error above 0) and a picture unlike Composite's.
 *   gpu:         the full volume in the budget against
 *                vtkGPUVolumeRayCastMapper under SLICE_BLEND with the same
 *                plane: unshaded, shaded, and the volume rotated and moved
 *                (its vtkVolume matrix; VTK takes the plane into the data
 *                frame with the matrix' inverse): RMSE < 0.01 unshaded and
 *                moved (measured 0.0071, 0.0074), < 0.03 shaded (measured
 *                0.021; gpu_shaded's bound: every pixel is one shaded
 *                sample, so the two mappers' gradients differ in full,
 *                where a composite averages them along the ray).
 *   bad_function: no slice function, then a vtkSphere: one warning naming
 *                the problem each, the volume drawn as Composite, no error.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkPlane.h"
#include "vtkSphere.h"

#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// The slice plane and an opacity above 0 everywhere on `scene`.
void SetSlice(Scene& scene, vtkPlane* plane)
{
  plane->SetOrigin(3.0, -2.0, 4.0);
  plane->SetNormal(0.5, 0.8, 0.35);
  scene.Property->SetSliceFunction(plane);
  vtkNew<vtkPiecewiseFunction> opacity;
  const double lo = scene.Range[0], hi = scene.Range[1];
  opacity->AddPoint(lo, 0.3);
  opacity->AddPoint(0.5 * (lo + hi), 0.6);
  opacity->AddPoint(hi, 1.0);
  scene.Property->SetScalarOpacity(opacity);
}

int Cpu()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.03);
  vtkNew<vtkPlane> plane;
  SetSlice(scene, plane);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const std::vector<double> composited = Grab(scene.Window);
  const vtkTypeInt64 compositeBytes = mapper->GetLastTextureBytes();
  mapper->SetBlendModeToSlice();
  for (bool shade : { false, true })
  {
    scene.Property->SetShade(shade);
    scene.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    const std::vector<double> gl = Grab(scene.Window);
    const std::vector<double> reference = CpuPicture(check, scene, mapper, errors);
    const double rmse = Rmse(gl, reference);
    const double change = Rmse(gl, composited);
    const std::string plan = shade ? "volume-slice-shaded" : "volume-slice";
    std::cout << "shade " << shade << ": bricks " << mapper->GetLastBricks() << ", plan '"
              << mapper->GetLastPlan() << "', texture bytes " << mapper->GetLastTextureBytes()
              << " (Composite " << compositeBytes << "), estimated error "
              << mapper->GetLastEstimatedError() << "; RGB RMSE GL vs CPU compositor " << rmse
              << " (threshold 0.005), vs Composite " << change << ", signal " << Signal(reference)
              << "\n";
    check.Check(mapper->GetLastPlan() == plan, "plan '" + plan + "'");
    check.Check(Signal(reference) > 0.02, "the slice shows");
    check.Check(rmse < 0.005, "GL within 0.005 of the CPU compositor");
    check.Check(change > 0.02, "the slice is not the Composite picture");
    check.Check(mapper->GetLastEstimatedError() > 0.0, "mixed strides (an estimated error)");
    check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  }
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "the Slice blend mode is drawn, no warning:\n" + errors->AllErrors());
  return check.Result();
}

/// vtkGPUVolumeRayCastMapper on the same scene, rays sampled every spacing.
int Gpu()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->AutoAdjustSampleDistancesOff();
  gpu->SetSampleDistance(1.0);
  gpu->SetUseJittering(0);
  Scene theirs(gpu);
  vtkNew<vtkPlane> plane;
  SetSlice(ours, plane);
  SetSlice(theirs, plane);
  mapper->SetBlendModeToSlice();
  gpu->SetBlendModeToSlice();
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  const char* cases[] = { "unshaded", "shaded", "moved" };
  for (const std::string what : cases)
  {
    for (Scene* s : { &ours, &theirs })
    {
      s->Property->SetShade(what == "shaded");
      if (what == "moved")
      {
        s->Volume->SetOrientation(10.0, -25.0, 15.0);
        s->Volume->SetPosition(4.0, -3.0, 2.0);
      }
    }
    ours.Window->Render();
    theirs.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    const std::vector<double> a = Grab(ours.Window);
    const std::vector<double> b = Grab(theirs.Window);
    const double rmse = Rmse(a, b);
    const double threshold = what == "shaded" ? 0.03 : 0.01;
    std::cout << what << ": plan '" << mapper->GetLastPlan() << "', bricks "
              << mapper->GetLastBricks() << ", texture bytes " << mapper->GetLastTextureBytes()
              << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse << " (threshold "
              << threshold << "), signal " << Signal(b) << "\n";
    check.Check(Signal(b) > 0.02, "the reference shows the slice");
    check.Check(rmse < threshold, what + ": within the threshold of vtkGPUVolumeRayCastMapper");
  }
  check.Check(
    errors->Errors.empty() && errors->Warnings.empty(), "no warning:\n" + errors->AllErrors());
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  return check.Result();
}

int BadFunction()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const std::vector<double> composited = Grab(scene.Window);
  mapper->SetBlendModeToSlice();
  vtkNew<vtkSphere> sphere;
  const std::pair<vtkImplicitFunction*, std::string> functions[] = { { nullptr, "none is set" },
    { sphere, "must be a vtkPlane, not a vtkSphere" } };
  for (const auto& f : functions)
  {
    scene.Property->SetSliceFunction(f.first);
    scene.Window->Render();
    int named = 0;
    for (const std::string& w : errors->Warnings)
    {
      named += w.find(f.second) != std::string::npos ? 1 : 0;
    }
    check.Check(named == 1 && errors->Warnings.size() == 1 && errors->Errors.empty(),
      "one warning naming '" + f.second + "':\n" + errors->AllErrors());
    check.Check(mapper->GetLastRenderOK() && Rmse(Grab(scene.Window), composited) < 1e-6 &&
        mapper->GetLastPlan() == std::string("volume"),
      "drawn as Composite: " + f.second);
    errors->Clear();
  }
  return check.Result();
}
} // namespace

int TestHybridOctreeSlice(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "cpu";
  if (scenario == "cpu")
  {
    return Cpu();
  }
  if (scenario == "gpu")
  {
    return Gpu();
  }
  if (scenario == "bad_function")
  {
    return BadFunction();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
