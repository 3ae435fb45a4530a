/**
 * vtkHybridOctreeVolumeMapper over many frames, and its errors, under Xvfb.
 *
 *   orbit:       two laps of 36 frames (10 degrees apart) with the region of
 *                interest moving and the budget changing: resident texture
 *                bytes never above the budget, the texture pages holding
 *                them within 2x their bytes + 256 KiB, the second lap uploads no more
 *                than the first (bricks stay resident), the resident texture
 *                count does not grow from lap to lap, and releasing the
 *                graphics resources frees them all.
 *   interactive: a window asking for 30 frames a second gets the interactive
 *                budget; a still frame after it refines to the full budget;
 *                PrintSelf shows every setting and statistic.
 *   warnings:    each setting the mapper does not draw (the Slice blend
 *                mode without a slice function, the 2D transfer function mode without
 *                an image, dependent components)
 *                gives one warning naming it, once while it stays on; the
 *                picture is the one without it; turned off and on again, or
 *                changed (Slice to an unknown mode), it is warned about
 *                again.
 *   grey:        a grey colour function (SetColor(vtkPiecewiseFunction*))
 *                draws the picture of the equal RGB function and stays grey
 *                (VTK's GetRGBTransferFunction would replace it).
 *   interactive_resident, interactive_surface (a translucent isosurface):
 *                after a still frame, interactive frames draw its resident
 *                textures (0 bytes uploaded, its bricks): at full sampling
 *                the still picture (volume: RMSE <= 0.001; the surface
 *                drawn per brick: <= 0.06), at the coarsest sampling (a
 *                window asking for a million frames a second) within RMSE
 *                0.01 of it (surface: 0.07), also while the camera moves; the next still frame
 *                is the full one again (not interactive, full sampling, the
 *                same bricks, the same picture); an opacity changed while
 *                interactive selects under the interactive budget.
 *   no_input, not_image, budget_zero, point_factor, multi_component,
 *   empty_image, infinity, all_nan:
 *                a clear vtkErrorMacro, nothing drawn, no crash, no OpenGL
 *                error left behind (NaN is no data: an infinity is an
 *                error, and so is an image of NaN only, "no data").
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkDoubleArray.h"
#include "vtkPolyData.h"

#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace
{
using namespace MapperScene;

int Orbit()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->UseRoiOn();
  mapper->SetRoiRadius(12.0);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  vtkTypeInt64 uploaded[2] = { 0, 0 };
  vtkTypeInt64 count[2] = { 0, 0 };
  bool bounded = true;
  bool drew = true;
  // The texture pages hold every resident brick, and their free slots stay
  // within the resident bytes plus the pages first made for each shape.
  bool paged = true;
  double pageRatio = 0.0;
  // The bricks that share a page draw in runs, one call each.
  vtkTypeInt64 draws = 0;
  vtkTypeInt64 drawn = 0;
  bool runs = true;
  for (int lap = 0; lap < 2; ++lap)
  {
    for (int frame = 0; frame < 36; ++frame)
    {
      // The ROI circles the volume; the budget alternates 0.3 and 0.2 MB.
      const double angle = frame * 10.0 * 3.14159265358979 / 180.0;
      mapper->SetRoiCenter(24.0 * std::cos(angle), 24.0 * std::sin(angle), 0.0);
      const double budget = frame % 2 ? 0.2 : 0.3;
      mapper->SetBudgetMB(budget);
      camera->Azimuth(10.0);
      scene.Renderer->ResetCameraClippingRange();
      scene.Window->Render();
      drew = drew && mapper->GetLastRenderOK();
      bounded = bounded && mapper->GetLastTextureBytes() <= budget * 1.0e6;
      uploaded[lap] += mapper->GetLastUploadedBytes();
      count[lap] = std::max(count[lap], mapper->GetResidentTextureCount());
      const vtkTypeInt64 pageBytes = mapper->GetResidentTexturePageBytes();
      const vtkTypeInt64 resident = mapper->GetLastTextureBytes();
      paged = paged && pageBytes >= resident && pageBytes <= 2 * resident + (256 << 10) &&
        mapper->GetResidentTexturePageCount() > 0;
      pageRatio =
        std::max(pageRatio, static_cast<double>(pageBytes) / std::max<vtkTypeInt64>(resident, 1));
      draws += mapper->GetLastBrickDraws();
      drawn += mapper->GetLastBricks();
      runs = runs && mapper->GetLastBrickDraws() >= 1 &&
        mapper->GetLastBrickDraws() <= mapper->GetLastBricks();
    }
  }
  std::cout << "uploaded bytes lap 1 " << uploaded[0] << ", lap 2 " << uploaded[1]
            << "; most resident textures lap 1 " << count[0] << ", lap 2 " << count[1]
            << "; texture pages at most " << pageRatio << "x the resident bytes, "
            << mapper->GetResidentTexturePageCount() << " pages at the end; " << draws
            << " draw calls for " << drawn << " bricks\n";
  check.Check(drew, "every frame drew:\n" + errors->AllErrors());
  check.Check(bounded, "resident texture bytes never above the budget");
  check.Check(uploaded[0] > 0 && uploaded[1] <= uploaded[0], "the second lap uploads no more");
  check.Check(count[1] <= count[0], "resident textures do not grow");
  check.Check(paged, "texture pages hold the resident bricks within 2x their bytes + 256 KiB");
  check.Check(runs && 2 * draws <= drawn, "bricks drawn in runs: at most one call for 2 bricks");
  mapper->ReleaseGraphicsResources(scene.Window);
  check.Check(mapper->GetResidentTextureCount() == 0 &&
      mapper->GetResidentTexturePageCount() == 0 && mapper->GetResidentTexturePageBytes() == 0,
    "released textures and their pages are gone");
  scene.Window->Render();
  check.Check(mapper->GetLastRenderOK() && mapper->GetLastUploadedBytes() > 0,
    "a frame after the release uploads again");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}

int Interactive()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(1.0);
  mapper->SetInteractiveBudgetMB(0.1);
  scene.Window->SetDesiredUpdateRate(30.0);
  scene.Window->Render();
  const bool interactive = mapper->GetLastInteractive();
  const vtkTypeInt64 interactiveBytes = mapper->GetLastTextureBytes();
  const double interactiveError = mapper->GetLastEstimatedError();
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  std::cout << "interactive: " << interactiveBytes << " texture bytes, estimated error "
            << interactiveError << "; still: " << mapper->GetLastTextureBytes()
            << " resident bytes, estimated error " << mapper->GetLastEstimatedError() << "\n";
  check.Check(interactive, "30 frames a second is interactive");
  check.Check(interactiveBytes <= 100000, "the interactive frame keeps to its budget");
  check.Check(!mapper->GetLastInteractive(), "the still frame is not interactive");
  check.Check(mapper->GetLastEstimatedError() < interactiveError, "the still frame refines");
  check.Check(mapper->GetLastTextureBytes() > interactiveBytes, "with more texture bytes");
  // PrintSelf shows every setting and statistic.
  std::ostringstream printed;
  mapper->Print(printed);
  for (const char* name : { "BudgetMB: 1", "InteractiveBudgetMB: 0.1", "ErrorTolerance", "UseRoi",
         "RoiCenter", "RoiRadius", "ShowSurface", "Isovalue", "SurfaceColor", "SurfaceOpacity",
         "LastBricks", "LastTextureBytes", "LastUploadedBytes", "LastPlan: volume",
         "LastFrameMilliseconds", "LastEstimatedError", "LastInteractive: 0", "LastRenderOK: 1" })
  {
    check.Check(
      printed.str().find(name) != std::string::npos, std::string("PrintSelf shows ") + name);
  }
  return check.Result();
}

/// How many of the warnings `errors` recorded since the last call contain
/// `fragment`, with all of them in `all` (one a line); clears them.
int TakeWarnings(
  ErrorRecorder* errors, const std::string& fragment, std::string& all, int* total = nullptr)
{
  int count = 0;
  all.clear();
  for (const std::string& w : errors->Warnings)
  {
    count += w.find(fragment) != std::string::npos ? 1 : 0;
    all += w + "\n";
  }
  if (total)
  {
    *total = static_cast<int>(errors->Warnings.size());
  }
  errors->Clear();
  return count;
}

int Warnings()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const std::vector<double> plain = Grab(scene.Window);
  std::string all;
  check.Check(TakeWarnings(errors, "", all) == 0, "no warning for the supported settings:\n" + all);

  // Each setting: turn it on, the fragment its warning must hold, turn it off.
  struct Setting
  {
    const char* Fragment;
    std::function<void(bool)> Turn;
  };
  const std::vector<Setting> settings = {
    { "the Slice blend mode",
      [&](bool on) { mapper->SetBlendMode(on ? vtkVolumeMapper::SLICE_BLEND : 0); } },
    { "the 2D transfer function",
      [&](bool on) {
        scene.Property->SetTransferFunctionMode(
          on ? vtkVolumeProperty::TF_2D : vtkVolumeProperty::TF_1D);
      } },
  };
  for (const Setting& s : settings)
  {
    s.Turn(true);
    scene.Window->Render();
    const std::vector<double> with = Grab(scene.Window);
    int total = 0;
    const int named = TakeWarnings(errors, s.Fragment, all, &total);
    check.Check(
      named == 1 && total == 1, std::string("one warning naming ") + s.Fragment + ", got:\n" + all);
    check.Check(mapper->GetLastRenderOK() && Rmse(with, plain) < 1e-6,
      std::string("drawn as without it: ") + s.Fragment);
    scene.Window->Render();
    check.Check(
      TakeWarnings(errors, "", all) == 0, std::string("told once: ") + s.Fragment + "\n" + all);
    s.Turn(false);
    scene.Window->Render();
    check.Check(TakeWarnings(errors, "", all) == 0, std::string("off: no warning: ") + s.Fragment);
    s.Turn(true);
    scene.Window->Render();
    check.Check(TakeWarnings(errors, s.Fragment, all) == 1,
      std::string("on again: told again: ") + s.Fragment + "\n" + all);
    s.Turn(false);
    scene.Window->Render();
    errors->Clear();
  }
  // Another value of the same setting is another warning.
  mapper->SetBlendModeToSlice();
  scene.Window->Render();
  mapper->SetBlendMode(7); // no VTK blend mode
  scene.Window->Render();
  check.Check(TakeWarnings(errors, "the blend mode 7 blend mode", all) == 1,
    "blend mode 7 after Slice:\n" + all);
  mapper->SetBlendModeToComposite();

  // Dependent components: a two-component image, component 0 drawn.
  vtkNew<vtkImageData> image;
  image->SetDimensions(9, 9, 9);
  vtkNew<vtkDoubleArray> values;
  values->SetNumberOfComponents(2);
  values->SetNumberOfTuples(9 * 9 * 9);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    // Component 1, the opacity of dependent components: where the scene's opacity shows.
    values->SetTuple2(i, 0.01 * i, scene.Range[1]);
  }
  image->GetPointData()->SetScalars(values);
  mapper->SetInputDataObject(image);
  mapper->SetComponent(0);
  scene.Window->Render();
  check.Check(TakeWarnings(errors, "", all) == 0, "independent components: no warning\n" + all);
  // Two dependent components (colour, opacity) are drawn in Composite: no warning.
  scene.Property->IndependentComponentsOff();
  scene.Window->Render();
  check.Check(TakeWarnings(errors, "", all) == 0, "2 dependent components: no warning\n" + all);
  check.Check(mapper->GetLastRenderOK() &&
      std::string(mapper->GetLastEffects()).find("dependent-components") != std::string::npos,
    "2 dependent components drawn as such: " + std::string(mapper->GetLastEffects()));
  // Under a reducing blend mode the chosen component is drawn, and said so.
  mapper->SetBlendModeToMaximumIntensity();
  scene.Window->Render();
  check.Check(TakeWarnings(errors, "drawn in Composite only", all) == 1,
    "2 dependent components under MIP named:\n" + all);
  check.Check(mapper->GetLastRenderOK(), "2 dependent components under MIP: component 0 drawn");
  mapper->SetBlendModeToComposite();
  // Four dependent components (RGBA) are drawn in Composite: no warning.
  vtkNew<vtkDoubleArray> rgba;
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(9 * 9 * 9);
  for (vtkIdType i = 0; i < rgba->GetNumberOfTuples(); ++i)
  {
    rgba->SetTuple4(i, 0.01 * i, 0.5, 0.5, scene.Range[1]);
  }
  image->GetPointData()->SetScalars(rgba);
  scene.Window->Render();
  check.Check(TakeWarnings(errors, "", all) == 0, "4 dependent components: no warning\n" + all);
  check.Check(mapper->GetLastRenderOK() &&
      std::string(mapper->GetLastEffects()).find("rgba-components") != std::string::npos,
    "4 dependent components drawn as RGBA: " + std::string(mapper->GetLastEffects()));
  // Three dependent components (RGB, no opacity) are not drawn as such: component 0, said so.
  vtkNew<vtkDoubleArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(9 * 9 * 9);
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    rgb->SetTuple3(i, 0.01 * i, 0.5, 0.5);
  }
  image->GetPointData()->SetScalars(rgb);
  scene.Window->Render();
  check.Check(
    TakeWarnings(errors, "3-component array", all) == 1, "3 dependent components named:\n" + all);
  check.Check(mapper->GetLastRenderOK(), "3 dependent components: component 0 drawn");
  return check.Result();
}

int Grey()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  const double lo = scene.Range[0], hi = scene.Range[1];
  vtkNew<vtkColorTransferFunction> rgb;
  rgb->AddRGBPoint(lo, 0.2, 0.2, 0.2);
  rgb->AddRGBPoint(hi, 0.9, 0.9, 0.9);
  scene.Property->SetColor(rgb);
  scene.Window->Render();
  const std::vector<double> fromRgb = Grab(scene.Window);
  vtkNew<vtkPiecewiseFunction> grey;
  grey->AddPoint(lo, 0.2);
  grey->AddPoint(hi, 0.9);
  scene.Property->SetColor(grey);
  scene.Window->Render();
  const std::vector<double> fromGrey = Grab(scene.Window);
  const double rmse = Rmse(fromGrey, fromRgb);
  std::cout << "grey against equal RGB: RMSE " << rmse << ", signal " << Signal(fromGrey) << "\n";
  check.Check(mapper->GetLastRenderOK() && Signal(fromGrey) > 0.005, "the grey volume shows");
  check.Check(rmse < 1e-6, "a grey function draws as the equal RGB function");
  check.Check(scene.Property->GetColorChannels(0) == 1, "the property keeps its grey function");
  return check.Result();
}

int InteractiveResident(bool surface)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(1.0);
  mapper->SetInteractiveBudgetMB(0.1);
  const double mid = 0.5 * (scene.Range[0] + scene.Range[1]);
  if (surface)
  {
    mapper->ShowSurfaceOn();
    mapper->SetIsovalue(mid + 0.3 * (scene.Range[1] - mid));
    mapper->SetSurfaceOpacity(0.4);
  }
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  vtkRenderWindow* window = scene.Window;
  const std::string plan = surface ? "surface-per-brick,volume" : "volume";

  // A still frame makes its textures resident.
  window->SetDesiredUpdateRate(0.0001);
  window->Render();
  const std::vector<double> still = Grab(window);
  const int bricks = mapper->GetLastBricks();
  const vtkTypeInt64 resident = mapper->GetLastTextureBytes();
  const double error = mapper->GetLastEstimatedError();
  check.Check(mapper->GetLastRenderOK() && !mapper->GetLastInteractive() && resident > 0,
    "the still frame drew:\n" + errors->AllErrors());

  // Interactive frames at full sampling: the still picture from resident textures.
  mapper->AutoAdjustSampleDistancesOff();
  window->SetDesiredUpdateRate(30.0);
  window->Render();
  const double full = Rmse(Grab(window), still);
  check.Check(mapper->GetLastInteractive() && mapper->GetLastRenderOK(), "interactive frame drawn");
  check.Check(mapper->GetLastUploadedBytes() == 0, "no upload after the still frame");
  check.Check(mapper->GetLastBricks() == bricks && mapper->GetLastTextureBytes() == resident,
    "the still frame's bricks, resident");
  check.Check(mapper->GetLastImageSampleDistance() == 1.0 && mapper->GetLastSampleSpacing() == 1,
    "full sampling without AutoAdjustSampleDistances");
  check.Check(
    mapper->GetLastPlan() == plan, "interactive plan " + plan + ": " + mapper->GetLastPlan());

  // The coarsest sampling: a million frames a second leaves a microsecond.
  mapper->AutoAdjustSampleDistancesOn();
  window->SetDesiredUpdateRate(1.0e6);
  window->Render();
  const double coarse = Rmse(Grab(window), still);
  check.Check(mapper->GetLastImageSampleDistance() == 6.0 && mapper->GetLastSampleSpacing() == 2,
    "the coarsest sampling: image sample distance 6, samples every 2 d0");
  check.Check(mapper->GetLastUploadedBytes() == 0, "no upload at the coarsest sampling");
  // The camera moves: still no uploads.
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  vtkTypeInt64 uploaded = 0;
  for (int k = 0; k < 5; ++k)
  {
    camera->Azimuth(10.0);
    window->Render();
    uploaded += mapper->GetLastUploadedBytes();
  }
  camera->Azimuth(-50.0);
  check.Check(uploaded == 0, "no upload while the camera moves");
  std::cout << (surface ? "surface" : "volume") << ": interactive RMSE to the still picture "
            << full << " at full sampling, " << coarse << " at the coarsest\n";
  // Measured: volume 0 and 0.0045; surface 0.044 and 0.052 (its triangles
  // before or after their brick's volume instead of between its slices).
  check.Check(full <= (surface ? 0.06 : 0.001), "full sampling: the still picture");
  check.Check(coarse > (surface ? 0.0 : full) && coarse <= (surface ? 0.07 : 0.01),
    "the coarsest sampling: within RMSE 0.01 (surface: 0.07)");

  // The release: a still frame, the full one again.
  window->SetDesiredUpdateRate(0.0001);
  window->Render();
  const double released = Rmse(Grab(window), still);
  check.Check(!mapper->GetLastInteractive() && mapper->GetLastImageSampleDistance() == 1.0 &&
      mapper->GetLastSampleSpacing() == 1,
    "the still frame samples fully");
  check.Check(mapper->GetLastBricks() == bricks && mapper->GetLastEstimatedError() == error &&
      mapper->GetLastUploadedBytes() == 0,
    "the still frame's selection, still resident");
  check.Check(released < 0.002, "the still picture again: RMSE " + std::to_string(released));

  // An opacity changed while interactive: the still selection is out of date,
  // so an interactive frame selects under the interactive budget.
  window->SetDesiredUpdateRate(30.0);
  scene.Property->GetScalarOpacity()->AddPoint(mid + 0.1 * (scene.Range[1] - mid), 0.02);
  window->Render();
  check.Check(mapper->GetLastRenderOK() && mapper->GetLastInteractive() &&
      mapper->GetLastUploadedBytes() <= 100000 && mapper->GetLastEstimatedError() > error,
    "a new opacity while interactive: the interactive budget");
  check.Check(NoGLError(window), "no OpenGL error left behind");
  return check.Result();
}

int BadInput(const std::string& scenario)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->RemoveAllInputConnections(0);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  std::string expected;
  vtkNew<vtkPolyData> polyData;
  vtkNew<vtkImageData> image;
  image->SetDimensions(9, 9, 9);
  vtkNew<vtkDoubleArray> values;
  values->SetName("values");
  if (scenario == "no_input")
  {
    expected = "no input";
  }
  else if (scenario == "not_image")
  {
    mapper->SetInputDataObject(polyData);
    expected = "not a vtkImageData";
  }
  else if (scenario == "budget_zero")
  {
    mapper->SetInputConnection(scene.Wavelet->GetOutputPort());
    mapper->SetBudgetMB(0.0);
    expected = "budget";
  }
  else if (scenario == "point_factor")
  {
    // Points completing stride-3 textures: the octree's strides are powers of two.
    mapper->SetInputConnection(scene.Wavelet->GetOutputPort());
    mapper->UsePointsOn();
    mapper->SetPointFactor(3);
    expected = "factor 3";
  }
  else if (scenario == "multi_component")
  {
    values->SetNumberOfComponents(3);
    values->SetNumberOfTuples(9 * 9 * 9);
    values->Fill(1.0);
    image->GetPointData()->SetScalars(values);
    mapper->SetInputDataObject(image);
    expected = "SetComponent";
  }
  else if (scenario == "empty_image")
  {
    vtkNew<vtkImageData> empty;
    mapper->SetInputDataObject(empty);
    expected = "empty";
  }
  else if (scenario == "infinity" || scenario == "all_nan")
  {
    const bool all = scenario == "all_nan";
    values->SetNumberOfTuples(9 * 9 * 9);
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      values->SetValue(i,
        all || i == 50 ? nan
          : i == 100   ? -std::numeric_limits<double>::infinity()
                       : 0.01 * i);
    }
    image->GetPointData()->SetScalars(values);
    mapper->SetInputDataObject(image);
    expected = all ? "no data: all 729 samples are NaN"
                   : "1 infinite sample(s), the first at point index 100";
  }
  scene.Window->Render();
  // vtkVolume skips a mapper without input: call Render() directly as well.
  mapper->Render(scene.Renderer, scene.Volume);
  check.Check(
    errors->HasError(expected), "error containing '" + expected + "'; got\n" + errors->AllErrors());
  check.Check(!mapper->GetLastRenderOK(), "nothing drawn");
  check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
  return check.Result();
}
} // namespace

int TestHybridOctreeVolumeMapperFrames(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "orbit";
  if (scenario == "orbit")
  {
    return Orbit();
  }
  if (scenario == "interactive")
  {
    return Interactive();
  }
  if (scenario == "warnings")
  {
    return Warnings();
  }
  if (scenario == "grey")
  {
    return Grey();
  }
  if (scenario == "interactive_resident" || scenario == "interactive_surface")
  {
    return InteractiveResident(scenario == "interactive_surface");
  }
  return BadInput(scenario);
}
