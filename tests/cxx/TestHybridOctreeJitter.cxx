/**
 * Jittering (vtkHybridOctreeVolumeMapper::UseJittering, as
 * vtkGPUVolumeRayCastMapper's) under Xvfb, on the mapper tests' wavelet
 * scene (HybridOctreeMapperScene.h). Metric: RMSE of the RGB channels in
 * [0, 1] over the 256x256 window.
 *
 *   jitter:     a thin opaque shell of the wavelet (opacity 0.7 at 66 % of
 *               its range, 0 at 62 % and 70 %) under a budget of 0.3 MB (mixed
 *               strides), Composite and MIP. Off (the default): the effects
 *               hold no "jittering". On: they end with it, and the GL picture
 *               is within RMSE 0.005 of the CPU compositor's jittered picture
 *               of the same DrawList (the same fixed per-pixel noise and
 *               lattice offsets in both; measured 0.0014 in both modes),
 *               while the jitter moves the picture by more than 0.008
 *               (measured 0.0135 Composite, 0.0109 MIP): the GL jitter is
 *               the CPU compositor's, not a no-op.
 *   gpu_jitter: the full volume in the budget, jittered, against
 *               vtkGPUVolumeRayCastMapper jittered too (its random noise
 *               texture): RMSE < 0.01 (measured 0.0015).
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkPiecewiseFunction.h"

#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

bool Jittered(vtkHybridOctreeVolumeMapper* mapper)
{
  return std::string(mapper->GetLastEffects()).find("jittering") != std::string::npos;
}

/// Mixed strides: off, then on against the CPU compositor, Composite and MIP.
int Jitter()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  // A thin opaque shell of the wavelet: a coarse lattice shows it as rings.
  const double lo = scene.Range[0], hi = scene.Range[1];
  vtkPiecewiseFunction* opacity = scene.Property->GetScalarOpacity();
  opacity->RemoveAllPoints();
  opacity->AddPoint(lo, 0.0);
  opacity->AddPoint(lo + 0.62 * (hi - lo), 0.0);
  opacity->AddPoint(lo + 0.66 * (hi - lo), 0.7);
  opacity->AddPoint(lo + 0.70 * (hi - lo), 0.0);
  opacity->AddPoint(hi, 0.0);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.3);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  check.Check(mapper->GetUseJittering() == 0, "off by default, as VTK's");
  for (int mode : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
  {
    mapper->SetBlendMode(mode);
    mapper->UseJitteringOff();
    scene.Window->Render();
    check.Check(mapper->GetLastRenderOK() && !Jittered(mapper),
      std::string("off: no jittering in the effects '") + mapper->GetLastEffects() + "'");
    const std::vector<double> lattice = Grab(scene.Window);
    mapper->UseJitteringOn();
    std::cout << "blend mode " << mode << ", jittered: ";
    CompareWithCpu(check, scene, mapper, 0.005, errors);
    check.Check(Jittered(mapper),
      std::string("on: jittering in the effects '") + mapper->GetLastEffects() + "'");
    check.Check(mapper->GetLastEstimatedError() > 0.0, "a budget under the full volume");
    const double moved = Rmse(Grab(scene.Window), lattice);
    std::cout << "jittered vs lattice picture: RMSE " << moved << " (must exceed 0.008)\n";
    check.Check(moved > 0.008, "the jitter is drawn");
  }
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "no warning or error:\n" + errors->AllErrors() +
      (errors->Warnings.empty() ? "" : "  warning: " + errors->Warnings[0] + "\n"));
  return check.Result();
}

/// The full volume, jittered, against vtkGPUVolumeRayCastMapper jittered.
int GpuJitter()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(8.0);
  mapper->UseJitteringOn();
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  gpu->SetUseJittering(1);
  Scene theirs(gpu);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  check.Check(Jittered(mapper), std::string("effects '") + mapper->GetLastEffects() + "'");
  check.Check(mapper->GetLastEstimatedError() == 0.0, "the full volume at full resolution");
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(Grab(ours.Window), b);
  std::cout << "jittered: bricks " << mapper->GetLastBricks()
            << "; RGB RMSE against vtkGPUVolumeRayCastMapper jittered " << rmse
            << " (threshold 0.01), signal " << Signal(b) << "\n";
  check.Check(Signal(b) > 0.02, "the reference shows the volume");
  check.Check(rmse < 0.01, "within 0.01 of vtkGPUVolumeRayCastMapper");
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  return check.Result();
}
} // namespace

int TestHybridOctreeJitter(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "jitter";
  if (scenario == "jitter")
  {
    return Jitter();
  }
  if (scenario == "gpu_jitter")
  {
    return GpuJitter();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
