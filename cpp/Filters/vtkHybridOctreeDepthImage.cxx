#include "vtkHybridOctreeDepthImage.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeFieldData.h"
#include "vtkHybridOctreeImageInput.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <string>

vtkStandardNewMacro(vtkHybridOctreeDepthImage);

vtkHybridOctreeDepthImage::vtkHybridOctreeDepthImage()
{
  // The point scalars by default (ParaView's 'Scalars' property).
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkHybridOctreeDepthImage::~vtkHybridOctreeDepthImage() = default;

int vtkHybridOctreeDepthImage::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkHybridOctreeDepthImage::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The output is the picture, whatever the input's extent.
  vtkInformation* out = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, this->ImageSize - 1, 0, this->ImageSize - 1, 0, 0 };
  out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  out->Set(vtkDataObject::SPACING(), spacing, 3);
  out->Set(vtkDataObject::ORIGIN(), origin, 3);
  return 1;
}

int vtkHybridOctreeDepthImage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkHybridOctreeImageInput::RequestWholeExtent(inputVector);
  return 1;
}

int vtkHybridOctreeDepthImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("the output is not vtkImageData");
    return 0;
  }
  output->Initialize();
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* chosen =
    input ? this->GetInputArrayToProcess(0, inputVector, association) : nullptr;
  std::string error;
  vtkDataArray* scalars =
    vtkHybridOctreeImageInput::CheckPointScalars(input, chosen, association, error);
  if (!scalars)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkHybridOctreeBridge::FtbOptions options;
  options.Isovalue = this->Isovalue;
  options.UseLabel = this->UseLabel != 0;
  options.Label = this->Label;
  for (int a = 0; a < 3; ++a)
  {
    options.Vpn[a] = this->ViewPlaneNormal[a];
  }
  options.ImageSize = static_cast<std::size_t>(this->ImageSize);
  options.BackToFront = this->Method == BACK_TO_FRONT;
  // The core draws into the output arrays, rows from the bottom (VTK's order).
  const vtkIdType n = this->ImageSize;
  vtkNew<vtkFloatArray> depth;
  depth->SetName("depth");
  depth->SetNumberOfTuples(n * n);
  vtkNew<vtkUnsignedCharArray> face;
  face->SetName("face");
  face->SetNumberOfTuples(n * n);
  vtkNew<vtkUnsignedCharArray> shaded;
  shaded->SetName("shaded");
  shaded->SetNumberOfComponents(3);
  shaded->SetNumberOfTuples(n * n);
  vtkHybridOctreeBridge::FtbImageBuffers image;
  image.Depth = depth->GetPointer(0);
  image.Face = face->GetPointer(0);
  image.Shaded = shaded->GetPointer(0);
  vtkHybridOctreeBridge::FtbResult result;
  if (!vtkHybridOctreeBridge::FtbDisplay(vtkHybridOctreeImageInput::Bytes(scalars),
        vtkHybridOctreeImageInput::ByteCount(scalars),
        vtkHybridOctreeImageInput::DescribeGrid(input, scalars, this->Component), options, image,
        result, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  output->SetExtent(0, static_cast<int>(n) - 1, 0, static_cast<int>(n) - 1, 0, 0);
  output->SetSpacing(1.0, 1.0, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  output->GetPointData()->SetScalars(depth);
  output->GetPointData()->AddArray(face);
  output->GetPointData()->AddArray(shaded);

  vtkFieldData* fd = output->GetFieldData();
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "white_visited", result.WhiteVisited);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "black_visited", result.BlackVisited);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "gray_visited", result.GrayVisited);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "faces", result.Faces);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "scanlines", result.Scanlines);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "pixels", result.Pixels);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "display_ms", result.DisplayMs);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "build_ms", result.BuildMs);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "bitmap_bytes", result.BitmapBytes);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "white_octants", result.WhiteOctants);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "black_octants", result.BlackOctants);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "gray_octants", result.GrayOctants);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fd, "resolution", result.Resolution);
  vtkNew<vtkStringArray> viewCase;
  viewCase->SetName("view_case");
  viewCase->InsertNextValue(result.ViewCase);
  fd->AddArray(viewCase);
  vtkNew<vtkStringArray> method;
  method->SetName("method");
  method->InsertNextValue(this->Method == BACK_TO_FRONT ? "back-to-front" : "front-to-back");
  fd->AddArray(method);
  return 1;
}

void vtkHybridOctreeDepthImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Isovalue: " << this->Isovalue << "\n";
  os << indent << "UseLabel: " << this->UseLabel << "\n";
  os << indent << "Label: " << this->Label << "\n";
  os << indent << "ViewPlaneNormal: " << this->ViewPlaneNormal[0] << ", "
     << this->ViewPlaneNormal[1] << ", " << this->ViewPlaneNormal[2] << "\n";
  os << indent << "ImageSize: " << this->ImageSize << "\n";
  os << indent << "Method: " << (this->Method == BACK_TO_FRONT ? "BackToFront" : "FrontToBack")
     << "\n";
  os << indent << "Component: " << this->Component << "\n";
}
