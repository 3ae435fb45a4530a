/**
 * @file   HybridOctreeMapperScene.h
 * @brief  The scene the vtkHybridOctreeVolumeMapper tests draw, and image metrics.
 *
 * A 65^3 wavelet (vtkRTAnalyticSource) in a 256x256 window over a fixed
 * background, a colour map over its range and an opacity that is 0 below the
 * middle of the range (so the selection skips transparent nodes and draws
 * many bricks of several strides), a perspective camera off the axes.
 */
#ifndef HybridOctreeMapperScene_h
#define HybridOctreeMapperScene_h

#include "HybridOctreeTestUtilities.h"
#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace MapperScene
{
constexpr int Size = 256;
const double Background[3] = { 0.32, 0.34, 0.43 };

/// RGB of a window (rows from the bottom), 0..1, drawn again (`rerender`)
/// or, for a window that does not swap its buffers (SwapBuffersOff), as its
/// last Render() left it.
inline std::vector<double> Grab(vtkRenderWindow* window, bool rerender = true)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetShouldRerender(rerender);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkUnsignedCharArray* pixels =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  std::vector<double> rgb;
  if (pixels)
  {
    rgb.resize(static_cast<std::size_t>(pixels->GetNumberOfValues()));
    for (vtkIdType i = 0; i < pixels->GetNumberOfValues(); ++i)
    {
      rgb[static_cast<std::size_t>(i)] = pixels->GetValue(i) / 255.0;
    }
  }
  return rgb;
}

/// The CPU compositor's premultiplied RGBA (rows from the top) over the background, as Grab().
inline std::vector<double> OverBackground(vtkFloatArray* rgba, int size)
{
  std::vector<double> rgb(3 * static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const float* p = rgba->GetPointer(4 * (x + size * (size - 1 - y)));
      for (int c = 0; c < 3; ++c)
      {
        rgb[3 * (x + size * y) + c] = p[c] + (1.0 - p[3]) * Background[c];
      }
    }
  }
  return rgb;
}

/// Root mean square of the channel differences (0 when the sizes differ: check sizes first).
inline double Rmse(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return 1.0;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

/// Mean |value - background| over the channels: how much the volume shows.
inline double Signal(const std::vector<double>& rgb)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < rgb.size(); ++i)
  {
    sum += std::fabs(rgb[i] - Background[i % 3]);
  }
  return rgb.empty() ? 0.0 : sum / static_cast<double>(rgb.size());
}

/// VTK's GPU ray caster as the mapper tests' reference: rays sampled every
/// spacing (1), no automatic adjustment, no jittering.
inline vtkNew<vtkGPUVolumeRayCastMapper> MakeReference()
{
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->AutoAdjustSampleDistancesOff();
  gpu->SetSampleDistance(1.0);
  gpu->SetUseJittering(0);
  return gpu;
}

/// A window, renderer and volume around any volume mapper: linear
/// interpolation, no shading, the camera looking at the origin from
/// `position` with a 30 degree view angle.
struct Stage
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;

  void Build(vtkVolumeMapper* mapper, vtkColorTransferFunction* color,
    vtkPiecewiseFunction* opacity, const double position[3])
  {
    this->Window->SetSize(Size, Size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(Background[0], Background[1], Background[2]);
    this->Property->SetColor(color);
    this->Property->SetScalarOpacity(opacity);
    this->Property->SetInterpolationTypeToLinear();
    this->Property->ShadeOff();
    this->Volume->SetMapper(mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(position[0], position[1], position[2]);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetViewAngle(30.0);
    this->Renderer->ResetCameraClippingRange();
  }
};

/// The wavelet (vtkRTAnalyticSource, `half` samples either side of the
/// origin) on a Stage: blue-yellow-red colours, transparent below mid-range.
struct Scene : Stage
{
  vtkNew<vtkRTAnalyticSource> Wavelet;
  double Range[2] = { 0.0, 1.0 };

  explicit Scene(vtkVolumeMapper* mapper, int half = 32)
  {
    this->Wavelet->SetWholeExtent(-half, half, -half, half, -half, half);
    this->Wavelet->Update();
    this->Wavelet->GetOutput()->GetPointData()->GetScalars()->GetRange(this->Range);
    mapper->SetInputConnection(this->Wavelet->GetOutputPort());
    const double lo = this->Range[0], hi = this->Range[1], mid = 0.5 * (lo + hi);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(lo, 0.1, 0.2, 0.9);
    color->AddRGBPoint(mid, 0.9, 0.9, 0.2);
    color->AddRGBPoint(hi, 0.9, 0.1, 0.1);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(lo, 0.0);
    opacity->AddPoint(mid, 0.0);
    opacity->AddPoint(mid + 0.2 * (hi - mid), 0.05);
    opacity->AddPoint(hi, 0.4);
    const double position[3] = { 95.0, 75.0, 130.0 };
    this->Build(mapper, color, opacity, position);
  }
};

/// The OME-Zarr tests' scene on `stage`: `mapper` (input set) drawing the
/// phantom of a store of the CLI's (values 0..1) in blue-yellow-red, the
/// low values transparent, seen from (120, 80, 160) off the volume's `centre`.
inline void BuildStoreStage(Stage& stage, vtkVolumeMapper* mapper, const double centre[3])
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
  color->AddRGBPoint(0.5, 0.9, 0.9, 0.2);
  color->AddRGBPoint(1.0, 0.9, 0.1, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.15, 0.0);
  opacity->AddPoint(0.3, 0.08);
  opacity->AddPoint(1.0, 0.5);
  const double position[3] = { centre[0] + 120.0, centre[1] + 80.0, centre[2] + 160.0 };
  stage.Build(mapper, color, opacity, position);
  stage.Renderer->GetActiveCamera()->SetFocalPoint(centre[0], centre[1], centre[2]);
  stage.Renderer->ResetCameraClippingRange();
}

/// True when OpenGL has no error pending (and clears it).
inline bool NoGLError(vtkRenderWindow* window)
{
  window->MakeCurrent();
  bool clean = true;
  while (glGetError() != GL_NO_ERROR)
  {
    clean = false;
  }
  return clean;
}

/// The CPU compositor's picture (CompositeOnCPU) of the mapper's last frame
/// of `stage`, over the background; checked to run.
inline std::vector<double> CpuPicture(
  Checker& check, Stage& stage, vtkHybridOctreeVolumeMapper* mapper, ErrorRecorder* errors)
{
  vtkNew<vtkFloatArray> cpu;
  check.Check(mapper->CompositeOnCPU(stage.Renderer, stage.Volume, Size, Size, cpu),
    "the CPU compositor ran:\n" + errors->AllErrors());
  return OverBackground(cpu, Size);
}

/// Renders `stage` and checks the mapper's picture against the CPU
/// compositor's on the same DrawList: RGB RMSE below `threshold`, a scene
/// that shows something, no OpenGL error; prints the frame's statistics.
inline void CompareWithCpu(Checker& check, Stage& stage, vtkHybridOctreeVolumeMapper* mapper,
  double threshold, ErrorRecorder* errors)
{
  stage.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  const std::vector<double> gl = Grab(stage.Window);
  const std::vector<double> reference = CpuPicture(check, stage, mapper, errors);
  const double rmse = Rmse(gl, reference);
  std::cout << "bricks " << mapper->GetLastBricks() << ", slices " << mapper->GetLastSlices()
            << ", surface triangles " << mapper->GetLastSurfaceTriangles() << ", plan '"
            << mapper->GetLastPlan() << "', effects '" << mapper->GetLastEffects()
            << "', texture bytes " << mapper->GetLastTextureBytes() << ", estimated error "
            << mapper->GetLastEstimatedError() << "\n"
            << "RGB RMSE GL vs CPU compositor " << rmse << " (threshold " << threshold
            << "), signal " << Signal(reference) << "\n";
  check.Check(Signal(reference) > 0.005, "the scene shows something");
  check.Check(rmse < threshold, "GL picture within the threshold of the CPU compositor");
  check.Check(NoGLError(stage.Window), "no OpenGL error left behind");
}
} // namespace MapperScene

#endif
