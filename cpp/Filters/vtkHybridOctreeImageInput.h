/**
 * @file   vtkHybridOctreeImageInput.h
 * @brief  A vtkImageData's scalars as the Rust core reads them (private to the module).
 *
 * The filter and the volume mapper hand the core the same thing: the chosen
 * point array, borrowed (its storage, all components), and the layout of the
 * image's samples. This is the one place that maps VTK types and image
 * geometry to the bridge's.
 */
#ifndef vtkHybridOctreeImageInput_h
#define vtkHybridOctreeImageInput_h

#include "vtkHybridOctreeBridge.h"

#include <cstddef>
#include <string>

class vtkDataArray;
class vtkImageData;
class vtkInformationVector;

namespace vtkHybridOctreeImageInput
{
/// Maps a VTK scalar type to the core's; false for types the core cannot read.
bool ToBridgeType(int vtkType, vtkHybridOctreeBridge::ScalarType& type);

/// The bytes of `scalars` that the core reads (all components).
std::size_t ByteCount(vtkDataArray* scalars);

/// The storage of `scalars`, or nullptr when it is empty.
const void* Bytes(vtkDataArray* scalars);

/**
 * The layout of `scalars` on `image`: point dims from the extent, spacing,
 * origin of the first sample (origin + extent start * spacing), components
 * and the chosen `component` (-1: none). The scalar type must be one
 * ToBridgeType() accepts (F32 is kept otherwise).
 */
vtkHybridOctreeBridge::GridDescription DescribeGrid(
  vtkImageData* image, vtkDataArray* scalars, int component);

/**
 * `scalars` (the algorithm's selected input array, with its `association`)
 * if the core can read it as the image's point samples; else nullptr and
 * `error` saying what to do (no input image, cell data, no array, an
 * unsupported type, a non-contiguous array). The filters' RequestData
 * preamble: `image` is the request's input, possibly null.
 */
vtkDataArray* CheckPointScalars(
  vtkImageData* image, vtkDataArray* scalars, int association, std::string& error);

/// Asks input 0 for its whole extent (the core reads the whole image,
/// whatever part of the output is asked for): RequestUpdateExtent's body.
void RequestWholeExtent(vtkInformationVector** inputVector);

/// Same dims, spacing, origin, type and component choice.
bool SameGrid(
  const vtkHybridOctreeBridge::GridDescription& a, const vtkHybridOctreeBridge::GridDescription& b);
}

#endif
