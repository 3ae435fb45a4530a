/**
 * vtkHybridOctreeVolumeMapper's frames within a time (TargetFrameMilliseconds), under Xvfb.
 *
 *   generous:  a target no frame misses (100 s): the warm-up's frames
 *              ("warm-up") draw BudgetMB, then shrinking budgets, then every
 *              frame is "full", draws the untimed frame's bricks and
 *              picture (RGB RMSE <= 0.001), predicts and measures a time
 *              above 0, reports the untimed frame's estimated RMS error,
 *              and aims its drawing below the target (by the time the
 *              frames before spent outside it), at no less than a tenth.
 *   tiny:      a target no frame meets (1 microsecond): after the warm-up,
 *              "below-fastest" with the least budget a timed frame draws
 *              (BudgetMB / 512: fewer texture bytes, a larger estimated
 *              RMS error than the full budget's, still a picture),
 *              widened slices drawn as the CPU compositor composites them
 *              (RGB RMSE <= 0.02).
 *   tiny_surface: a translucent isosurface and a target no frame meets:
 *              after the exact drawing's warm-up, its "below-fastest"
 *              frame sorts the surface into the slabs; the next frames of
 *              that target draw it per brick (the interactive drawing,
 *              warmed up under its own cost model), drawn as the CPU
 *              compositor composites the same DrawList (RGB RMSE <= 0.05);
 *              a frame without the surface, then with it again, tries the
 *              slabs again; a generous target sorts it into the slabs.
 *   window:    TARGET_FRAME_WINDOW: a still frame is untimed (target 0,
 *              no outcome); an interactive one (30 frames a second asked)
 *              targets 0.4 of the volume's allocated render time, all of
 *              it the drawing's.
 *   bad_target: below 0 (not -1), NaN, above ten minutes: a clear
 *              vtkErrorMacro naming TargetFrameMilliseconds, nothing drawn,
 *              no OpenGL error; 0 draws again.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"

#include <iostream>
#include <limits>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace
{
using namespace MapperScene;

/// Texture bytes of the last frame's bricks (all of them, resident ones left out).
vtkTypeInt64 FrameBytes(vtkHybridOctreeVolumeMapper* mapper)
{
  const double everywhere[6] = { -1e300, 1e300, -1e300, 1e300, -1e300, 1e300 };
  return mapper->GetLastTextureBytesWithin(everywhere);
}

void Print(vtkHybridOctreeVolumeMapper* mapper)
{
  std::cout << "target " << mapper->GetLastTargetMilliseconds() << " ms, predicted "
            << mapper->GetLastPredictedMilliseconds() << " ms, drawn "
            << mapper->GetLastDrawMilliseconds() << " ms, outcome '" << mapper->GetLastTimeOutcome()
            << "', bricks " << mapper->GetLastBricks() << ", frame bytes " << FrameBytes(mapper)
            << ", estimated RMS error " << mapper->GetLastEstimatedRMSError() << "\n";
}

/// The warm-up's frames of `mapper` in `scene`: the first draws BudgetMB's
/// `fullBytes`, the next ones no more than the one before, each says "warm-up".
void WarmUp(Checker& check, Scene& scene, vtkHybridOctreeVolumeMapper* mapper,
  vtkTypeInt64 fullBytes, ErrorRecorder* errors)
{
  vtkTypeInt64 previous = fullBytes;
  for (int i = 0; i < 4; ++i)
  {
    scene.Window->Render();
    Print(mapper);
    check.Check(mapper->GetLastRenderOK(), "a warm-up frame drew:\n" + errors->AllErrors());
    check.Check(std::string(mapper->GetLastTimeOutcome()) == "warm-up", "a warm-up frame");
    check.Check(mapper->GetLastReselected(), "each warm-up frame selects");
    check.Check(i > 0 || FrameBytes(mapper) == fullBytes, "the first warm-up frame draws BudgetMB");
    check.Check(FrameBytes(mapper) <= previous, "the warm-up's budgets shrink");
    previous = FrameBytes(mapper);
  }
  check.Check(previous < fullBytes, "the warm-up's last frame draws fewer bytes than the first");
}

int Generous()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.5);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the untimed frame drew:\n" + errors->AllErrors());
  check.Check(
    mapper->GetLastTargetMilliseconds() == 0.0 && std::string(mapper->GetLastTimeOutcome()).empty(),
    "an untimed frame has no target and no outcome");
  const std::vector<double> untimed = Grab(scene.Window);
  const vtkTypeInt64 untimedBytes = FrameBytes(mapper);
  const double untimedError = mapper->GetLastEstimatedRMSError();
  Print(mapper);
  check.Check(untimedError > 0.0, "a budget below the full resolution has an estimated RMS error");

  mapper->SetTargetFrameMilliseconds(1.0e5);
  WarmUp(check, scene, mapper, untimedBytes, errors);
  for (int i = 0; i < 3; ++i)
  {
    scene.Window->Render();
    Print(mapper);
    check.Check(mapper->GetLastRenderOK(), "a timed frame drew:\n" + errors->AllErrors());
    check.Check(std::string(mapper->GetLastTimeOutcome()) == "full", "a generous target is full");
    check.Check(mapper->GetLastTargetMilliseconds() == 1.0e5, "the target is reported");
    const double drawTarget = mapper->GetLastDrawTargetMilliseconds();
    std::cout << "draw target " << drawTarget << " ms\n";
    check.Check(drawTarget < 1.0e5 && drawTarget >= 1.0e4,
      "the drawing aims at the target less the time outside it, at least a tenth of it");
    check.Check(mapper->GetLastPredictedMilliseconds() > 0.0, "a predicted time");
    check.Check(mapper->GetLastDrawMilliseconds() > 0.0, "a measured time");
    check.Check(FrameBytes(mapper) == untimedBytes, "the full budget's bricks");
    check.Check(mapper->GetLastEstimatedRMSError() == untimedError, "the full budget's error");
  }
  const double rmse = Rmse(Grab(scene.Window), untimed);
  std::cout << "RGB RMSE full-target vs untimed " << rmse << " (threshold 0.001)\n";
  check.Check(rmse <= 0.001, "a generous target draws the untimed picture");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}

int Tiny()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.5);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const vtkTypeInt64 fullBytes = FrameBytes(mapper);
  const double fullError = mapper->GetLastEstimatedRMSError();
  mapper->SetTargetFrameMilliseconds(1.0e-3);
  WarmUp(check, scene, mapper, fullBytes, errors);
  scene.Window->Render();
  Print(mapper);
  check.Check(mapper->GetLastRenderOK(), "the fastest frame drew:\n" + errors->AllErrors());
  check.Check(std::string(mapper->GetLastTimeOutcome()) == "below-fastest",
    "a target below the fastest frame is said to be");
  check.Check(FrameBytes(mapper) < fullBytes, "the fastest frame draws fewer bytes");
  check.Check(
    mapper->GetLastEstimatedRMSError() > fullError, "the fastest frame pays a larger error");
  CompareWithCpu(check, scene, mapper, 0.02, errors);
  return check.Result();
}

int TinySurface()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.5);
  mapper->SetShowSurface(true);
  mapper->SetIsovalue(scene.Range[0] + 0.6 * (scene.Range[1] - scene.Range[0]));
  mapper->SetSurfaceOpacity(0.4);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const std::string exact = mapper->GetLastPlan();
  std::cout << "untimed plan '" << exact << "'\n";
  check.Check(
    exact.find("surface-in-slabs") != std::string::npos, "a still frame sorts the surface");
  mapper->SetTargetFrameMilliseconds(1.0e-3);
  WarmUp(check, scene, mapper, FrameBytes(mapper), errors);
  scene.Window->Render();
  Print(mapper);
  check.Check(std::string(mapper->GetLastTimeOutcome()) == "below-fastest" &&
      std::string(mapper->GetLastPlan()) == exact,
    "the exact drawing is below the fastest frame");
  for (int i = 0; i < 5; ++i)
  {
    scene.Window->Render();
    Print(mapper);
    check.Check(mapper->GetLastRenderOK(), "a per-brick frame drew:\n" + errors->AllErrors());
    check.Check(std::string(mapper->GetLastPlan()).find("surface-per-brick") != std::string::npos,
      "the next frames draw the surface per brick, and say so");
    check.Check(std::string(mapper->GetLastTimeOutcome()) == (i < 4 ? "warm-up" : "below-fastest"),
      "the per-brick drawing warms its own cost model up");
  }
  CompareWithCpu(check, scene, mapper, 0.05, errors);
  // The surface hidden for a frame: no slab work left, so the surface shown
  // again is tried in the slabs first.
  mapper->SetShowSurface(false);
  scene.Window->Render();
  mapper->SetShowSurface(true);
  scene.Window->Render();
  Print(mapper);
  check.Check(std::string(mapper->GetLastPlan()) == exact,
    "without slab work for a frame, the exact drawing is tried again");
  mapper->SetTargetFrameMilliseconds(1.0e5);
  scene.Window->Render();
  Print(mapper);
  check.Check(std::string(mapper->GetLastPlan()) == exact, "a new target tries the exact drawing");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}

int Window()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetTargetFrameMilliseconds(vtkHybridOctreeVolumeMapper::TARGET_FRAME_WINDOW);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  Print(mapper);
  check.Check(mapper->GetLastRenderOK(), "the still frame drew:\n" + errors->AllErrors());
  check.Check(mapper->GetLastTargetMilliseconds() == 0.0, "a still frame is untimed");
  check.Check(std::string(mapper->GetLastTimeOutcome()).empty(), "no outcome when untimed");
  scene.Window->SetDesiredUpdateRate(30.0);
  scene.Window->Render();
  Print(mapper);
  const double allocated = scene.Volume->GetAllocatedRenderTime();
  std::cout << "allocated render time " << allocated << " s\n";
  check.Check(mapper->GetLastRenderOK(), "the interactive frame drew:\n" + errors->AllErrors());
  check.Check(mapper->GetLastInteractive(), "the frame was interactive");
  check.Check(std::fabs(mapper->GetLastTargetMilliseconds() - 400.0 * allocated) < 1e-9,
    "an interactive frame targets 0.4 of the allocated render time");
  check.Check(mapper->GetLastDrawTargetMilliseconds() == mapper->GetLastTargetMilliseconds(),
    "the window's share is the drawing's");
  check.Check(std::string(mapper->GetLastTimeOutcome()) == "warm-up", "its model warms up");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}

int BadTarget()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  for (double target : { -5.0, std::numeric_limits<double>::quiet_NaN(), 1.0e9 })
  {
    errors->Clear();
    mapper->SetTargetFrameMilliseconds(target);
    scene.Window->Render();
    check.Check(errors->HasError("TargetFrameMilliseconds"),
      "an error naming TargetFrameMilliseconds for " + std::to_string(target) + "; got\n" +
        errors->AllErrors());
    check.Check(!mapper->GetLastRenderOK(), "nothing drawn");
    check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  }
  errors->Clear();
  mapper->SetTargetFrameMilliseconds(0.0);
  scene.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "untimed again, it draws:\n" + errors->AllErrors());
  return check.Result();
}
} // namespace

int TestHybridOctreeTimedFrames(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "generous";
  if (scenario == "generous")
  {
    return Generous();
  }
  if (scenario == "tiny")
  {
    return Tiny();
  }
  if (scenario == "tiny_surface")
  {
    return TinySurface();
  }
  if (scenario == "window")
  {
    return Window();
  }
  if (scenario == "bad_target")
  {
    return BadTarget();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
