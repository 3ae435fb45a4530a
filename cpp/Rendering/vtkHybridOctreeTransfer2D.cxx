#include "vtkHybridOctreeTransfer2D.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageResize.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

namespace
{
/// The largest side read (src/transfer/transfer2d.rs's MAX_SIDE).
constexpr int MaxSide = 4096;

/// The side of VTK's texture for a table side of `n` texels
/// (vtkOpenGLVolumeLookupTable::GetMaximumSupportedTextureWidth): the next
/// power of two, at least 1024 (at most MaxSide here, below every GL limit).
int VtkTextureSide(int n)
{
  int side = 1;
  while (side < n)
  {
    side *= 2;
  }
  return std::max(1024, side);
}
}

vtkImageData* vtkHybridOctreeTransfer2D::Usable(vtkVolumeProperty* property)
{
  if (!property || property->GetTransferFunctionMode() != vtkVolumeProperty::TF_2D)
  {
    return nullptr;
  }
  vtkImageData* image = property->GetTransferFunction2D(0);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  const bool sized =
    dims[0] >= 1 && dims[1] >= 1 && dims[2] == 1 && dims[0] <= MaxSide && dims[1] <= MaxSide;
  return sized && scalars && scalars->GetNumberOfComponents() == 4 &&
      scalars->GetNumberOfTuples() == static_cast<vtkIdType>(dims[0]) * dims[1]
    ? image
    : nullptr;
}

double vtkHybridOctreeTransfer2D::SmartSampleDistance(
  const double spacing[3], const std::size_t dims[3])
{
  double d = (spacing[0] + spacing[1] + spacing[2]) / 6.0;
  const double cells = static_cast<double>(dims[0] > 0 ? dims[0] - 1 : 0) *
    static_cast<double>(dims[1] > 0 ? dims[1] - 1 : 0) *
    static_cast<double>(dims[2] > 0 ? dims[2] - 1 : 0);
  const double n = std::pow(cells, 0.333);
  if (n < 100.0)
  {
    d *= 0.01 + (1.0 - 0.01) * n / 100.0;
  }
  return d;
}

bool vtkHybridOctreeTransfer2D::Update(vtkVolumeProperty* property, vtkDataArray* scalars,
  int component, const double spacing[3], const std::size_t dims[3], double sampleDistance)
{
  vtkImageData* image = Usable(property);
  if (!image || !scalars)
  {
    this->Width = this->Height = 0;
    this->ReadFrom = nullptr;
    return false;
  }
  vtkDataArray* texels = image->GetPointData()->GetScalars();
  double range[2];
  scalars->GetFiniteRange(range, component < 0 ? 0 : component);
  const double lo = std::min({ spacing[0], spacing[1], spacing[2] });
  const double hi = std::max({ spacing[0], spacing[1], spacing[2] });
  const double d0 = std::max(lo, hi / 16.0);
  const double d = sampleDistance > 0.0 ? sampleDistance : SmartSampleDistance(spacing, dims);
  const double exponent = d > 0.0 ? d0 / d : 1.0;
  const bool current = this->ReadFrom == image && this->Width != 0 && exponent == this->Exponent &&
    this->ReadTime > image->GetMTime() && this->ReadTime > texels->GetMTime() &&
    range[0] == this->Range[0] && range[1] == this->Range[1];
  if (current)
  {
    return true;
  }
  int imageDims[3];
  image->GetDimensions(imageDims);
  // VTK draws the table resized to its texture's size (vtkOpenGLVolumeTransferFunction2D:
  // vtkImageResize's defaults, a 5-lobe Lanczos with the corner texels' centres kept), read
  // as a linear texture: the same texels here, so that a table of ParaView's default 10 x 10
  // reads the values VTK reads at every scalar and gradient magnitude.
  const int width = VtkTextureSide(imageDims[0]);
  const int height = imageDims[1] > 1 ? VtkTextureSide(imageDims[1]) : 1;
  vtkNew<vtkImageResize> resize;
  if (width != imageDims[0] || height != imageDims[1])
  {
    resize->SetInputData(image);
    resize->SetResizeMethodToOutputDimensions();
    resize->SetOutputDimensions(width, height, 1);
    resize->Update();
    texels = resize->GetOutput()->GetPointData()->GetScalars();
  }
  this->Width = static_cast<std::size_t>(width);
  this->Height = static_cast<std::size_t>(height);
  this->RGBA.resize(4 * this->Width * this->Height);
  for (vtkIdType t = 0; t < texels->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < 4; ++c)
    {
      // Clamped to [0, 1] (NaN stays, and the selection refuses it with its texel).
      const double v = texels->GetComponent(t, c);
      this->RGBA[4 * t + c] = static_cast<float>(v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v));
    }
    float& a = this->RGBA[4 * t + 3];
    a = a < 1.0f ? static_cast<float>(1.0 - std::pow(1.0 - a, exponent)) : a;
  }
  this->Columns.assign(4 * this->Width, 0.0f);
  for (std::size_t j = 0; j < this->Height; ++j)
  {
    for (std::size_t i = 0; i < this->Width; ++i)
    {
      float& a = this->Columns[4 * i + 3];
      a = std::max(a, this->RGBA[4 * (i + j * this->Width) + 3]);
    }
  }
  this->Range[0] = range[0];
  this->Range[1] = range[1];
  this->Exponent = exponent;
  this->ReadFrom = image;
  this->ReadTime.Modified();
  this->Uploaded = false;
  return true;
}

void vtkHybridOctreeTransfer2D::Describe(
  std::size_t size[2], std::vector<float>* rgba, double range[2]) const
{
  size[0] = this->Width;
  size[1] = this->Height;
  range[0] = this->Range[0];
  range[1] = this->Range[1];
  if (rgba)
  {
    *rgba = this->Empty() ? std::vector<float>() : this->RGBA;
  }
}

std::vector<double> vtkHybridOctreeTransfer2D::Key() const
{
  return { static_cast<double>(this->Width), static_cast<double>(this->Height), this->Range[0],
    this->Range[1], this->Exponent,
    this->Empty() ? 0.0 : static_cast<double>(this->ReadTime.GetMTime()) };
}

const std::vector<float>& vtkHybridOctreeTransfer2D::ColumnTable(double& lo, double& hi) const
{
  // Column i's centre: lo + (i + 1/2) (hi - lo) / width (a range of 0 spans 1e-6, as VTK's).
  const double span = this->Range[1] > this->Range[0] ? this->Range[1] - this->Range[0] : 1.0e-6;
  const double w = static_cast<double>(this->Width);
  lo = this->Range[0] + 0.5 * span / w;
  hi = this->Range[0] + (w - 0.5) * span / w;
  return this->Columns;
}

vtkTextureObject* vtkHybridOctreeTransfer2D::Activate(
  vtkOpenGLRenderWindow* window, std::string& error)
{
  if (this->Empty())
  {
    error = "no 2D transfer function to activate";
    return nullptr;
  }
  if (!this->Texture)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
    this->Uploaded = false;
  }
  if (!this->Uploaded || this->Texture->GetContext() != window)
  {
    this->Texture->SetContext(window);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
    this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!this->Texture->Create2DFromRaw(static_cast<unsigned int>(this->Width),
          static_cast<unsigned int>(this->Height), 4, VTK_FLOAT, this->RGBA.data()))
    {
      error = "OpenGL could not create the 2D transfer function's texture (" +
        std::to_string(this->Width) + " x " + std::to_string(this->Height) + ")";
      return nullptr;
    }
    this->Uploaded = true;
  }
  this->Texture->Activate();
  return this->Texture;
}

void vtkHybridOctreeTransfer2D::Deactivate()
{
  if (this->Texture && this->Texture->GetContext())
  {
    this->Texture->Deactivate();
  }
}

void vtkHybridOctreeTransfer2D::ReleaseGraphicsResources()
{
  if (this->Texture && this->Texture->GetContext())
  {
    this->Texture->ReleaseGraphicsResources(this->Texture->GetContext());
  }
  this->Texture = nullptr;
  this->Uploaded = false;
}
