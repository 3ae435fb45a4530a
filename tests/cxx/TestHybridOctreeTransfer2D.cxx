/**
 * vtkHybridOctreeVolumeMapper with vtkVolumeProperty's 2D transfer function
 * (TF_2D mode, GetTransferFunction2D(); ParaView's Use 2D Transfer Function)
 * on the wavelet of HybridOctreeMapperScene.h. Metric: RMSE of the RGB
 * channels in [0, 1] over the background.
 *
 *   transfer_2d: a 2D table whose opacity rises with the value and the
 *                gradient magnitude, under a budget with a region of interest
 *                (bricks of several strides): the GL picture within RMSE 0.005
 *                of the CPU compositor on the same DrawList (the same
 *                algorithm; the existing scenarios' bound), effects
 *                "transfer-2d,sample-distance", no warning; it differs from the
 *                1D functions' picture (RMSE > 0.01); the same in 1D mode is the
 *                1D picture with no "transfer-2d" effect (no 2D work); shaded:
 *                "transfer-2d,shading,sample-distance" within the same bound; under Maximum
 *                Intensity: the 1D functions, one warning naming Composite.
 *   gpu_transfer_2d: the same table, shaded and unshaded, the full volume in
 *                the budget, against vtkGPUVolumeRayCastMapper with the same
 *                property (sample distance 1 = the smallest spacing, no
 *                jitter): RMSE < 0.01 (see the printed measure).
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkGPUVolumeRayCastMapper.h"

#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// A 64 x 32 table over VTK's axes (x the value over the data range, y the
/// gradient magnitude over [0, range / 4] per mean spacing; the wavelet's
/// magnitudes reach y ~ 0.35): colour by value and gradient, opacity 0
/// below 45 % of the range, then rising with the value and with the
/// gradient (a flat region is fainter than a boundary).
vtkSmartPointer<vtkImageData> MakeTable()
{
  const int w = 64, h = 32;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_FLOAT, 4);
  float* t = static_cast<float*>(image->GetScalarPointer());
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double x = (i + 0.5) / w, y = (j + 0.5) / h;
      float* c = t + 4 * (i + j * w);
      c[0] = static_cast<float>(x);
      c[1] = static_cast<float>(0.3 + 0.7 * std::min(1.0, 3.0 * y));
      c[2] = static_cast<float>(1.0 - x);
      const double ramp = x < 0.45 ? 0.0 : std::min(1.0, (x - 0.45) / 0.4);
      c[3] = static_cast<float>(0.12 * ramp * (0.15 + 0.85 * std::min(1.0, 4.0 * y)));
    }
  }
  return image;
}

void UseTable(vtkVolumeProperty* property, vtkImageData* table)
{
  property->SetTransferFunction2D(table);
  property->SetTransferFunctionModeTo2D();
}

int CpuMatch()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  // A mix of strides (as the cpu_match scenario): 0.12 MB with a region of interest.
  mapper->SetBudgetMB(0.12);
  mapper->UseRoiOn();
  mapper->SetRoiCenter(16.0, 16.0, 16.0);
  mapper->SetRoiRadius(10.0);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  scene.Window->Render();
  const std::vector<double> oneD = Grab(scene.Window);
  check.Check(std::string(mapper->GetLastEffects()).empty(), "1D: no effect");
  vtkSmartPointer<vtkImageData> table = MakeTable();
  UseTable(scene.Property, table);
  CompareWithCpu(check, scene, mapper, 0.005, errors);
  const std::vector<double> twoD = Grab(scene.Window);
  // The 2D function slices at VTK's sample distance (plan::sampling).
  check.Check(std::string(mapper->GetLastEffects()) == "transfer-2d,sample-distance",
    std::string("effects 'transfer-2d,sample-distance', not '") + mapper->GetLastEffects() + "'");
  check.Check(std::string(mapper->GetLastPlan()) == "volume",
    std::string("plan 'volume', not '") + mapper->GetLastPlan() + "'");
  check.Check(mapper->GetLastBricks() > 8, "many bricks");
  const double change = Rmse(twoD, oneD);
  std::cout << "RGB RMSE 2D vs 1D functions " << change << "\n";
  check.Check(change > 0.01, "the 2D transfer function shows");
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "the 2D transfer function is drawn, no warning:\n" + errors->AllErrors());

  // The table changed in place (its MTime): the next frame draws the new one.
  float* t = static_cast<float*>(table->GetScalarPointer());
  for (int k = 0; k < 64 * 32; ++k)
  {
    t[4 * k + 3] *= 0.5f;
  }
  table->Modified();
  CompareWithCpu(check, scene, mapper, 0.005, errors);
  check.Check(Rmse(Grab(scene.Window), twoD) > 0.005, "a modified table is drawn anew");

  // Back to 1D: no 2D work, the 1D picture.
  scene.Property->SetTransferFunctionModeTo1D();
  scene.Window->Render();
  const double back = Rmse(Grab(scene.Window), oneD);
  std::cout << "1D again: effects '" << mapper->GetLastEffects() << "', RGB RMSE against 1D "
            << back << "\n";
  check.Check(std::string(mapper->GetLastEffects()).empty() && back < 1e-6,
    "1D mode: no 'transfer-2d', the 1D picture");

  // Shaded: one gradient for both.
  UseTable(scene.Property, table);
  scene.Property->ShadeOn();
  CompareWithCpu(check, scene, mapper, 0.005, errors);
  check.Check(std::string(mapper->GetLastEffects()) == "transfer-2d,shading,sample-distance" &&
      std::string(mapper->GetLastPlan()) == "volume-shaded",
    std::string("shaded: effects '") + mapper->GetLastEffects() + "', plan '" +
      mapper->GetLastPlan() + "'");
  check.Check(errors->Warnings.empty(), "shaded: no warning:\n" + errors->AllErrors());
  scene.Property->ShadeOff();

  // Maximum intensity: the 1D functions, warned once.
  mapper->SetBlendModeToMaximumIntensity();
  scene.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "MIP drew");
  check.Check(std::string(mapper->GetLastEffects()).empty(), "MIP: no 2D transfer function");
  bool warned = false;
  for (const std::string& w : errors->Warnings)
  {
    warned = warned || w.find("Composite blend mode only") != std::string::npos;
  }
  check.Check(warned, "MIP with a 2D transfer function warns:\n" + errors->AllErrors());
  return check.Result();
}

int Gpu()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  // VTK's alpha is per its sample distance, here 1 (vtkSmartVolumeMapper's otherwise).
  mapper->SetTransfer2DSampleDistance(1.0);
  mapper->SetSampleDistance(1.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->AutoAdjustSampleDistancesOff();
  gpu->SetSampleDistance(1.0);
  gpu->SetUseJittering(0);
  Scene theirs(gpu);
  vtkSmartPointer<vtkImageData> table = MakeTable();
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  for (bool shade : { false, true })
  {
    for (Scene* s : { &ours, &theirs })
    {
      UseTable(s->Property, table);
      s->Property->SetShade(shade ? 1 : 0);
    }
    ours.Window->Render();
    theirs.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    const std::string effects = shade ? "transfer-2d,shading" : "transfer-2d";
    check.Check(mapper->GetLastEffects() == effects,
      "effects '" + effects + "', not '" + mapper->GetLastEffects() + "'");
    const std::vector<double> a = Grab(ours.Window);
    const std::vector<double> b = Grab(theirs.Window);
    const double rmse = Rmse(a, b);
    // How much the 2D function changes VTK's picture (against its 1D functions).
    theirs.Property->SetTransferFunctionModeTo1D();
    theirs.Window->Render();
    const double change = Rmse(Grab(theirs.Window), b);
    std::cout << (shade ? "shaded" : "unshaded") << ": bricks " << mapper->GetLastBricks()
              << ", texture bytes " << mapper->GetLastTextureBytes()
              << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse
              << " (threshold 0.01), signal " << Signal(b) << ", 2D vs 1D in VTK " << change
              << "\n";
    check.Check(Signal(b) > 0.01, "the reference shows the volume");
    check.Check(change > 5.0 * rmse, "the 2D transfer function shows");
    check.Check(rmse < 0.01, "within 0.01 of vtkGPUVolumeRayCastMapper");
  }
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "no error or warning:\n" + errors->AllErrors());
  return check.Result();
}
} // namespace

int TestHybridOctreeTransfer2D(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "transfer_2d";
  if (scenario == "transfer_2d")
  {
    return CpuMatch();
  }
  if (scenario == "gpu_transfer_2d")
  {
    return Gpu();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
