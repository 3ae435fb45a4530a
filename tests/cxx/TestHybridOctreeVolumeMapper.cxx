/**
 * Pictures of vtkHybridOctreeVolumeMapper under Xvfb (Mesa llvmpipe), on the
 * scene of HybridOctreeMapperScene.h. Metric: RMSE of the RGB channels in
 * [0, 1] over the 256x256 window.
 *
 *   cpu_match:   a budget under the full volume (many bricks, several
 *                strides) against the CPU compositor executing the same
 *                DrawList and table (same algorithm: RMSE < 0.005; the mapper
 *                composites in a float target, the window rounds once).
 *   tiny_opacity: cpu_match with opacities of 0.001 to 0.004 a sample,
 *                summed over ~65 slices (each slice's c a' is below an 8-bit
 *                step): RMSE < 0.004.
 *   inside:      cpu_match with the camera inside the volume (rays start at
 *                the near plane): the same threshold.
 *   multisample: cpu_match in a 4-sample window (the mapper blits the
 *                window's depth, which resolves it): the same threshold.
 *   opaque_surface, translucent_surface: the isosurface drawn with the
 *                volume (opaque pre-pass with depth; batches in the slabs)
 *                against the CPU compositor: RMSE < 0.006 (rasterised
 *                triangle edges against ray-triangle hits).
 *   points_square, points_gaussian: cpu_match with the hybrid
 *                representation's points (factor 2) bought within the same
 *                budget and drawn in the slabs, square or Gaussian
 *                footprints, against the CPU compositor splatting the same
 *                points: RMSE < 0.004; the points change the picture
 *                (RMSE > 0.005 against it without them) and bring it closer
 *                to the full resolution (RMSE at most 0.8 times).
 *                The wavelet gets bars 3 samples wide at its maximum,
 *                which stride-2 textures smear and the points sharpen.
 *   points_surface: points_square with a translucent isosurface, both in
 *                the slabs, each slab's triangles and points far first:
 *                RMSE < 0.01 against the CPU compositor (which orders them
 *                per pixel, OpenGL per primitive).
 *   nan_hole:    cpu_match on the wavelet with a NaN ball (radius 8, in the
 *                region of interest) and a NaN slab on the x = -32 face: NaN
 *                is no data, transparent in the shader as in the CPU
 *                compositor (llvmpipe's linear filter keeps NaN): RMSE <
 *                0.005 (measured 0.0016), no error message, the holes
 *                show (RMSE > 0.005 against the picture without them;
 *                measured 0.016) and GetLastNaNSamples() counts them.
 *   gpu_reference: at a budget holding the full volume, against VTK's
 *                vtkGPUVolumeRayCastMapper (rays every spacing, not slices):
 *                RMSE < 0.03; every visible brick is drawn at full
 *                resolution, so GetLastEstimatedError() is 0.
 *   actor:       an opaque vtkActor (a sphere) intersecting the volume: the
 *                same scene drawn by vtkGPUVolumeRayCastMapper, RMSE < 0.03,
 *                and the sphere hides the volume behind it.
 *   shaded:      Shade on (VTK's default material, the default headlight),
 *                mixed strides: the plan is "volume-shaded", the GL picture
 *                within RMSE 0.005 of the CPU compositor on the same
 *                DrawList, and it differs from the unshaded one.
 *   gpu_shaded, gpu_light_kit: Shade on, the full volume in the budget,
 *                against vtkGPUVolumeRayCastMapper with the default
 *                headlight and with a vtkLightKit: RMSE < 0.03.
 *   cropped:     cropping (fence flags) and a clipping plane, mixed strides:
 *                GetLastEffects() is "cropping,clipping", the plan "volume",
 *                the GL picture within RMSE 0.005 of the CPU compositor on
 *                the same DrawList, it differs from the uncropped one, no
 *                warning; a cropping box around the whole volume and a plane
 *                with the volume on its kept side remove nothing: no effect,
 *                the uncropped picture. The region again with a gradient
 *                opacity and Shade (effects
 *                "gradient-opacity,shading,cropping,clipping"), then under
 *                MIP, additive and Isosurface: each GL vs CPU within the
 *                same bound.
 *   gpu_cropped, gpu_cropped_moved: cropping (the subvolume) and two
 *                clipping planes, the full volume in the budget, against
 *                vtkGPUVolumeRayCastMapper with the same settings: RMSE <
 *                0.03; moved: the vtkVolume rotated and translated (the
 *                cropping planes stay in data coordinates, the clipping
 *                planes in world coordinates).
 *   gradient_opacity, gradient_opacity_shaded: a gradient opacity
 *                (vtkVolumeProperty::SetGradientOpacity, VTK's magnitudes
 *                per voxel), unshaded and shaded, mixed strides: the effects
 *                are "gradient-opacity" (and "shading"), the GL picture
 *                within RMSE 0.003 of the CPU compositor on the same
 *                DrawList (measured 0.0016), it differs from the picture
 *                without it (0.049, shaded 0.028), no warning; a constant
 *                gradient opacity of 1 is no effect (the picture without
 *                it), a constant 0.5 the effect "opacity-scale" (GL vs CPU
 *                0.0016).
 *   gpu_gradient_opacity: that gradient opacity, shaded, the full volume in
 *                the budget, against vtkGPUVolumeRayCastMapper with the same
 *                property: RMSE < 0.01 (measured 0.0016, while the gradient
 *                opacity moves VTK's picture by 0.012; VTK multiplies after
 *                its opacity correction, the core before it: equal at first
 *                order in the opacity).
 *   mip, minip, average, additive: cpu_match under the blend mode (an
 *                opacity above 0 everywhere, so that MinIP shows too), mixed
 *                strides (MIP and MinIP bricks with peak-keeping texels): the
 *                plan is "volume-<mode>", the GL reduction resolved through
 *                the transfer function within RMSE 0.005 of the CPU
 *                compositor, no warning, and the picture is not Composite's.
 *   isosurface:  cpu_match under the Isosurface blend mode (two values;
 *                a sample shows the value crossed since the one before it),
 *                same bound.
 *   gpu_composite, gpu_mip, gpu_minip, gpu_average, gpu_additive, gpu_isosurface: the
 *                blend mode with the full volume in the budget, against
 *                vtkGPUVolumeRayCastMapper under the same mode, with
 *                ScalarOpacityUnitDistance 1 (the spacing) and 5: RMSE < 0.03
 *                each, Additive at 5 < 0.01 (VTK corrects its opacity table
 *                by 1 - (1 - a)^(s / U) for Composite, by a s / U for
 *                Additive, not for the others). Measured at U = 5: composite
 *                0.0049, MIP 0.0047, MinIP 0.0054, average 0.022, additive
 *                0.0052, isosurface 0.0075; with the power rule in every mode
 *                but Composite's: 0.063, 0.036, 0.062, 0.022, 0.093.
 *   matrix:      the volume rotated and moved with its vtkVolume matrix, and
 *                the camera and the region of interest moved alike: the same
 *                bricks and picture, RMSE < 0.01.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkActor.h"
#include "vtkAutoInit.h"
#include "vtkContourValues.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkLightKit.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"

#include <iostream>
#include <limits>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// The gradient opacity of the gradient_opacity scenarios on `scene`'s
/// property: VTK's magnitudes per voxel (the wavelet's are up to about 20),
/// 0.05 at 0 rising to 1 at 12, so homogeneous regions fade.
void SetGradientOpacity(Stage& scene)
{
  vtkNew<vtkPiecewiseFunction> gradient;
  gradient->AddPoint(0.0, 0.05);
  gradient->AddPoint(12.0, 1.0);
  scene.Property->SetGradientOpacity(gradient);
}

/// The blend mode of a scenario ("mip", "gpu_minip", "gpu_composite", ...), -1 for the others.
int BlendOf(std::string scenario)
{
  if (scenario.rfind("gpu_", 0) == 0)
  {
    scenario = scenario.substr(4);
  }
  const char* names[] = { "composite", "mip", "minip", "average", "additive", "isosurface" };
  for (int mode = 0; mode <= 5; ++mode)
  {
    if (scenario == names[mode])
    {
      return mode;
    }
  }
  return -1;
}

/// An opacity above 0 over the whole range (the blend scenarios: a minimum
/// projection of the default function, 0 below the middle, shows nothing).
void OpacityEverywhere(Scene& scene)
{
  // The Isosurface blend mode's two surfaces.
  const double lo0 = scene.Range[0], hi0 = scene.Range[1];
  scene.Property->GetIsoSurfaceValues()->SetValue(0, lo0 + 0.6 * (hi0 - lo0));
  scene.Property->GetIsoSurfaceValues()->SetValue(1, lo0 + 0.75 * (hi0 - lo0));
  vtkNew<vtkPiecewiseFunction> opacity;
  const double lo = scene.Range[0], hi = scene.Range[1];
  opacity->AddPoint(lo, 0.5);
  opacity->AddPoint(0.5 * (lo + hi), 0.05);
  opacity->AddPoint(hi, 0.6);
  scene.Property->SetScalarOpacity(opacity);
}

int CpuMatch(const std::string& scenario)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  Scene scene(mapper);
  mapper->SetLeafSize(8);
  // The full 65^3 floats are 1.1 MB, the root at stride 2 0.14 MB: under
  // 0.12 MB with a region of interest, a mix of strides.
  mapper->SetBudgetMB(0.12);
  mapper->UseRoiOn();
  mapper->SetRoiCenter(16.0, 16.0, 16.0);
  mapper->SetRoiRadius(10.0);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  double threshold = 0.005;
  std::string plan = "volume";
  if (scenario == "tiny_opacity")
  {
    // 0.001 to 0.004 a sample over ~65 slices: in an 8-bit target each
    // slice's c a' (below 1/255) would round away.
    vtkNew<vtkPiecewiseFunction> tiny;
    tiny->AddPoint(scene.Range[0], 0.0);
    tiny->AddPoint(0.5 * (scene.Range[0] + scene.Range[1]), 0.001);
    tiny->AddPoint(scene.Range[1], 0.004);
    scene.Property->SetScalarOpacity(tiny);
    threshold = 0.004;
  }
  if (scenario == "inside")
  {
    // The camera inside the volume, near a corner where the opacity is 0:
    // rays start at the near plane (0.01 from the eye; the CPU compositor's
    // rays start at the eye itself, whose sample is transparent there),
    // bricks behind the eye draw nothing.
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    camera->SetPosition(27.0, -25.0, 26.0);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetClippingRange(0.01, 200.0);
  }
  if (scenario == "multisample")
  {
    scene.Window->SetMultiSamples(4); // the opaque depth is resolved by a blit
  }
  if (scenario == "opaque_surface" || scenario == "translucent_surface")
  {
    mapper->ShowSurfaceOn();
    mapper->SetIsovalue(scene.Range[0] + 0.7 * (scene.Range[1] - scene.Range[0]));
    mapper->SetSurfaceColor(0.9, 0.85, 0.7);
    const bool opaque = scenario == "opaque_surface";
    mapper->SetSurfaceOpacity(opaque ? 1.0 : 0.4);
    plan = opaque ? "surface-opaque,volume" : "surface-in-slabs,volume";
    threshold = 0.006;
  }
  const bool points =
    scenario == "points_square" || scenario == "points_gaussian" || scenario == "points_surface";
  std::vector<double> withoutPoints;
  vtkNew<vtkImageData> bars;
  if (points)
  {
    // Fine detail stride-2 textures smear: bars along z, 3 samples square
    // (x, y = 5, 6, 7 mod 16), at the data's maximum. T_2 keeps their middle
    // sample only and halves the two beside it; the points restore those.
    // (One-sample lines at odd samples, which T_2 loses entirely, buy few
    // points in this budget: 255, 1.6 % closer; with each point's own
    // sample's opacity instead of its voxel mean they made it 3 % worse;
    // see docs/BENCHMARKS.md.)
    bars->DeepCopy(scene.Wavelet->GetOutput());
    vtkDataArray* values = bars->GetPointData()->GetScalars();
    int dims[3];
    bars->GetDimensions(dims);
    for (int z = 0; z < dims[2]; ++z)
    {
      for (int y = 0; y < dims[1]; ++y)
      {
        for (int x = 0; x < dims[0]; ++x)
        {
          if ((x + 11) % 16 < 3 && (y + 11) % 16 < 3)
          {
            values->SetComponent(
              x + dims[0] * (y + static_cast<vtkIdType>(dims[1]) * z), 0, scene.Range[1]);
          }
        }
      }
    }
    mapper->SetInputData(bars);
    if (scenario == "points_surface")
    {
      // A translucent isosurface through the bars: triangles and points in
      // the same slabs (OpenGL draws a slab's triangles, then its points;
      // the CPU compositor sorts both by depth per pixel).
      mapper->ShowSurfaceOn();
      mapper->SetIsovalue(scene.Range[0] + 0.7 * (scene.Range[1] - scene.Range[0]));
      mapper->SetSurfaceColor(0.9, 0.85, 0.7);
      mapper->SetSurfaceOpacity(0.4);
    }
    scene.Window->Render();
    withoutPoints = Grab(scene.Window);
    mapper->UsePointsOn();
    mapper->SetPointFactor(2);
    mapper->SetPointThreshold(0.1);
    if (scenario == "points_gaussian")
    {
      mapper->SetPointFootprintToGaussian();
    }
    const bool surface = scenario == "points_surface";
    plan = surface ? "surface-in-slabs,volume,points" : "volume,points";
    // With the surface: OpenGL orders a slab's triangles and points per
    // primitive (a triangle at its centroid's depth), the CPU compositor
    // per pixel; inside the tubes around the bars that differs (0.0087).
    threshold = surface ? 0.01 : 0.004;
  }
  std::vector<double> withoutHoles;
  vtkNew<vtkImageData> holed;
  vtkTypeInt64 nanSamples = 0;
  if (scenario == "nan_hole")
  {
    scene.Window->Render();
    withoutHoles = Grab(scene.Window);
    holed->DeepCopy(scene.Wavelet->GetOutput());
    vtkDataArray* values = holed->GetPointData()->GetScalars();
    for (vtkIdType id = 0; id < values->GetNumberOfTuples(); ++id)
    {
      double x[3];
      holed->GetPoint(id, x);
      const double r2 =
        (x[0] - 16) * (x[0] - 16) + (x[1] - 16) * (x[1] - 16) + (x[2] - 16) * (x[2] - 16);
      if (x[0] < -28 || r2 <= 64)
      {
        values->SetComponent(id, 0, std::numeric_limits<double>::quiet_NaN());
        ++nanSamples;
      }
    }
    mapper->SetInputData(holed);
  }
  std::vector<double> uncropped;
  vtkNew<vtkPlaneCollection> planes;
  if (scenario == "cropped")
  {
    scene.Window->Render();
    uncropped = Grab(scene.Window);
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(-12.0, 14.0, -10.0, 18.0, -16.0, 9.0);
    mapper->SetCroppingRegionFlagsToFence();
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(4.0, 0.0, 0.0);
    plane->SetNormal(-1.0, 0.3, 0.2);
    planes->AddItem(plane);
    mapper->SetClippingPlanes(planes);
  }
  std::vector<double> unshaded;
  std::vector<double> withoutGradientOpacity;
  const bool gradientOpacity =
    scenario == "gradient_opacity" || scenario == "gradient_opacity_shaded";
  std::string effects;
  if (gradientOpacity)
  {
    if (scenario == "gradient_opacity_shaded")
    {
      scene.Property->ShadeOn();
      plan = "volume-shaded";
    }
    scene.Window->Render();
    withoutGradientOpacity = Grab(scene.Window);
    SetGradientOpacity(scene);
    effects = scenario == "gradient_opacity" ? "gradient-opacity" : "gradient-opacity,shading";
    threshold = 0.003;
  }
  const int blend = BlendOf(scenario);
  std::vector<double> composited;
  if (blend > 0)
  {
    OpacityEverywhere(scene);
    scene.Window->Render();
    composited = Grab(scene.Window);
    mapper->SetBlendMode(blend);
    plan = "volume-" + scenario;
  }
  if (scenario == "shaded")
  {
    scene.Window->Render();
    unshaded = Grab(scene.Window);
    scene.Property->ShadeOn();
    plan = "volume-shaded";
  }
  CompareWithCpu(check, scene, mapper, threshold, errors);
  if (scenario == "shaded")
  {
    const double change = Rmse(Grab(scene.Window), unshaded);
    std::cout << "RGB RMSE shaded vs unshaded " << change << "\n";
    check.Check(change > 0.01, "the shading shows");
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      "Shade is drawn, no warning:\n" + errors->AllErrors());
  }
  if (scenario == "cropped")
  {
    const double change = Rmse(Grab(scene.Window), uncropped);
    std::cout << "effects '" << mapper->GetLastEffects() << "', RGB RMSE cropped vs uncropped "
              << change << "\n";
    check.Check(std::string(mapper->GetLastEffects()) == "cropping,clipping",
      std::string("effects 'cropping,clipping', not '") + mapper->GetLastEffects() + "'");
    check.Check(change > 0.01, "the cropping and the plane show");
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      "cropping and clipping are drawn, no warning:\n" + errors->AllErrors());
    // Removing nothing: no effect, the uncropped picture.
    mapper->SetCroppingRegionPlanes(-40.0, 40.0, -32.0, 32.0, -33.0, 50.0);
    mapper->SetCroppingRegionFlagsToSubVolume();
    vtkPlane::SafeDownCast(planes->GetItemAsObject(0))->SetOrigin(-32.0, -32.0, -32.0);
    vtkPlane::SafeDownCast(planes->GetItemAsObject(0))->SetNormal(1.0, 1.0, 1.0);
    scene.Window->Render();
    const double none = Rmse(Grab(scene.Window), uncropped);
    std::cout << "a region removing nothing: effects '" << mapper->GetLastEffects()
              << "', RGB RMSE against uncropped " << none << "\n";
    // Not bit for bit: bricks the cropped frame did not draw come back in
    // other slots of the texture pages, where the linear filter's weights
    // round otherwise (measured 1.3e-5; a cropping shows above 0.01).
    check.Check(std::string(mapper->GetLastEffects()).empty() && none < 1e-4,
      "a region removing nothing is not drawn");
    // The region again, in the other sampling paths: after the per-sample
    // effects (gradient opacity, shading), and in the reducing and
    // Isosurface blend modes (a removed sample is no sample).
    mapper->SetCroppingRegionPlanes(-12.0, 14.0, -10.0, 18.0, -16.0, 9.0);
    mapper->SetCroppingRegionFlagsToFence();
    vtkPlane::SafeDownCast(planes->GetItemAsObject(0))->SetOrigin(4.0, 0.0, 0.0);
    vtkPlane::SafeDownCast(planes->GetItemAsObject(0))->SetNormal(-1.0, 0.3, 0.2);
    SetGradientOpacity(scene);
    scene.Property->ShadeOn();
    CompareWithCpu(check, scene, mapper, threshold, errors);
    const std::string all = "gradient-opacity,shading,cropping,clipping";
    check.Check(mapper->GetLastEffects() == all,
      "effects '" + all + "', not '" + mapper->GetLastEffects() + "'");
    scene.Property->ShadeOff();
    scene.Property->SetDisableGradientOpacity(1);
    OpacityEverywhere(scene);
    for (const char* mode : { "mip", "additive", "isosurface" })
    {
      mapper->SetBlendMode(BlendOf(mode));
      std::cout << mode << ", cropped and clipped: ";
      CompareWithCpu(check, scene, mapper, threshold, errors);
      // Isosurface slices at VTK's sample distance (plan::sampling).
      const std::string effects = std::string(mode) == "isosurface"
        ? "cropping,clipping,sample-distance"
        : "cropping,clipping";
      check.Check(mapper->GetLastPlan() == "volume-" + std::string(mode) &&
          std::string(mapper->GetLastEffects()) == effects,
        std::string(mode) + ": plan '" + mapper->GetLastPlan() + "', effects '" +
          mapper->GetLastEffects() + "'");
    }
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      "the region with the other effects and blend modes: no warning:\n" + errors->AllErrors());
    plan = "volume-isosurface"; // the last frame's
  }
  if (gradientOpacity)
  {
    const double change = Rmse(Grab(scene.Window), withoutGradientOpacity);
    std::cout << "effects '" << mapper->GetLastEffects()
              << "'; RGB RMSE with vs without the gradient opacity " << change << "\n";
    check.Check(change > 0.01, "the gradient opacity shows");
    check.Check(mapper->GetLastEffects() == effects, "effects '" + effects + "'");
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      "the gradient opacity is drawn, no warning:\n" + errors->AllErrors());
    // Constant functions: 1 is no effect, 0.5 scales every opacity.
    vtkNew<vtkPiecewiseFunction> constant;
    constant->AddPoint(0.0, 1.0);
    constant->AddPoint(100.0, 1.0);
    scene.Property->SetGradientOpacity(constant);
    scene.Window->Render();
    const double one = Rmse(Grab(scene.Window), withoutGradientOpacity);
    const std::string shading = scenario == "gradient_opacity" ? "" : "shading";
    check.Check(one < 1e-6 && mapper->GetLastEffects() == shading,
      "a gradient opacity of 1 everywhere is no effect (RMSE " + std::to_string(one) +
        ", effects '" + mapper->GetLastEffects() + "')");
    constant->RemoveAllPoints();
    constant->AddPoint(0.0, 0.5);
    const std::string halved = shading.empty() ? "opacity-scale" : "opacity-scale,shading";
    CompareWithCpu(check, scene, mapper, threshold, errors);
    check.Check(mapper->GetLastEffects() == halved,
      "a constant gradient opacity 0.5 is '" + halved + "', not '" + mapper->GetLastEffects() +
        "'");
  }
  if (blend > 0)
  {
    const double change = Rmse(Grab(scene.Window), composited);
    std::cout << "RGB RMSE " << scenario << " vs composite " << change << "\n";
    check.Check(change > 0.01, "the blend mode shows");
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      "the blend mode is drawn, no warning:\n" + errors->AllErrors());
  }
  check.Check(mapper->GetLastBricks() > 8, "many bricks");
  if (scenario == "nan_hole")
  {
    const double change = Rmse(Grab(scene.Window), withoutHoles);
    std::cout << "RGB RMSE with vs without the NaN holes " << change << "\n";
    check.Check(change > 0.005, "the NaN holes show");
    check.Check(mapper->GetLastNaNSamples() == nanSamples,
      "the mapper counts " + std::to_string(nanSamples) + " NaN samples, not " +
        std::to_string(mapper->GetLastNaNSamples()));
    check.Check(errors->Errors.empty(), "NaN is no data, not an error:\n" + errors->AllErrors());
  }
  check.Check(mapper->GetLastPlan() == plan, "plan '" + plan + "'");
  check.Check(mapper->GetLastTextureBytes() <= 120000, "texture bytes within the budget");
  if (plan.find("surface-") != std::string::npos)
  {
    check.Check(mapper->GetLastSurfaceTriangles() > 0, "surface triangles drawn");
  }
  if (points)
  {
    const std::vector<double> withPoints = Grab(scene.Window);
    const double change = Rmse(withPoints, withoutPoints);
    std::cout << "points drawn " << mapper->GetLastPoints() << ", point bytes "
              << mapper->GetLastPointBytes() << ", RGB RMSE with vs without points " << change
              << "\n";
    const vtkTypeInt64 drawn = mapper->GetLastPoints();
    const vtkTypeInt64 bytes = mapper->GetLastPointBytes();
    check.Check(drawn > 0, "points drawn");
    check.Check(bytes > 0 && mapper->GetLastTextureBytes() + bytes <= 120000,
      "points bought within the budget with the textures");
    check.Check(change > 0.005, "the points change the picture");
    // Against the full resolution (the whole volume in the budget, no points):
    // the points bring the picture closer.
    mapper->UsePointsOff();
    mapper->SetBudgetMB(4.0);
    scene.Window->Render();
    const std::vector<double> full = Grab(scene.Window);
    const double before = Rmse(withoutPoints, full);
    const double after = Rmse(withPoints, full);
    std::cout << "RGB RMSE against the full resolution: without points " << before
              << ", with points " << after << "\n";
    check.Check(after < 0.8 * before, "the points remove at least 20 % of the error");
    const std::string off = scenario == "points_surface" ? "surface-in-slabs,volume" : "volume";
    check.Check(mapper->GetLastPoints() == 0 && mapper->GetLastPointBytes() == 0 &&
        std::string(mapper->GetLastPlan()) == off,
      "points off: none drawn, plan '" + off + "'");
  }
  return check.Result();
}

/// Shade on, the full volume in the budget, against vtkGPUVolumeRayCastMapper:
/// the default headlight, or a vtkLightKit.
int GpuShaded(bool lightKit)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  Scene theirs(gpu);
  vtkNew<vtkLightKit> kit;
  for (Scene* s : { &ours, &theirs })
  {
    s->Property->ShadeOn();
    if (lightKit)
    {
      s->Renderer->AutomaticLightCreationOff();
      s->Renderer->RemoveAllLights();
      kit->AddLightsToRenderer(s->Renderer);
    }
  }
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  check.Check(std::string(mapper->GetLastPlan()) == "volume-shaded",
    std::string("plan 'volume-shaded', not '") + mapper->GetLastPlan() + "'");
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  std::cout << (lightKit ? "light kit" : "headlight") << ": bricks " << mapper->GetLastBricks()
            << ", texture bytes " << mapper->GetLastTextureBytes()
            << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse
            << " (threshold 0.03), signal " << Signal(b) << "\n";
  check.Check(Signal(b) > 0.02, "the reference shows the volume");
  check.Check(rmse < 0.03, "within 0.03 of vtkGPUVolumeRayCastMapper");
  return check.Result();
}

/// Cropping (the subvolume) and two clipping planes, the full volume in the
/// budget, against vtkGPUVolumeRayCastMapper; `moved`: the vtkVolume
/// rotated and translated, the camera with it.
int GpuCropped(bool moved)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  Scene theirs(gpu);
  vtkNew<vtkTransform> transform;
  transform->Translate(30.0, -20.0, 10.0);
  transform->RotateWXYZ(40.0, 1.0, 2.0, 0.5);
  vtkNew<vtkPlaneCollection> planes;
  vtkNew<vtkPlane> oblique;
  vtkNew<vtkPlane> side;
  // Planes in data coordinates, moved into world coordinates with the volume.
  double o1[3] = { 2.0, 0.0, 4.0 }, n1[3] = { -1.0, 0.4, 0.3 };
  double o2[3] = { 0.0, -14.0, 0.0 }, n2[3] = { 0.0, 1.0, 0.0 };
  if (moved)
  {
    transform->TransformPoint(o1, o1);
    transform->TransformNormal(n1, n1);
    transform->TransformPoint(o2, o2);
    transform->TransformNormal(n2, n2);
  }
  oblique->SetOrigin(o1);
  oblique->SetNormal(n1);
  side->SetOrigin(o2);
  side->SetNormal(n2);
  planes->AddItem(oblique);
  planes->AddItem(side);
  for (Scene* s : { &ours, &theirs })
  {
    vtkVolumeMapper* m = vtkVolumeMapper::SafeDownCast(s->Volume->GetMapper());
    m->CroppingOn();
    m->SetCroppingRegionPlanes(-20.0, 18.0, -25.0, 22.0, -30.0, 12.0);
    m->SetClippingPlanes(planes);
    if (moved)
    {
      s->Volume->SetUserTransform(transform);
      vtkCamera* camera = s->Renderer->GetActiveCamera();
      double p[3], f[3], up[3];
      transform->TransformPoint(camera->GetPosition(), p);
      transform->TransformPoint(camera->GetFocalPoint(), f);
      transform->TransformVector(camera->GetViewUp(), up);
      camera->SetPosition(p);
      camera->SetFocalPoint(f);
      camera->SetViewUp(up);
      s->Renderer->ResetCameraClippingRange();
    }
  }
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  check.Check(std::string(mapper->GetLastEffects()) == "cropping,clipping",
    std::string("effects 'cropping,clipping', not '") + mapper->GetLastEffects() + "'");
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  // Without the cropping and the planes: how much they change the picture.
  gpu->CroppingOff();
  gpu->RemoveAllClippingPlanes();
  theirs.Window->Render();
  const double change = Rmse(Grab(theirs.Window), b);
  std::cout << (moved ? "moved: " : "") << "bricks " << mapper->GetLastBricks()
            << ", texture bytes " << mapper->GetLastTextureBytes()
            << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse
            << " (threshold 0.03), signal " << Signal(b)
            << ", the cropping and planes change it by " << change << "\n";
  check.Check(Signal(b) > 0.01, "the reference shows the volume");
  check.Check(change > 2.0 * rmse, "the cropping and planes show");
  check.Check(rmse < 0.03, "within 0.03 of vtkGPUVolumeRayCastMapper");
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "no error or warning:\n" + errors->AllErrors());
  return check.Result();
}

/// A gradient opacity, shaded, the full volume in the budget, against
/// vtkGPUVolumeRayCastMapper with the same property.
int GpuGradientOpacity()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  Scene theirs(gpu);
  for (Scene* s : { &ours, &theirs })
  {
    s->Property->ShadeOn();
  }
  theirs.Window->Render();
  const std::vector<double> without = Grab(theirs.Window);
  for (Scene* s : { &ours, &theirs })
  {
    SetGradientOpacity(*s);
  }
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  check.Check(std::string(mapper->GetLastEffects()) == "gradient-opacity,shading",
    std::string("effects 'gradient-opacity,shading', not '") + mapper->GetLastEffects() + "'");
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  const double change = Rmse(b, without);
  std::cout << "gradient opacity: bricks " << mapper->GetLastBricks() << ", texture bytes "
            << mapper->GetLastTextureBytes() << "; RGB RMSE against vtkGPUVolumeRayCastMapper "
            << rmse << " (threshold 0.01), signal " << Signal(b)
            << "; the gradient opacity moves VTK's picture by " << change << "\n";
  check.Check(Signal(b) > 0.02, "the reference shows the volume");
  check.Check(change > 2.0 * rmse, "the gradient opacity shows more than the difference");
  check.Check(rmse < 0.01, "within 0.01 of vtkGPUVolumeRayCastMapper");
  return check.Result();
}

/// A blend mode with the full volume in the budget, against
/// vtkGPUVolumeRayCastMapper, at ScalarOpacityUnitDistance 1 (the spacing)
/// and 5.
int GpuBlend(const std::string& scenario)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0);
  // The reference's rays sample every spacing (1): ours slice there too.
  mapper->SetSampleDistance(1.0);
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  Scene theirs(gpu);
  const int blend = BlendOf(scenario);
  mapper->SetBlendMode(blend);
  gpu->SetBlendMode(blend);
  OpacityEverywhere(ours);
  OpacityEverywhere(theirs);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  const std::string plan = blend == 0 ? "volume" : "volume-" + scenario.substr(4);
  std::vector<double> atSpacing;
  for (const double unit : { 1.0, 5.0 })
  {
    ours.Property->SetScalarOpacityUnitDistance(unit);
    theirs.Property->SetScalarOpacityUnitDistance(unit);
    ours.Window->Render();
    theirs.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    check.Check(std::string(mapper->GetLastPlan()) == plan,
      "plan '" + plan + "', not '" + mapper->GetLastPlan() + "'");
    const std::vector<double> a = Grab(ours.Window);
    const std::vector<double> b = Grab(theirs.Window);
    const double rmse = Rmse(a, b);
    // Additive's linear factor against a power: 0.0052 against 0.022 at U = 5.
    const double threshold = blend == vtkVolumeMapper::ADDITIVE_BLEND && unit != 1.0 ? 0.01 : 0.03;
    std::cout << scenario << ", unit distance " << unit << ": bricks " << mapper->GetLastBricks()
              << ", texture bytes " << mapper->GetLastTextureBytes()
              << "; RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse << " (threshold "
              << threshold << "), signal " << Signal(b);
    if (atSpacing.empty())
    {
      atSpacing = b;
    }
    else
    {
      // VTK corrects its table for Composite and Additive only.
      std::cout << "; the unit distance moves VTK's picture by " << Rmse(b, atSpacing);
    }
    std::cout << "\n";
    check.Check(Signal(b) > 0.02, "the reference shows the volume");
    check.Check(rmse < threshold, "within the threshold of vtkGPUVolumeRayCastMapper");
  }
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  return check.Result();
}

int GpuReference(bool withActor)
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(4.0); // the whole volume at stride 1
  Scene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  Scene theirs(gpu);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(10.0, 8.0, 12.0);
  sphere->SetRadius(14.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(0.2, 0.8, 0.3);
  if (withActor)
  {
    ours.Renderer->AddActor(actor);
    theirs.Renderer->AddActor(actor);
    ours.Renderer->ResetCameraClippingRange();
    theirs.Renderer->ResetCameraClippingRange();
  }
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  std::cout << "bricks " << mapper->GetLastBricks() << ", texture bytes "
            << mapper->GetLastTextureBytes() << ", estimated error "
            << mapper->GetLastEstimatedError() << "; RGB RMSE against vtkGPUVolumeRayCastMapper "
            << rmse << " (threshold 0.03), signal " << Signal(b) << "\n";
  check.Check(Signal(b) > 0.02, "the reference shows the volume");
  check.Check(rmse < 0.03, "within 0.03 of vtkGPUVolumeRayCastMapper");
  check.Check(mapper->GetLastEstimatedError() == 0.0,
    "the budget holds everything: estimated error 0, not " +
      std::to_string(mapper->GetLastEstimatedError()));
  if (withActor)
  {
    // The pixel at the sphere's projected centre shows the lit sphere (its
    // front hemisphere lies in front of the volume it intersects): the
    // volume in front of it is thin, so it stays mostly green.
    double display[3];
    ours.Renderer->SetWorldPoint(10.0, 8.0, 12.0, 1.0);
    ours.Renderer->WorldToDisplay();
    ours.Renderer->GetDisplayPoint(display);
    const std::size_t p =
      3 * (static_cast<std::size_t>(display[0]) + Size * static_cast<std::size_t>(display[1]));
    std::cout << "pixel at the sphere's centre: " << a[p] << " " << a[p + 1] << " " << a[p + 2]
              << " (reference " << b[p] << " " << b[p + 1] << " " << b[p + 2] << ")\n";
    check.Check(a[p + 1] > a[p] && a[p + 1] > a[p + 2], "the sphere shows at its centre");
    check.Check(std::fabs(a[p + 1] - b[p + 1]) < 0.05, "and as in the reference");
  }
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  return check.Result();
}

int Matrix()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> plainMapper;
  vtkNew<vtkHybridOctreeVolumeMapper> movedMapper;
  Scene plain(plainMapper);
  Scene moved(movedMapper);
  for (vtkHybridOctreeVolumeMapper* m : { plainMapper.Get(), movedMapper.Get() })
  {
    m->SetLeafSize(8);
    m->SetBudgetMB(0.12);
    m->UseRoiOn();
    m->SetRoiRadius(10.0);
  }
  plainMapper->SetRoiCenter(16.0, 16.0, 16.0);
  vtkNew<vtkTransform> transform;
  transform->Translate(40.0, -25.0, 10.0);
  transform->RotateWXYZ(35.0, 1.0, 2.0, 0.5);
  moved.Volume->SetUserTransform(transform);
  // The camera moved by the same transform sees the same picture.
  vtkCamera* a = plain.Renderer->GetActiveCamera();
  vtkCamera* b = moved.Renderer->GetActiveCamera();
  double p[3], f[3], up[3];
  transform->TransformPoint(a->GetPosition(), p);
  transform->TransformPoint(a->GetFocalPoint(), f);
  transform->TransformVector(a->GetViewUp(), up);
  b->SetPosition(p);
  b->SetFocalPoint(f);
  b->SetViewUp(up);
  double roi[3];
  transform->TransformPoint(plainMapper->GetRoiCenter(), roi);
  movedMapper->SetRoiCenter(roi); // in world coordinates: moved with the volume
  moved.Renderer->ResetCameraClippingRange();
  plain.Window->Render();
  moved.Window->Render();
  check.Check(plainMapper->GetLastRenderOK() && movedMapper->GetLastRenderOK(), "both drew");
  const double rmse = Rmse(Grab(plain.Window), Grab(moved.Window));
  std::cout << "RGB RMSE moved vs plain " << rmse << " (threshold 0.01), bricks "
            << plainMapper->GetLastBricks() << " and " << movedMapper->GetLastBricks() << "\n";
  check.Check(rmse < 0.01, "the moved volume seen by the moved camera looks the same");
  check.Check(plainMapper->GetLastBricks() > 8 &&
      plainMapper->GetLastBricks() == movedMapper->GetLastBricks(),
    "the same many bricks (the region of interest moved with the volume)");
  check.Check(Signal(Grab(plain.Window)) > 0.02, "the volume shows");
  return check.Result();
}
} // namespace

int TestHybridOctreeVolumeMapper(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "cpu_match";
  if (scenario == "cpu_match" || scenario == "multisample" || scenario == "tiny_opacity" ||
    scenario == "inside" || scenario == "opaque_surface" || scenario == "translucent_surface" ||
    scenario == "points_square" || scenario == "points_gaussian" || scenario == "points_surface" ||
    scenario == "nan_hole" || scenario == "shaded" || scenario == "cropped" ||
    scenario == "gradient_opacity" || scenario == "gradient_opacity_shaded" ||
    (BlendOf(scenario) > 0 && scenario.rfind("gpu_", 0) != 0))
  {
    return CpuMatch(scenario);
  }
  if (BlendOf(scenario) >= 0 && scenario.rfind("gpu_", 0) == 0)
  {
    return GpuBlend(scenario);
  }
  if (scenario == "gpu_gradient_opacity")
  {
    return GpuGradientOpacity();
  }
  if (scenario == "gpu_shaded" || scenario == "gpu_light_kit")
  {
    return GpuShaded(scenario == "gpu_light_kit");
  }
  if (scenario == "gpu_cropped" || scenario == "gpu_cropped_moved")
  {
    return GpuCropped(scenario == "gpu_cropped_moved");
  }
  if (scenario == "gpu_reference" || scenario == "actor")
  {
    return GpuReference(scenario == "actor");
  }
  if (scenario == "matrix")
  {
    return Matrix();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
