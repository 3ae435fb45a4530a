/**
 * vtkHybridOctreeVolumeMapper's view-dependent selection (SetViewSelection,
 * SetMinTexelPixels, SetViewChangeDegrees), under Xvfb.
 *
 *   wall:  a 64^3 volume whose near half (z >= 32, seen from +z) is an
 *          opaque wall over x < 48, faint detail everywhere else. At the same
 *          budget (0.25 MB, a quarter of the volume), VISIBILITY (and BOTH)
 *          spend at most a quarter of DATA's texture bytes on the bricks
 *          behind the wall (x <= 32, z <= 32), and draw within RMSE(DATA) +
 *          0.005 of vtkGPUVolumeRayCastMapper at full resolution.
 *   orbit: 20 still frames 2 degrees apart under BOTH and ViewChangeDegrees
 *          5: a selection at the first frame, then only when the view has
 *          turned past 5 degrees from the last selection's (every 3rd
 *          frame: 7 in all), 0 ms and no upload for a kept one; the uploaded
 *          bytes per frame after the first average at most 10 % of the
 *          budget. DATA selects once. A resized window selects again.
 *   bad_settings: ViewSelection 4, MinTexelPixels -1 and NaN,
 *          ViewChangeDegrees -1: a vtkErrorMacro naming the setting, nothing
 *          drawn, no crash; a good setting draws again.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"

#include <iostream>
#include <limits>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

constexpr int N = 64;

/// The wall volume: 1 (opaque) over x < 48, z >= 32; elsewhere a ripple in [0.1, 0.5].
vtkNew<vtkImageData> WallImage()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(N, N, N);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  for (int z = 0; z < N; ++z)
  {
    for (int y = 0; y < N; ++y)
    {
      for (int x = 0; x < N; ++x)
      {
        const bool wall = x < 48 && z >= 32;
        const double ripple =
          0.3 + 0.2 * std::sin(0.9 * x) * std::cos(0.7 * y) * std::sin(0.8 * z + 0.3 * x);
        values->SetValue(x + N * (y + static_cast<vtkIdType>(N) * z), wall ? 1.0f : ripple);
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// The wall volume on a Stage, seen from +z.
struct WallScene : Stage
{
  explicit WallScene(vtkVolumeMapper* mapper, vtkImageData* image)
  {
    mapper->SetInputDataObject(image);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.1, 0.1, 0.3, 0.9);
    color->AddRGBPoint(0.5, 0.9, 0.8, 0.2);
    color->AddRGBPoint(1.0, 0.8, 0.8, 0.8);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.1, 0.0);
    opacity->AddPoint(0.5, 0.08);
    opacity->AddPoint(0.9, 1.0);
    opacity->AddPoint(1.0, 1.0);
    const double position[3] = { 0.0, 0.0, 1.0 };
    this->Build(mapper, color, opacity, position);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(31.5, 31.5, 31.5);
    camera->SetPosition(31.5, 31.5, 31.5 + 190.0);
    this->Renderer->ResetCameraClippingRange();
  }
};

int Wall()
{
  Checker check;
  vtkNew<vtkImageData> image = WallImage();
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  WallScene theirs(gpu, image);
  theirs.Window->Render();
  const std::vector<double> reference = Grab(theirs.Window);
  check.Check(Signal(reference) > 0.02, "the reference shows the volume");
  // Behind the wall, as seen from the camera.
  const double behind[6] = { -1.0, 32.5, -1.0, 64.0, -1.0, 32.5 };
  double dataRmse = 0.0;
  vtkTypeInt64 dataBehind = 0;
  for (int mode : { vtkHybridOctreeVolumeMapper::VIEW_SELECTION_DATA,
         vtkHybridOctreeVolumeMapper::VIEW_SELECTION_VISIBILITY,
         vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH })
  {
    vtkNew<vtkHybridOctreeVolumeMapper> mapper;
    mapper->SetLeafSize(4);
    mapper->SetBudgetMB(0.25);
    mapper->SetViewSelection(mode);
    WallScene ours(mapper, image);
    vtkSmartPointer<ErrorRecorder> errors =
      vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
    errors->Watch(mapper);
    ours.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    const double selectMs = mapper->GetLastSelectMilliseconds();
    const double rmse = Rmse(Grab(ours.Window), reference);
    const vtkTypeInt64 hidden = mapper->GetLastTextureBytesWithin(behind);
    std::cout << "view: " << mapper->GetLastViewSelection() << ": texture bytes "
              << mapper->GetLastTextureBytes() << ", behind the wall " << hidden
              << ", selection ms " << selectMs << ", RGB RMSE against vtkGPUVolumeRayCastMapper "
              << rmse << "\n";
    check.Check(mapper->GetLastTextureBytes() <= 250000, "within the budget");
    if (mode == vtkHybridOctreeVolumeMapper::VIEW_SELECTION_DATA)
    {
      check.Check(std::string(mapper->GetLastViewSelection()) == "data", "data ran");
      dataRmse = rmse;
      dataBehind = hidden;
      continue;
    }
    const std::string name =
      mode == vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH ? "both" : "visibility";
    check.Check(mapper->GetLastViewSelection() == name, name + " ran");
    check.Check(4 * hidden <= dataBehind,
      name + ": at most a quarter of data's bytes behind the wall (" + std::to_string(hidden) +
        " vs " + std::to_string(dataBehind) + ")");
    check.Check(rmse <= dataRmse + 0.005,
      name + ": RMSE " + std::to_string(rmse) + " no worse than data's " +
        std::to_string(dataRmse) + " + 0.005");
  }
  return check.Result();
}

int Orbit()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.3);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  int selections[2] = { 0, 0 };
  bool drew = true;
  bool keptIsFree = true;
  bool atTheRightFrames = true;
  double uploaded = 0.0;
  const int frames = 20;
  for (int mode : { vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH,
         vtkHybridOctreeVolumeMapper::VIEW_SELECTION_DATA })
  {
    const int m = mode == vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH ? 0 : 1;
    mapper->SetViewSelection(mode);
    std::cout << "view " << (m == 0 ? "both" : "data") << ", uploaded bytes per frame:";
    for (int frame = 0; frame < frames; ++frame)
    {
      if (frame > 0)
      {
        camera->Azimuth(2.0);
      }
      scene.Renderer->ResetCameraClippingRange();
      scene.Window->Render();
      drew = drew && mapper->GetLastRenderOK();
      std::cout << " " << mapper->GetLastUploadedBytes();
      if (m == 0 && frame > 0)
      {
        uploaded += static_cast<double>(mapper->GetLastUploadedBytes());
      }
      if (m == 0)
      {
        // Turned 2 degrees a frame: past 5 degrees at every 3rd frame.
        atTheRightFrames = atTheRightFrames && mapper->GetLastReselected() == (frame % 3 == 0);
      }
      if (mapper->GetLastReselected())
      {
        ++selections[m];
      }
      else
      {
        keptIsFree = keptIsFree && mapper->GetLastSelectMilliseconds() == 0.0 &&
          mapper->GetLastUploadedBytes() == 0;
      }
    }
    std::cout << "\n";
  }
  std::cout << "selections over " << frames << " frames: both " << selections[0] << ", data "
            << selections[1] << "; mean uploaded bytes per frame after the first (both) "
            << uploaded / (frames - 1) << "\n";
  check.Check(drew, "every frame drew:\n" + errors->AllErrors());
  check.Check(selections[0] == 7 && atTheRightFrames,
    "both: a selection every 3rd frame of 2 degrees (7), got " + std::to_string(selections[0]));
  // DATA's key differs from BOTH's: one selection, then kept while the view turns.
  check.Check(selections[1] == 1, "data: one selection, got " + std::to_string(selections[1]));
  check.Check(keptIsFree, "a kept selection takes 0 ms and uploads nothing");
  // A new selection uploads only the bricks the last one did not hold
  // (measured 4.8 kB a frame at a 0.3 MB budget).
  check.Check(uploaded / (frames - 1) <= 0.1 * 0.3e6,
    "uploads after the first frame average at most 10 % of the budget, got " +
      std::to_string(uploaded / (frames - 1)) + " bytes a frame");
  mapper->SetViewSelection(vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH);
  scene.Window->Render();
  scene.Window->Render();
  check.Check(!mapper->GetLastReselected(), "the same view keeps its selection");
  scene.Window->SetSize(Size, Size / 2);
  scene.Window->Render();
  check.Check(mapper->GetLastReselected(), "a resized viewport selects again");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}

int BadSettings()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(0.3);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad
  {
    const char* What;
    int Mode;
    double MinTexel;
    double Change;
    const char* Expected;
  };
  const Bad bads[] = {
    { "ViewSelection 4", 4, 1.0, 5.0, "view selection 4" },
    { "MinTexelPixels -1", 3, -1.0, 5.0, "smallest texel -1" },
    { "MinTexelPixels NaN", 1, nan, 5.0, "smallest texel NaN" },
    { "ViewChangeDegrees -1", 3, 1.0, -1.0, "ViewChangeDegrees -1" },
  };
  for (const Bad& bad : bads)
  {
    errors->Clear();
    mapper->SetViewSelection(bad.Mode);
    mapper->SetMinTexelPixels(bad.MinTexel);
    mapper->SetViewChangeDegrees(bad.Change);
    scene.Window->Render();
    std::cout << bad.What << ": " << errors->AllErrors();
    check.Check(errors->HasError(bad.Expected),
      std::string(bad.What) + ": error containing '" + bad.Expected + "'; got\n" +
        errors->AllErrors());
    check.Check(!mapper->GetLastRenderOK(), std::string(bad.What) + ": nothing drawn");
    // A good setting draws again.
    errors->Clear();
    mapper->SetViewSelection(vtkHybridOctreeVolumeMapper::VIEW_SELECTION_BOTH);
    mapper->SetMinTexelPixels(1.0);
    mapper->SetViewChangeDegrees(5.0);
    scene.Window->Render();
    check.Check(mapper->GetLastRenderOK(),
      std::string("after ") + bad.What + ", good settings draw:\n" + errors->AllErrors());
  }
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}
} // namespace

int TestHybridOctreeViewSelection(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "wall";
  if (scenario == "orbit")
  {
    return Orbit();
  }
  if (scenario == "bad_settings")
  {
    return BadSettings();
  }
  return Wall();
}
