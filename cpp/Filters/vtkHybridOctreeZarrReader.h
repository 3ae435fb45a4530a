/**
 * @class   vtkHybridOctreeZarrReader
 * @brief   Reads an OME-Zarr image as a light vtkImageData that names the
 *          volume on disk, for vtkHybridOctreeVolumeMapper to draw from it.
 *
 * FileName is the image's folder (e.g. `image.ome.zarr`): one written by
 * `hybrid-octree convert` (its levels are the exact strides 2^p of the full
 * resolution, and it holds the Volume Octree), or an NGFF 0.4/0.5 image
 * written by another tool (its full resolution is read; a level p is then
 * its stride-2^p subsampling, and time and channel axes are taken at index 0).
 *
 * The output is the finest level whose samples fit MaximumMegabytes
 * (10^6 bytes each; default 64): level p holds the samples
 * x_p(i) = min(i 2^p, n - 1) per axis, so its origin is the store's and
 * its spacing 2^p times the store's. When n - 1 is not a multiple of 2^p,
 * the level's last plane is the full resolution's last sample, n - 1, but
 * the image places it at (m_p - 1) 2^p, less than 2^p samples beyond: every
 * other plane sits exactly where its samples are, and the image's bounds
 * reach up to 2^p - 1 full-resolution samples past the volume's (level 0
 * has no such plane). The point scalars are named as the store's image;
 * the field data (vtkHybridOctreeStoreFieldData.h) carries the store's
 * folder and its full resolution's dims, spacing and origin, with the
 * arrays "HybridOctreeStoreLevel" (p) and "HybridOctreeStoreLevels".
 * vtkHybridOctreeVolumeMapper given this image draws the full-resolution
 * volume from the store (its bounds are the store's); any other
 * representation draws the light image.
 *
 * Errors (no FileName, a missing folder, a folder that is not an OME-Zarr
 * image, damaged metadata, a chunk missing or damaged, no level within
 * MaximumMegabytes) are reported with vtkErrorMacro naming the problem and
 * the fix, and fail the request.
 */
#ifndef vtkHybridOctreeZarrReader_h
#define vtkHybridOctreeZarrReader_h

#include "HybridOctreeFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr

class HYBRIDOCTREEFILTERS_EXPORT vtkHybridOctreeZarrReader : public vtkImageAlgorithm
{
public:
  static vtkHybridOctreeZarrReader* New();
  vtkTypeMacro(vtkHybridOctreeZarrReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The OME-Zarr image's folder.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// The output's largest size in megabytes (10^6 bytes; default 64): the
  /// finest level whose samples fit is read.
  vtkSetClampMacro(MaximumMegabytes, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumMegabytes, double);
  ///@}

  /// The level the last update read (stride 2^Level), -1 before one.
  vtkGetMacro(Level, int);

  /// 1 when `name` is a folder holding OME-Zarr metadata (zarr.json or .zattrs).
  static int CanReadFile(const char* name);

protected:
  vtkHybridOctreeZarrReader();
  ~vtkHybridOctreeZarrReader() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkHybridOctreeZarrReader(const vtkHybridOctreeZarrReader&) = delete;
  void operator=(const vtkHybridOctreeZarrReader&) = delete;

  /// Opens the store and chooses the level; false after reporting the error.
  bool OpenStore();

  char* FileName = nullptr;
  double MaximumMegabytes = 64.0;
  int Level = -1;
  struct vtkInternals; ///< the open store
  std::unique_ptr<vtkInternals> Internals;
};

#endif
