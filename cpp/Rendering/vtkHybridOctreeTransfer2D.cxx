#include "vtkHybridOctreeTransfer2D.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"

#include <algorithm>

namespace
{
/// The largest side read (src/transfer/transfer2d.rs's MAX_SIDE).
constexpr int MaxSide = 4096;
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
  const bool sized = dims[0] >= 1 && dims[1] >= 1 && dims[2] == 1 && dims[0] <= MaxSide &&
    dims[1] <= MaxSide;
  return sized && scalars && scalars->GetNumberOfComponents() == 4 &&
      scalars->GetNumberOfTuples() == static_cast<vtkIdType>(dims[0]) * dims[1]
    ? image
    : nullptr;
}

bool vtkHybridOctreeTransfer2D::Update(
  vtkVolumeProperty* property, vtkDataArray* scalars, int component)
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
  const bool current = this->ReadFrom == image && this->Width != 0 &&
    this->ReadTime > image->GetMTime() && this->ReadTime > texels->GetMTime() &&
    range[0] == this->Range[0] && range[1] == this->Range[1];
  if (current)
  {
    return true;
  }
  int dims[3];
  image->GetDimensions(dims);
  this->Width = static_cast<std::size_t>(dims[0]);
  this->Height = static_cast<std::size_t>(dims[1]);
  this->RGBA.resize(4 * this->Width * this->Height);
  for (vtkIdType t = 0; t < texels->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < 4; ++c)
    {
      // Clamped to [0, 1] (NaN stays, and the selection refuses it with its texel).
      const double v = texels->GetComponent(t, c);
      this->RGBA[4 * t + c] = static_cast<float>(v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v));
    }
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
  this->ReadFrom = image;
  this->ReadTime.Modified();
  this->Uploaded = false;
  return true;
}

void vtkHybridOctreeTransfer2D::Describe(
  std::size_t size[2], std::vector<float>& rgba, double range[2]) const
{
  size[0] = this->Width;
  size[1] = this->Height;
  rgba = this->RGBA;
  range[0] = this->Range[0];
  range[1] = this->Range[1];
  if (this->Empty())
  {
    rgba.clear();
  }
}

std::vector<double> vtkHybridOctreeTransfer2D::Key() const
{
  return { static_cast<double>(this->Width), static_cast<double>(this->Height), this->Range[0],
    this->Range[1], this->Empty() ? 0.0 : static_cast<double>(this->ReadTime.GetMTime()) };
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
