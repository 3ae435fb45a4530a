/**
 * @file   vtkHybridOctreeTransfer2D.h
 * @brief  vtkVolumeProperty's 2D transfer function for vtkHybridOctreeVolumeMapper
 * (private to the module).
 *
 * In TF_2D mode (vtkVolumeProperty::SetTransferFunctionModeTo2D; ParaView's
 * Use 2D Transfer Function) the property's GetTransferFunction2D() image, 4
 * float components, x the scalar value over the data array's finite range, y
 * the gradient magnitude over VTK's [0, range / 4] per mean spacing
 * (src/transfer/transfer2d.rs), gives each sample's colour and opacity.
 * Update() reads it each frame (copied again only when the image, its
 * scalars or the data range change: their MTimes), resized as
 * vtkOpenGLVolumeTransferFunction2D resizes it for its texture
 * (vtkImageResize to the next power of two, at least 1024 a side), for the selection
 * (Describe()); Activate() uploads it as a linear, clamp-to-edge 2D texture,
 * what the brick shader's HO_TRANSFER_2D variant reads; ColumnTable() is the
 * 1D table of its largest alpha per column, for the geometry's empty-space
 * test. Composite only: under the other blend modes the 1D functions are
 * drawn (and warned about, vtkHybridOctreeUnsupportedEffects).
 */
#ifndef vtkHybridOctreeTransfer2D_h
#define vtkHybridOctreeTransfer2D_h

#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <cstddef>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkVolumeProperty;

class vtkHybridOctreeTransfer2D
{
public:
  /// Whether `property` is in TF_2D mode with a usable 2D function (2D, 4
  /// components, at most 4096 per side): the one the mapper draws.
  static vtkImageData* Usable(vtkVolumeProperty* property);

  /// Reads `property`'s table for `scalars` (component `component`) on a
  /// grid of `spacing` and `dims`: false (and Empty()) when the property
  /// does not draw one. The texels are copied again only when something
  /// changed. VTK takes the alpha as the opacity of one sample at its sample
  /// distance `d` (`sampleDistance`; below 0 vtkSmartVolumeMapper's still
  /// frames', SampleDistance()); the copy holds the opacity over the
  /// reference spacing d0 = max(min spacing, max spacing / 16) the DrawList
  /// corrects against, a' = 1 - (1 - a)^(d0 / d).
  bool Update(vtkVolumeProperty* property, vtkDataArray* scalars, int component,
    const double spacing[3], const std::size_t dims[3], double sampleDistance);

  /// vtkSmartVolumeMapper's still-frame sample distance (vtkVolumeMapper::
  /// SpacingAdjustedSampleDistance, LockSampleDistanceToInputSpacing): half
  /// the mean spacing, times 0.01 + 0.99 n / 100 when the geometric mean n of
  /// the cells per side is below 100.
  static double SmartSampleDistance(const double spacing[3], const std::size_t dims[3]);

  /// No table (1D mode, or none usable).
  bool Empty() const { return this->Width == 0; }

  /// Its size, texels (when `rgba` is given) and the data range its x axis
  /// spans, for the selection.
  void Describe(std::size_t size[2], std::vector<float>* rgba, double range[2]) const;

  /// A key of what the selection depends on (size, range, the time of the texels).
  std::vector<double> Key() const;

  /// Its largest alpha per column as a 1D RGBA table (one cell per column)
  /// over [lo, hi], the columns' centres: 0 exactly where the 2D table is 0
  /// at every gradient magnitude.
  const std::vector<float>& ColumnTable(double& lo, double& hi) const;

  /// Uploads the table (when changed or for another context) and activates
  /// its texture; the texture, or nullptr with `error` set.
  vtkTextureObject* Activate(vtkOpenGLRenderWindow* window, std::string& error);

  /// Deactivates the texture.
  void Deactivate();

  void ReleaseGraphicsResources();

private:
  std::size_t Width = 0;
  std::size_t Height = 0;
  std::vector<float> RGBA;
  std::vector<float> Columns;
  double Range[2] = { 0.0, 1.0 };
  double Exponent = 1.0;
  vtkTimeStamp ReadTime;
  vtkImageData* ReadFrom = nullptr;
  bool Uploaded = false;
  vtkSmartPointer<vtkTextureObject> Texture;
};

#endif
