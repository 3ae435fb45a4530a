/**
 * @file   vtkHybridOctreeSlice.h
 * @brief  The Slice blend mode's plane as VTK 9.2's GPU ray caster takes it
 * (private to the module).
 *
 * vtkVolumeMapper::SLICE_BLEND draws the volume where the pixel rays meet
 * vtkVolumeProperty's SliceFunction, which must be a vtkPlane
 * (vtkOpenGLGPUVolumeRayCastMapper, vtkVolumeShaderComposer.h:
 * intersectRayPlane). Its origin and normal are world coordinates; VTK
 * takes them into the volume's data coordinates with the inverse of the
 * volume's matrix, the normal as a direction (in_inverseVolumeMatrix *
 * vec4(normal, 0)), and so does Describe() (with the inverse of the matrix
 * that takes the octree's frame to world coordinates).
 */
#ifndef vtkHybridOctreeSlice_h
#define vtkHybridOctreeSlice_h

#include <string>

class vtkMatrix4x4;
class vtkVolumeProperty;

namespace vtkHybridOctreeSlice
{
/**
 * The plane of `property`'s SliceFunction in the octree's frame (`modelInverse`
 * takes world coordinates there; nullptr: the identity): origin x, y, z,
 * normal x, y, z into `plane`. False, with `problem` saying what is wrong and
 * what to do, when there is no slice function, it is not a vtkPlane, or its
 * origin or normal is not finite or the normal is 0.
 */
bool Describe(
  vtkVolumeProperty* property, vtkMatrix4x4* modelInverse, double plane[6], std::string& problem);
}

#endif
