#include "vtkPVHybridOctreeRepresentation.h"

#include "vtkAlgorithm.h"
#include "vtkColorTransferFunction.h"
#include "vtkHybridOctreeVolumeMapper.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkScalarsToColors.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkPVHybridOctreeRepresentation);

vtkPVHybridOctreeRepresentation::vtkPVHybridOctreeRepresentation()
{
  // The base class made its vtkMultiBlockVolumeMapper; the actor gets the
  // mapper in UpdateMapperParameters().
  this->VolumeMapper = vtkSmartPointer<vtkHybridOctreeVolumeMapper>::New();
}

vtkPVHybridOctreeRepresentation::~vtkPVHybridOctreeRepresentation() = default;

vtkHybridOctreeVolumeMapper* vtkPVHybridOctreeRepresentation::Mapper() const
{
  return static_cast<vtkHybridOctreeVolumeMapper*>(this->VolumeMapper.GetPointer());
}

vtkHybridOctreeVolumeMapper* vtkPVHybridOctreeRepresentation::GetHybridOctreeMapper()
{
  return this->Mapper();
}

int vtkPVHybridOctreeRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

void vtkPVHybridOctreeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  // A multi-component array: the component the colour map shows
  // (vtkScalarsToColors::COMPONENT); magnitude is not drawn (the mapper
  // then says to choose a component).
  vtkColorTransferFunction* ctf = this->Property->GetRGBTransferFunction(0);
  const bool component = ctf && ctf->GetVectorMode() == vtkScalarsToColors::COMPONENT;
  this->Mapper()->SetComponent(component ? ctf->GetVectorComponent() : -1);
  // The 2D transfer function's y axis is the gradient magnitude; a second
  // array as y axis (UseGradientForTransfer2D off) is not drawn.
  const bool secondArray =
    this->UseTransfer2D && !this->UseGradientForTransfer2D && !this->ColorArray2Name.empty();
  if (secondArray && !this->WarnedTransfer2DArray)
  {
    vtkWarningMacro("the 2D transfer function's y axis from a second array ('"
      << this->ColorArray2Name
      << "', Use Gradient For Transfer 2D off) is not implemented: Hybrid Octree Volume reads "
         "the y axis as the gradient magnitude; turn Use Gradient For Transfer 2D on, or use "
         "the Volume representation");
  }
  this->WarnedTransfer2DArray = secondArray;
}

// ---- Forwarded settings -------------------------------------------------------

void vtkPVHybridOctreeRepresentation::SetBudgetMB(double mb)
{
  this->Mapper()->SetBudgetMB(mb);
}

void vtkPVHybridOctreeRepresentation::SetTexelFormat(int format)
{
  this->Mapper()->SetTexelFormat(format);
}

void vtkPVHybridOctreeRepresentation::SetInteractiveBudgetMB(double mb)
{
  this->Mapper()->SetInteractiveBudgetMB(mb);
}

void vtkPVHybridOctreeRepresentation::SetTargetFrameMilliseconds(double ms)
{
  this->Mapper()->SetTargetFrameMilliseconds(ms);
}

void vtkPVHybridOctreeRepresentation::SetErrorTolerance(double tolerance)
{
  this->Mapper()->SetErrorTolerance(tolerance);
}

void vtkPVHybridOctreeRepresentation::SetViewSelection(int mode)
{
  this->Mapper()->SetViewSelection(mode);
}

void vtkPVHybridOctreeRepresentation::SetMinTexelPixels(double pixels)
{
  this->Mapper()->SetMinTexelPixels(pixels);
}

void vtkPVHybridOctreeRepresentation::SetViewChangeDegrees(double degrees)
{
  this->Mapper()->SetViewChangeDegrees(degrees);
}

void vtkPVHybridOctreeRepresentation::SetAsynchronousLoading(bool on)
{
  this->Mapper()->SetAsynchronousLoading(on);
}

void vtkPVHybridOctreeRepresentation::SetLoadingMemoryMB(double mb)
{
  this->Mapper()->SetLoadingMemoryMB(mb);
}

void vtkPVHybridOctreeRepresentation::SetUseRoi(bool use)
{
  this->Mapper()->SetUseRoi(use);
}

void vtkPVHybridOctreeRepresentation::SetRoiCenter(double x, double y, double z)
{
  this->Mapper()->SetRoiCenter(x, y, z);
}

void vtkPVHybridOctreeRepresentation::SetRoiRadius(double radius)
{
  this->Mapper()->SetRoiRadius(radius);
}

void vtkPVHybridOctreeRepresentation::SetShowSurface(bool show)
{
  this->Mapper()->SetShowSurface(show);
}

void vtkPVHybridOctreeRepresentation::SetIsovalue(double value)
{
  this->Mapper()->SetIsovalue(value);
}

void vtkPVHybridOctreeRepresentation::SetSurfaceColor(double r, double g, double b)
{
  this->Mapper()->SetSurfaceColor(r, g, b);
}

void vtkPVHybridOctreeRepresentation::SetSurfaceOpacity(double opacity)
{
  this->Mapper()->SetSurfaceOpacity(opacity);
}

void vtkPVHybridOctreeRepresentation::SetLeafSize(int cells)
{
  this->Mapper()->SetLeafSize(cells);
}

void vtkPVHybridOctreeRepresentation::SetUsePoints(bool use)
{
  this->Mapper()->SetUsePoints(use);
}

void vtkPVHybridOctreeRepresentation::SetPointFactor(int factor)
{
  this->Mapper()->SetPointFactor(factor);
}

void vtkPVHybridOctreeRepresentation::SetPointThreshold(double threshold)
{
  this->Mapper()->SetPointThreshold(threshold);
}

void vtkPVHybridOctreeRepresentation::SetPointBudget(int points)
{
  this->Mapper()->SetPointBudget(points);
}

void vtkPVHybridOctreeRepresentation::SetPointFootprint(int footprint)
{
  this->Mapper()->SetPointFootprint(footprint);
}

void vtkPVHybridOctreeRepresentation::SetGlobalIlluminationReach(float reach)
{
  this->Mapper()->SetGlobalIlluminationReach(reach);
  this->Modified();
}

void vtkPVHybridOctreeRepresentation::SetVolumetricScatteringBlending(float blending)
{
  this->Mapper()->SetVolumetricScatteringBlending(blending);
  this->Modified();
}

// ---- Statistics -----------------------------------------------------------------

int vtkPVHybridOctreeRepresentation::GetLastBricks()
{
  return this->Mapper()->GetLastBricks();
}

int vtkPVHybridOctreeRepresentation::GetLastBrickDraws()
{
  return static_cast<int>(this->Mapper()->GetLastBrickDraws());
}

double vtkPVHybridOctreeRepresentation::GetLastTextureMB()
{
  return static_cast<double>(this->Mapper()->GetLastTextureBytes()) / 1.0e6;
}

const char* vtkPVHybridOctreeRepresentation::GetLastPlan()
{
  this->LastPlan = this->Mapper()->GetLastPlan();
  return this->LastPlan.c_str();
}

const char* vtkPVHybridOctreeRepresentation::GetLastEffects()
{
  this->LastEffects = this->Mapper()->GetLastEffects();
  return this->LastEffects.c_str();
}

double vtkPVHybridOctreeRepresentation::GetLastFrameMilliseconds()
{
  return this->Mapper()->GetLastFrameMilliseconds();
}

int vtkPVHybridOctreeRepresentation::GetLastPoints()
{
  return static_cast<int>(std::min<vtkTypeInt64>(this->Mapper()->GetLastPoints(), VTK_INT_MAX));
}

double vtkPVHybridOctreeRepresentation::GetLastUploadedMB()
{
  return static_cast<double>(this->Mapper()->GetLastUploadedBytes()) / 1.0e6;
}

int vtkPVHybridOctreeRepresentation::GetLastBricksLoading()
{
  return this->Mapper()->GetLastBricksLoading();
}

double vtkPVHybridOctreeRepresentation::GetLastStoreMBRead()
{
  return static_cast<double>(this->Mapper()->GetLastStoreBytesRead()) / 1.0e6;
}

double vtkPVHybridOctreeRepresentation::GetLastSelectMilliseconds()
{
  return this->Mapper()->GetLastSelectMilliseconds();
}

int vtkPVHybridOctreeRepresentation::GetLastReselected()
{
  return this->Mapper()->GetLastReselected() ? 1 : 0;
}

const char* vtkPVHybridOctreeRepresentation::GetLastViewSelection()
{
  this->LastViewSelection = this->Mapper()->GetLastViewSelection();
  return this->LastViewSelection.c_str();
}

double vtkPVHybridOctreeRepresentation::GetLastTargetMilliseconds()
{
  return this->Mapper()->GetLastTargetMilliseconds();
}

double vtkPVHybridOctreeRepresentation::GetLastDrawTargetMilliseconds()
{
  return this->Mapper()->GetLastDrawTargetMilliseconds();
}

double vtkPVHybridOctreeRepresentation::GetLastPredictedMilliseconds()
{
  return this->Mapper()->GetLastPredictedMilliseconds();
}

double vtkPVHybridOctreeRepresentation::GetLastDrawMilliseconds()
{
  return this->Mapper()->GetLastDrawMilliseconds();
}

const char* vtkPVHybridOctreeRepresentation::GetLastTimeOutcome()
{
  this->LastTimeOutcome = this->Mapper()->GetLastTimeOutcome();
  return this->LastTimeOutcome.c_str();
}

double vtkPVHybridOctreeRepresentation::GetLastEstimatedRMSError()
{
  return this->Mapper()->GetLastEstimatedRMSError();
}

double* vtkPVHybridOctreeRepresentation::GetTextureBudgetRangeMB()
{
  const int* e = this->WholeExtent;
  if (e[1] < e[0] || e[3] < e[2] || e[5] < e[4])
  {
    return this->TextureBudgetRangeMB; // no input yet
  }
  const double leaf = std::max(this->Mapper()->GetLeafSize(), 1);
  double texels = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const double cells = std::max(e[2 * a + 1] - e[2 * a], 1);
    texels *= cells + std::ceil(cells / leaf);
  }
  this->TextureBudgetRangeMB[1] = std::max(4.0 * texels / 1.0e6, this->TextureBudgetRangeMB[0]);
  return this->TextureBudgetRangeMB;
}

double vtkPVHybridOctreeRepresentation::GetLastEstimatedError()
{
  return this->Mapper()->GetLastEstimatedError();
}

void vtkPVHybridOctreeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "HybridOctreeMapper:\n";
  this->Mapper()->PrintSelf(os, indent.GetNextIndent());
}
