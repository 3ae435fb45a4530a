/**
 * @class   vtkHybridOctreePoints
 * @brief   The points of the hybrid point/volume representation: where a
 *          low-resolution copy of the image is wrong, as vtkPolyData.
 *
 * Paper 3 (Wilson, Ma, McCormick, "A hybrid method for interactive volume
 * rendering"): the input image kept every Factor-th sample (2, 4 or 8) and
 * reconstructed trilinearly is wrong by e = f - T_f at each sample; a point
 * goes where |e| exceeds Threshold (a fraction of the data range), or at the
 * PointBudget largest errors. UnderestimatesOnly keeps only e > 0 (the
 * errors an additive point can correct); MaxOverestimate (>= 0) lowers the
 * low resolution so it overestimates by at most that fraction (the paper's
 * optimized representation). With FileName set, the points are also written
 * as a HOPOINTS file (6 bytes a point up to 256^3), which the command line
 * tool reads.
 *
 * Output: one vertex per point at its sample's position, with point arrays
 * "value" (the original value, active scalars), "error" and "Normals" (the
 * quantised gradient direction, as stored). Field data: "points",
 * "point_bytes", "underestimates", "factor", "generate_ms",
 * "low_resolution_bytes" (4-byte texels of the stride-Factor volume) and
 * "total_bytes". Show it with Point Gaussian next to a volume to see where
 * the low resolution loses detail.
 *
 * Errors (no point scalars, a factor other than 2, 4 or 8, a threshold or
 * bound outside [0, 1], an image too small for the factor, infinite samples
 * or NaN only (NaN samples are no data: no point there), a
 * file that cannot be written) are reported with vtkErrorMacro and fail the
 * request with an empty output.
 */
#ifndef vtkHybridOctreePoints_h
#define vtkHybridOctreePoints_h

#include "HybridOctreeFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for FileName

class HYBRIDOCTREEFILTERS_EXPORT vtkHybridOctreePoints : public vtkPolyDataAlgorithm
{
public:
  static vtkHybridOctreePoints* New();
  vtkTypeMacro(vtkHybridOctreePoints, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Low-resolution factor: the image keeps every 2, 4 or 8 samples (default 4).
  vtkSetMacro(Factor, int);
  vtkGetMacro(Factor, int);
  ///@}

  ///@{
  /// A point wherever |error| exceeds this fraction of the data range (default 0.1).
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /// Above 0: the points of the largest errors, this many, instead of Threshold (default 0).
  vtkSetClampMacro(PointBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(PointBudget, vtkIdType);
  ///@}

  ///@{
  /// Only where the low resolution underestimates (default off).
  vtkSetMacro(UnderestimatesOnly, vtkTypeBool);
  vtkGetMacro(UnderestimatesOnly, vtkTypeBool);
  vtkBooleanMacro(UnderestimatesOnly, vtkTypeBool);
  ///@}

  ///@{
  /// The optimized representation's bound, a fraction of the data range; below 0 (default -1): off.
  vtkSetMacro(MaxOverestimate, double);
  vtkGetMacro(MaxOverestimate, double);
  ///@}

  ///@{
  /// Also write the points here (HOPOINTS file); empty (default): do not.
  void SetFileName(const std::string& name);
  const std::string& GetFileName() const { return this->FileName; }
  ///@}

  ///@{
  /// Component of a multi-component array (-1: none, single-component arrays only).
  vtkSetMacro(Component, int);
  vtkGetMacro(Component, int);
  ///@}

protected:
  vtkHybridOctreePoints();
  ~vtkHybridOctreePoints() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// The whole input image.
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Factor = 4;
  double Threshold = 0.1;
  vtkIdType PointBudget = 0;
  vtkTypeBool UnderestimatesOnly = 0;
  double MaxOverestimate = -1.0;
  std::string FileName;
  int Component = -1;

private:
  vtkHybridOctreePoints(const vtkHybridOctreePoints&) = delete;
  void operator=(const vtkHybridOctreePoints&) = delete;
};

#endif
