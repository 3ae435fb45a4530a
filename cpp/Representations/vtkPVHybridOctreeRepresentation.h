/**
 * @class   vtkPVHybridOctreeRepresentation
 * @brief   ParaView's "Hybrid Octree Volume" representation of image data.
 *
 * ParaView's own volume representation of image data
 * (vtkImageVolumeRepresentation: colour and opacity transfer functions of
 * the coloured array, visibility, LOD outline, data delivery, ordered
 * compositing of the ranks' pieces) with vtkHybridOctreeVolumeMapper as its
 * mapper: each rank builds the Hybrid Octree of its own piece, selects its
 * bricks under the texture budget and draws them; ParaView composites the
 * ranks' images in visibility order from the pieces' bounds
 * (vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION, as the base class asks).
 *
 * The Hybrid Octree settings are forwarded to the mapper; the statistics of
 * the last frame are read back from it (the server manager's
 * information-only properties).
 */
#ifndef vtkPVHybridOctreeRepresentation_h
#define vtkPVHybridOctreeRepresentation_h

#include "HybridOctreeRepresentationsModule.h"
#include "vtkImageVolumeRepresentation.h"

#include <string>

class vtkHybridOctreeVolumeMapper;

class HYBRIDOCTREEREPRESENTATIONS_EXPORT vtkPVHybridOctreeRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkPVHybridOctreeRepresentation* New();
  vtkTypeMacro(vtkPVHybridOctreeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Forwarded to vtkHybridOctreeVolumeMapper (see its documentation).
  void SetBudgetMB(double mb);
  void SetInteractiveBudgetMB(double mb);
  void SetTargetFrameMilliseconds(double ms);
  void SetTexelFormat(int format);
  void SetErrorTolerance(double tolerance);
  void SetViewSelection(int mode);
  void SetMinTexelPixels(double pixels);
  void SetViewChangeDegrees(double degrees);
  void SetAsynchronousLoading(bool on);
  void SetLoadingMemoryMB(double mb);
  void SetUseRoi(bool use);
  void SetRoiCenter(double x, double y, double z);
  void SetRoiRadius(double radius);
  void SetShowSurface(bool show);
  void SetIsovalue(double value);
  void SetSurfaceColor(double r, double g, double b);
  void SetSurfaceOpacity(double opacity);
  void SetLeafSize(int cells);
  void SetUsePoints(bool use);
  void SetPointFactor(int factor);
  void SetPointThreshold(double threshold);
  void SetPointBudget(int points);
  void SetPointFootprint(int footprint);
  ///@}

  ///@{
  /// ParaView's Volume properties GlobalIlluminationReach and
  /// VolumetricScatteringBlending: vtkImageVolumeRepresentation hands them to
  /// a vtkSmartVolumeMapper only, so they are taken here and forwarded to
  /// vtkHybridOctreeVolumeMapper (VolumeAnisotropy reaches it through the
  /// vtkVolumeProperty). The base class's are hidden, not virtual: the
  /// server manager calls these on this class.
  void SetGlobalIlluminationReach(float reach);
  void SetVolumetricScatteringBlending(float blending);
  ///@}

  ///@{
  /// Statistics of the last frame this process drew (0 or empty before one).
  int GetLastBricks();
  int GetLastBrickDraws();
  double GetLastTextureMB();
  const char* GetLastPlan();
  /// What removed volume samples: "cropping", "clipping", both, or "".
  const char* GetLastEffects();
  double GetLastFrameMilliseconds();
  double GetLastEstimatedError();
  int GetLastPoints();
  /// Texture MB uploaded in the last frame, its selection's milliseconds
  /// (0 when it drew a kept one), 1 when it selected, and the view
  /// importance of its selection ("data", "screen", "visibility", "both").
  double GetLastUploadedMB();
  double GetLastSelectMilliseconds();
  int GetLastReselected();
  const char* GetLastViewSelection();
  /// A frame within Target Frame (ms): its target (0 untimed), the share
  /// its drawing aimed at, predicted and measured drawing milliseconds, the choice's outcome
  /// ("warm-up", "met", "full", "below-fastest"; "" untimed), and the estimated RMS error of its
  /// selection (a fraction of the data range, timed or not).
  double GetLastTargetMilliseconds();
  double GetLastDrawTargetMilliseconds();
  double GetLastPredictedMilliseconds();
  double GetLastDrawMilliseconds();
  const char* GetLastTimeOutcome();
  double GetLastEstimatedRMSError();
  /// Drawn from an OME-Zarr store with Asynchronous Loading: the bricks the
  /// last frame drew by a stand-in (still loading), and the MB of samples
  /// read from the store since it was opened.
  int GetLastBricksLoading();
  double GetLastStoreMBRead();
  ///@}

  /// The budget slider's range, {0.1, full} in MB: `full` is the texture
  /// bytes of the whole input at full resolution, every leaf brick at
  /// stride 1 with its shared border, 4 bytes a texel:
  /// 4 * prod_a (c_a + ceil(c_a / L)) for c_a cells along axis a and leaf
  /// size L (at least 0.1 MB; 64 MB before the input is known).
  double* GetTextureBudgetRangeMB() VTK_SIZEHINT(2);

  /// The mapper (for tests and Python).
  vtkHybridOctreeVolumeMapper* GetHybridOctreeMapper();

protected:
  vtkPVHybridOctreeRepresentation();
  ~vtkPVHybridOctreeRepresentation() override;

  /// Image data only (the mapper draws vtkImageData).
  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// The base class's parameters (array, scalar mode, independent
  /// components), then the component of a multi-component array from the
  /// colour map's vector mode.
  void UpdateMapperParameters() override;

private:
  vtkPVHybridOctreeRepresentation(const vtkPVHybridOctreeRepresentation&) = delete;
  void operator=(const vtkPVHybridOctreeRepresentation&) = delete;

  vtkHybridOctreeVolumeMapper* Mapper() const;
  std::string LastPlan;
  std::string LastEffects;
  std::string LastViewSelection;
  std::string LastTimeOutcome;
  double TextureBudgetRangeMB[2] = { 0.1, 64.0 };
  /// Whether the 2D transfer function's second-array y axis was warned about (while it stays on).
  bool WarnedTransfer2DArray = false;
};

#endif
