/**
 * @class   vtkHybridOctreeDepthImage
 * @brief   The depth image of a binary object's octree, drawn front to back
 *          with blocking quadtrees (or back to front), as vtkImageData.
 *
 * Paper 2 (Zhao and Davis, "Fast Display of Octree Representations of 3D
 * Objects"): the voxels of the input image inside the object (the selected
 * point array at or above Isovalue, or equal to Label when UseLabel is on)
 * are encoded as an octree of white, black and gray octants and projected in
 * parallel along ViewPlaneNormal (towards the viewer). Method FrontToBack
 * traverses the octree nearest octant first and skips octants and faces
 * hidden behind what is drawn, the test being array indexing in three
 * blocking bitmaps; BackToFront is Meagher's painter's display. Both give
 * the same depth image, bit for bit.
 *
 * Output: an ImageSize x ImageSize x 1 image (spacing 1, origin 0, row 0 at
 * the bottom as VTK images are) with point arrays "depth" (float, distance
 * from the view plane, smaller is nearer, NaN where the object is not seen;
 * active scalars), "face" (unsigned char: 0 none, 1 X, 2 Y, 3 Z face) and
 * "shaded" (unsigned char RGB, the depth-shaded picture). Field data: the
 * counters of the paper's tables II and III ("white_visited",
 * "black_visited", "gray_visited", "faces", "scanlines", "pixels"),
 * "display_ms", "build_ms", "bitmap_bytes", "white_octants", "black_octants",
 * "gray_octants", "resolution" and the string "view_case".
 *
 * Errors (no point scalars, a view plane normal of (0, 0, 0), a non-finite
 * isovalue, an image size out of 8..8192, infinite samples or NaN only; a NaN
 * sample is no data, never inside) are reported with
 * vtkErrorMacro and fail the request with an empty output.
 */
#ifndef vtkHybridOctreeDepthImage_h
#define vtkHybridOctreeDepthImage_h

#include "HybridOctreeFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class HYBRIDOCTREEFILTERS_EXPORT vtkHybridOctreeDepthImage : public vtkImageAlgorithm
{
public:
  static vtkHybridOctreeDepthImage* New();
  vtkTypeMacro(vtkHybridOctreeDepthImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum
  {
    FRONT_TO_BACK = 0,
    BACK_TO_FRONT = 1
  };

  ///@{
  /// Inside the object: value at or above Isovalue (default 0).
  vtkSetMacro(Isovalue, double);
  vtkGetMacro(Isovalue, double);
  ///@}

  ///@{
  /// Inside the object: value equal to Label instead (label volumes). Default off.
  vtkSetMacro(UseLabel, vtkTypeBool);
  vtkGetMacro(UseLabel, vtkTypeBool);
  vtkBooleanMacro(UseLabel, vtkTypeBool);
  vtkSetMacro(Label, double);
  vtkGetMacro(Label, double);
  ///@}

  ///@{
  /// View plane normal, from the object towards the viewer (default 1, -1, 1).
  vtkSetVector3Macro(ViewPlaneNormal, double);
  vtkGetVector3Macro(ViewPlaneNormal, double);
  ///@}

  ///@{
  /// Side of the output image in pixels (default 512).
  vtkSetClampMacro(ImageSize, int, 8, 8192);
  vtkGetMacro(ImageSize, int);
  ///@}

  ///@{
  /// FRONT_TO_BACK (blocking quadtrees, default) or BACK_TO_FRONT (Meagher).
  vtkSetClampMacro(Method, int, FRONT_TO_BACK, BACK_TO_FRONT);
  vtkGetMacro(Method, int);
  ///@}

  ///@{
  /// Component of a multi-component array (-1: none, single-component arrays only).
  vtkSetMacro(Component, int);
  vtkGetMacro(Component, int);
  ///@}

protected:
  vtkHybridOctreeDepthImage();
  ~vtkHybridOctreeDepthImage() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /// The whole input image, whatever part of the picture is asked for.
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double Isovalue = 0.0;
  vtkTypeBool UseLabel = 0;
  double Label = 0.0;
  double ViewPlaneNormal[3] = { 1.0, -1.0, 1.0 };
  int ImageSize = 512;
  int Method = FRONT_TO_BACK;
  int Component = -1;

private:
  vtkHybridOctreeDepthImage(const vtkHybridOctreeDepthImage&) = delete;
  void operator=(const vtkHybridOctreeDepthImage&) = delete;
};

#endif
