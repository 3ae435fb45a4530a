// vtkHybridOctreeVolumeMapper: a frame's brick textures and its OpenGL drawing, and the CPU
// compositor on the same DrawList (vtkHybridOctreeVolumeMapperInternals.h).
#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeImageInput.h"
#include "vtkHybridOctreeInteractiveReduction.h"
#include "vtkHybridOctreeVolumeMapperInternals.h"
#include "vtkOpenGLHybridOctreeBrickTextures.h"
#include "vtkOpenGLHybridOctreeFloatTarget.h"

#include "vtkFloatArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
using namespace vtkHybridOctreeBridge;
using vtkHybridOctreeImageInput::ByteCount;
using vtkHybridOctreeImageInput::Bytes;

/// The reduction of the DrawList's blend mode, the brick shader's
/// reduceMode: 1 maximum, 2 minimum, 3 average intensity, 4 additive (VTK's
/// values), 0 for the compositing modes.
int ReduceMode(int blendMode)
{
  return blendMode >= vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND &&
      blendMode <= vtkVolumeMapper::ADDITIVE_BLEND
    ? blendMode
    : 0;
}

} // namespace

bool vtkHybridOctreeVolumeMapper::DrawFrame(vtkRenderer* ren, vtkOpenGLRenderWindow* window,
  vtkOpenGLCamera* camera, const DrawList& list, bool interactive, int level)
{
  vtkInternals& in = *this->Internals;
  std::vector<const vtkOpenGLHybridOctreeBrickTextures::Resident*> textures;
  vtkHybridOctreeBridge::BrickGeometryInput geometryInput;
  if (!this->AcquireBrickTextures(window, list, textures, geometryInput) ||
    !this->UploadTable(window))
  {
    return false;
  }
  const CameraDescription cam = this->ModelCamera(ren);
  const vtkHybridOctreeInteractiveReduction::Level sampling =
    vtkHybridOctreeInteractiveReduction::GetLevel(level);
  if (!this->MakeBrickGeometry(list, cam, interactive, sampling.SampleSpacing, geometryInput))
  {
    return false;
  }
  this->LastImageSampleDistance = sampling.ImageSampleDistance;
  this->LastSampleSpacing = sampling.SampleSpacing;

  // Model to clip: VTK's key matrices are transposed for OpenGL.
  vtkMatrix4x4* wcvc;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  vtkMatrix3x3* normals;
  camera->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  vtkNew<vtkMatrix4x4> mcwc;
  vtkMatrix4x4::Transpose(in.Model, mcwc);
  vtkNew<vtkMatrix4x4> mcdc;
  vtkMatrix4x4::Multiply4x4(mcwc, wcdc, mcdc);
  const double rgba[4] = { this->SurfaceColor[0], this->SurfaceColor[1], this->SurfaceColor[2],
    this->SurfaceOpacity };

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglActiveTexture activeTexture(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  in.Drawer.SetRegion(list.Region);
  return this->DrawOpaqueSurface(window, mcdc, cam, list, rgba) &&
    this->DrawBricks(ren, window, mcdc, cam, list, textures, interactive,
      sampling.ImageSampleDistance, sampling.SampleSpacing, rgba);
}

bool vtkHybridOctreeVolumeMapper::AcquireBrickTextures(vtkOpenGLRenderWindow* window,
  const DrawList& list, std::vector<const vtkOpenGLHybridOctreeBrickTextures::Resident*>& textures,
  vtkHybridOctreeBridge::BrickGeometryInput& geometryInput)
{
  vtkInternals& in = *this->Internals;
  std::string error;
  const std::size_t bricks = list.GetNumberOfBricks();
  // The points bought share the budget: the textures get the rest.
  const Selection& selected = *in.Frame->Selected;
  const double textureBudget =
    this->BudgetMB * 1.0e6 - static_cast<double>(in.Frame->Summary.PointBytes);
  // Gradients (shading, gradient opacity) or Isosurface: textures with one
  // border texel per side (the gradient and the sample before a brick's
  // first read them); the resident ones of the other kind are released first.
  const bool isosurface = list.BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND;
  const bool bordered = list.Bordered;
  // MIP and MinIP: coarse textures keep their peaks (other texels, so the
  // resident textures of the other kind go too).
  const int reduceMode = ReduceMode(list.BlendMode);
  const bool pooled = reduceMode == 1 || reduceMode == 2;
  // Dependent: (colour, opacity) texel pairs; RGBA: four channels, RGBA8
  // (TexelFormat unorm8, u8 data) or RGBA32F, alpha decoded by TexelScale.
  const bool dependent = list.Effects.find("dependent-components") != std::string::npos;
  const bool rgba = list.Effects.find("rgba-components") != std::string::npos;
  in.Bricks.SetChannels(window, rgba ? 4 : dependent ? 2 : 1);
  in.Bricks.SetTexelFormat(window, list.TexelFormat);
  in.Drawer.SetTexelDecode(list.TexelScale, list.TexelBias);
  in.Drawer.SetDependent(dependent, in.ColourRange);
  in.Drawer.SetRgba(rgba, list.RgbaReading);
  if (bordered != in.BorderedTextures || pooled != in.PooledTextures ||
    in.TexturesTime < in.OctreeTime)
  {
    in.TexturesTime.Modified();
    in.Bricks.Clear(window);
    in.BorderedTextures = bordered;
    in.PooledTextures = pooled;
  }
  // Scattering shades (VTK's model blends the gradient shading, identity or not).
  const bool scatters = list.Effects.find("volume-scattering") != std::string::npos;
  ShadingDescription shading = in.Shading;
  shading.Shade = list.Shading || scatters;
  in.Drawer.SetShading(shading);
  if (scatters && in.Store)
  {
    vtkErrorMacro("volumetric scattering's shadow volume needs every sample in memory, and the "
                  "image names the OME-Zarr store '"
      << in.StorePath << "', drawn from disk: set VolumetricScatteringBlending to 0");
    return false;
  }
  if (scatters &&
    !in.Scattering.Activate(window, selected, Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
      in.OctreeTime.GetMTime(), error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.Drawer.SetScattering(scatters ? &in.Scattering : nullptr);
  in.Drawer.SetIsosurfaces(isosurface ? in.Isosurfaces : std::vector<double>());
  in.Drawer.SetSlice(!list.SlicePlane.empty());
  in.Drawer.SetOpacityEffects(
    list.Gradients, list.GradientOpacityTable, list.GradientOpacityEnd, list.OpacityScale);
  // The 2D transfer function's texture, when the plan classifies by it.
  vtkTextureObject* transfer2D = nullptr;
  if (list.Effects.find("transfer-2d") != std::string::npos &&
    !(transfer2D = in.Transfer2D.Activate(window, error)))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.Drawer.SetTransfer2D(transfer2D, list.Transfer2DAxes);
  const std::size_t border = bordered ? 1 : 0;
  in.Bricks.BeginFrame(
    static_cast<std::size_t>(std::max(textureBudget, 0.0)), list.NodeId, list.Stride);
  textures.assign(bricks, nullptr);
  // The frame's geometry is made from each brick's block ranges (kept with its texture).
  geometryInput.BlockRanges.assign(bricks, nullptr);
  for (std::size_t i = 0; i < bricks; ++i)
  {
    const std::size_t brick = list.Brick[i];
    const std::size_t dims[3] = { list.Texels[3 * i] + 2 * border,
      list.Texels[3 * i + 1] + 2 * border, list.Texels[3 * i + 2] + 2 * border };
    const vtkOpenGLHybridOctreeBrickTextures::Resident* resident = in.Bricks.Acquire(
      window, { list.NodeId[i], list.Stride[i] }, dims,
      [&](float* texels, unsigned char* encoded, std::size_t count) {
        if (in.Store)
        {
          return selected.GetBrickTexelsFromStore(*in.Octree, *in.Store, brick, bordered, texels,
            count, encoded, encoded ? count * in.Bricks.GetStagingBytes() : 0, error);
        }
        if (rgba)
        {
          return selected.GetBrickTexelsRgba(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, encoded, encoded ? count : 0, error);
        }
        if (dependent)
        {
          return selected.GetBrickTexelsDependent(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, error);
        }
        if (encoded)
        {
          return selected.GetBrickTexelsEncoded(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, encoded, count * in.Bricks.GetStagingBytes(), error);
        }
        return bordered ? selected.GetBrickTexelsBordered(Bytes(in.Scalars), ByteCount(in.Scalars),
                            in.Grid, brick, texels, count, error)
                        : selected.GetBrickTexels(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
                            brick, texels, count, error);
      },
      error, border);
    if (!resident)
    {
      vtkErrorMacro(<< error);
      return false;
    }
    textures[i] = resident;
    geometryInput.BlockRanges[i] = &resident->BlockRanges;
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::UploadTable(vtkOpenGLRenderWindow* window)
{
  vtkInternals& in = *this->Internals;
  if (!in.TableTexture)
  {
    in.TableTexture = vtkSmartPointer<vtkTextureObject>::New();
    in.TableUploaded = false;
  }
  if (!in.TableUploaded || in.TableTexture->GetContext() != window)
  {
    in.TableTexture->SetContext(window);
    in.TableTexture->SetWrapS(vtkTextureObject::ClampToEdge);
    in.TableTexture->SetWrapT(vtkTextureObject::ClampToEdge);
    in.TableTexture->SetMinificationFilter(vtkTextureObject::Linear);
    in.TableTexture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!in.TableTexture->Create2DFromRaw(
          static_cast<unsigned int>(this->TableSize), 1, 4, VTK_FLOAT, in.Table.data()))
    {
      vtkErrorMacro("OpenGL could not create the transfer function table texture");
      return false;
    }
    in.TableUploaded = true;
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::MakeBrickGeometry(const DrawList& list,
  const CameraDescription& cam, bool interactive, double sampleSpacing,
  vtkHybridOctreeBridge::BrickGeometryInput& geometryInput)
{
  vtkInternals& in = *this->Internals;
  const bool batches = !list.BatchOffsets.empty() && list.BatchOffsets.back() > 0;
  // Per brick its slices clipped to its visible blocks, the translucent
  // triangles and the points in the slabs between them, or its ray-marched
  // box. Interactive: every brick ray-marched, no triangles or points in slabs.
  geometryInput.List = &list;
  std::copy(cam.Position, cam.Position + 3, geometryInput.Eye);
  std::copy(cam.ViewUp, cam.ViewUp + 3, geometryInput.ViewUp);
  std::copy(in.Grid.Spacing, in.Grid.Spacing + 3, geometryInput.Spacing);
  geometryInput.Table = &in.Table;
  geometryInput.TableLo = in.RangeLo;
  geometryInput.TableHi = in.RangeHi;
  if (list.Effects.find("transfer-2d") != std::string::npos)
  {
    // A block is empty when the 2D table is 0 over its values at every gradient.
    geometryInput.Table = &in.Transfer2D.ColumnTable(geometryInput.TableLo, geometryInput.TableHi);
  }
  if (batches && !interactive)
  {
    geometryInput.SurfaceVertices = &in.SurfaceDrawer.GetVertexData();
    geometryInput.SurfaceTriangles = &in.SurfaceDrawer.GetIndexData();
  }
  if (in.HasPoints && !list.BucketOffsets.empty() && !interactive)
  {
    geometryInput.PointPositions = &in.Drawing.Position;
    geometryInput.PointShades = &in.Shades;
    geometryInput.GaussianPoints = this->PointFootprint == 1;
  }
  std::string error;
  vtkHybridOctreeBridge::BrickGeometry geometry;
  if (!vtkHybridOctreeBridge::GetBrickGeometry(geometryInput, geometry, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(geometry.TrianglesPlaced);
  this->LastPoints = static_cast<vtkTypeInt64>(geometry.PointsPlaced);
  in.Drawer.SetGeometry(std::move(geometry), list.ReferenceSpacing);
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    if (in.Drawer.IsDrawn(i))
    {
      // The lattice planes sampled: every factor-th slice of a sparser ray march.
      const double slices = static_cast<double>(list.SliceOffsets[i + 1] - list.SliceOffsets[i]);
      const double factor = list.SliceSpacing[i] > 0.0
        ? std::max(1.0, sampleSpacing * list.ReferenceSpacing / list.SliceSpacing[i])
        : 1.0;
      this->LastSlices += static_cast<vtkTypeInt64>(std::ceil(slices / factor));
      ++this->LastBricks;
    }
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::DrawOpaqueSurface(vtkOpenGLRenderWindow* window,
  vtkMatrix4x4* mcdc, const CameraDescription& cam, const DrawList& list, const double rgba[4])
{
  vtkInternals& in = *this->Internals;
  if (list.OpaqueTriangles == 0)
  {
    return true;
  }
  // Written to depth, so that the volume behind it is hidden.
  vtkOpenGLState* state = window->GetState();
  state->vtkglDisable(GL_BLEND);
  state->vtkglDepthMask(GL_TRUE);
  std::string error;
  if (!in.SurfaceDrawer.Bind(window, mcdc, cam.Position, list.Forward, cam.Parallel, rgba, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.SurfaceDrawer.Draw(0, list.OpaqueTriangles);
  in.SurfaceDrawer.Unbind();
  this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(list.OpaqueTriangles);
  return true;
}

bool vtkHybridOctreeVolumeMapper::DrawBricks(vtkRenderer* ren, vtkOpenGLRenderWindow* window,
  vtkMatrix4x4* mcdc, const CameraDescription& cam, const DrawList& list,
  const std::vector<const vtkOpenGLHybridOctreeBrickTextures::Resident*>& textures,
  bool interactive, double imageSampleDistance, double sampleSpacing, const double rgba[4])
{
  vtkInternals& in = *this->Internals;
  const std::size_t bricks = list.GetNumberOfBricks();
  const bool batches = !list.BatchOffsets.empty() && list.BatchOffsets.back() > 0;
  // Interactive: its triangles drawn before or after each brick, not in slabs.
  const bool surfacePerBrick = interactive && batches;
  vtkOpenGLState* state = window->GetState();
  std::string error;
  // Bricks back to front, each one draw: its slices back to front with the
  // translucent triangles of each slab between them; blended premultiplied,
  // depth tested, not written. The region of the window drawn: the bricks'
  // boxes (their triangles included); points' footprints may reach past
  // them, so all of it then. Additive shows every ray crossing the volume's
  // box (opaque, black without a sample), so its region is that box: the
  // bricks' boxes leave out those cropping and clipping remove whole.
  const int reduceMode = ReduceMode(list.BlendMode);
  double region[4] = { -1.0, 1.0, -1.0, 1.0 };
  if (this->LastPoints == 0 && reduceMode == 4)
  {
    std::vector<double> volume(6);
    for (int a = 0; a < 3; ++a)
    {
      volume[2 * a] = in.Grid.Origin[a];
      volume[2 * a + 1] = in.Grid.Origin[a] + (in.Grid.Dims[a] - 1.0) * in.Grid.Spacing[a];
    }
    this->ScreenRegion(mcdc, volume, region);
  }
  else if (this->LastPoints == 0)
  {
    this->ScreenRegion(mcdc, list.Bounds, region);
  }
  // The blend modes besides Composite reduce each ray in the target by the
  // blend equation (maximum: GL_MAX, sums: GL_FUNC_ADD) and resolve it at End().
  const bool extremum = reduceMode == 1 || reduceMode == 2;
  const float clear[4] = { extremum ? -3.0e38f : 0.0f, 0.0f, 0.0f, 0.0f };
  if (!in.Target.Begin(ren, window, imageSampleDistance, region, error, clear))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  state->vtkglEnable(GL_BLEND);
  if (reduceMode == 0)
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  else
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    state->vtkglBlendEquation(extremum ? GL_MAX : GL_FUNC_ADD);
  }
  in.Drawer.SetReduction(reduceMode, in.ValueRange, this->AverageIPScalarRange);
  state->vtkglDisable(GL_DEPTH_TEST); // the shader tests against the copied opaque depth
  state->vtkglDepthMask(GL_FALSE);
  in.TableTexture->Activate();
  in.Target.GetDepth()->Activate();
  in.Drawer.SetSampleSpacing(sampleSpacing);
  in.Drawer.SetJitter(list.Effects.find("jittering") != std::string::npos, list);
  if (surfacePerBrick)
  {
    in.SurfaceDrawer.OrderByBrick(
      list, cam.Position, list.Forward, cam.Parallel, this->IsInsideOpaque());
  }
  bool ok = !surfacePerBrick ||
    in.SurfaceDrawer.Bind(
      window, mcdc, cam.Position, list.Forward, cam.Parallel, rgba, error, &in.Target);
  ok = ok &&
    in.Drawer.Bind(window, mcdc, in.TableTexture, in.Target, this->TableSize, in.RangeLo,
      in.RangeHi, cam.Position, list.Forward, cam.Parallel, rgba, error);
  if (ok)
  {
    // Clip distances (the slabs' triangles) on while the program that writes
    // them is bound; interactive frames have no slabs.
    for (unsigned int plane : { GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE0 + 1 })
    {
      if (!interactive)
      {
        state->vtkglEnable(plane);
      }
    }
    // Ray-marched boxes keep only the faces rays leave by (see
    // plan::draw_geometry); a mirroring model matrix turns their winding
    // over. Culling is restored before the target is blended.
    vtkOpenGLState::ScopedglEnableDisable brickCulling(state, GL_CULL_FACE);
    state->vtkglCullFace(GL_BACK);
    glFrontFace(in.Model->Determinant() < 0.0 ? GL_CW : GL_CCW);
    std::vector<const vtkOpenGLHybridOctreeBrickPages::Slot*> slots(bricks);
    for (std::size_t i = 0; i < bricks; ++i)
    {
      slots[i] = &textures[i]->Slot;
    }
    ok = in.Drawer.SetBricks(window, list, in.Grid.Spacing, slots, error);
    // Runs of bricks in list order that share a page, a culling state and
    // no interactive surface between them: one draw call each.
    for (std::size_t i = 0, next = 0; ok && i < bricks; i = next)
    {
      const bool rayMarched = in.Drawer.IsRayMarched(i);
      if (rayMarched)
      {
        state->vtkglEnable(GL_CULL_FACE);
      }
      else
      {
        state->vtkglDisable(GL_CULL_FACE);
      }
      const std::size_t before = surfacePerBrick ? this->DrawSurfaceBefore(window, i) : 0;
      if (before > 0)
      {
        this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(before);
        state->vtkglEnable(GL_CULL_FACE); // every brick of an interactive frame is ray-marched
      }
      const vtkOpenGLHybridOctreeBrickPages::Slot& slot = textures[i]->Slot;
      next = i + 1;
      while (next < bricks && textures[next]->Slot.Owner == slot.Owner &&
        in.Drawer.IsRayMarched(next) == rayMarched &&
        !(surfacePerBrick && this->HasSurfaceBefore(next)))
      {
        ++next;
      }
      vtkTextureObject* page = vtkOpenGLHybridOctreeBrickPages::GetTexture(slot);
      page->Activate();
      ok = in.Drawer.DrawBricks(i, next, slot, error);
      page->Deactivate();
    }
    this->LastBrickDraws = static_cast<vtkTypeInt64>(in.Drawer.GetNumberOfDraws());
    if (surfacePerBrick)
    {
      this->LastSurfaceTriangles +=
        static_cast<vtkTypeInt64>(this->DrawSurfaceBefore(window, bricks));
    }
    glFrontFace(GL_CCW);
    for (unsigned int plane : { GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE0 + 1 })
    {
      state->vtkglDisable(plane);
    }
    in.Drawer.Unbind();
  }
  state->vtkglBlendEquation(GL_FUNC_ADD);
  in.Target.GetDepth()->Deactivate();
  in.TableTexture->Deactivate();
  vtkOpenGLHybridOctreeFloatTarget::Resolve resolve;
  resolve.ReduceMode = reduceMode;
  resolve.Table = in.TableTexture;
  resolve.TableEntries = this->TableSize;
  resolve.TableRange[0] = in.RangeLo;
  resolve.TableRange[1] = in.RangeHi;
  resolve.MCDC = mcdc;
  for (int a = 0; a < 3; ++a)
  {
    resolve.VolumeLo[a] = in.Grid.Origin[a];
    resolve.VolumeHi[a] = in.Grid.Origin[a] + (in.Grid.Dims[a] - 1.0) * in.Grid.Spacing[a];
  }
  in.Target.End(window, reduceMode != 0 ? &resolve : nullptr);
  if (!ok)
  {
    vtkErrorMacro(<< error);
  }
  return ok;
}

void vtkHybridOctreeVolumeMapper::ScreenRegion(
  vtkMatrix4x4* mcdc, const std::vector<double>& bounds, double region[4]) const
{
  // The normalized device box of the boxes' corners (VTK's key matrices are
  // transposed: clip_r = sum_j mcdc(j, r) p_j); everything when a corner
  // lies behind the eye.
  double box[4] = { 1.0, -1.0, 1.0, -1.0 };
  for (std::size_t i = 0; 6 * i + 5 < bounds.size(); ++i)
  {
    for (int c = 0; c < 8; ++c)
    {
      const double p[4] = { bounds[6 * i + (c & 1)], bounds[6 * i + 2 + ((c >> 1) & 1)],
        bounds[6 * i + 4 + ((c >> 2) & 1)], 1.0 };
      double clip[4];
      for (int r = 0; r < 4; ++r)
      {
        clip[r] = mcdc->GetElement(0, r) * p[0] + mcdc->GetElement(1, r) * p[1] +
          mcdc->GetElement(2, r) * p[2] + mcdc->GetElement(3, r) * p[3];
      }
      if (!(clip[3] > 0.0))
      {
        region[0] = region[2] = -1.0;
        region[1] = region[3] = 1.0;
        return;
      }
      for (int a = 0; a < 2; ++a)
      {
        box[2 * a] = std::min(box[2 * a], clip[a] / clip[3]);
        box[2 * a + 1] = std::max(box[2 * a + 1], clip[a] / clip[3]);
      }
    }
  }
  std::copy(box, box + 4, region);
}

bool vtkHybridOctreeVolumeMapper::HasSurfaceBefore(std::size_t i) const
{
  const std::pair<std::size_t, std::size_t> range =
    this->Internals->SurfaceDrawer.GetTrianglesBefore(i);
  return range.second > range.first;
}

std::size_t vtkHybridOctreeVolumeMapper::DrawSurfaceBefore(
  vtkOpenGLRenderWindow* window, std::size_t i)
{
  vtkInternals& in = *this->Internals;
  const std::pair<std::size_t, std::size_t> range = in.SurfaceDrawer.GetTrianglesBefore(i);
  if (range.second <= range.first)
  {
    return 0;
  }
  window->GetState()->vtkglDisable(GL_CULL_FACE);
  in.SurfaceDrawer.Rebind(window);
  in.SurfaceDrawer.Draw(range.first, range.second);
  in.Drawer.Rebind(window);
  return range.second - range.first;
}

bool vtkHybridOctreeVolumeMapper::IsInsideOpaque() const
{
  // The mean table opacity above the isovalue against below it.
  const vtkInternals& in = *this->Internals;
  const int n = this->TableSize;
  double sum[2] = { 0.0, 0.0 };
  int count[2] = { 0, 0 };
  for (int k = 0; k < n && 4 * static_cast<std::size_t>(k) + 3 < in.Table.size(); ++k)
  {
    const double v = in.RangeLo + (in.RangeHi - in.RangeLo) * k / (n - 1);
    const int inside = v >= this->Isovalue ? 1 : 0;
    sum[inside] += in.Table[4 * static_cast<std::size_t>(k) + 3];
    ++count[inside];
  }
  return sum[1] * std::max(count[0], 1) >= sum[0] * std::max(count[1], 1);
}

bool vtkHybridOctreeVolumeMapper::CompositeOnCPU(
  vtkRenderer* ren, vtkVolume* vol, int width, int height, vtkFloatArray* rgba)
{
  vtkInternals& in = *this->Internals;
  if (!ren || !ren->GetActiveCamera() || !rgba || width <= 0 || height <= 0)
  {
    vtkErrorMacro("CompositeOnCPU needs a renderer with a camera, a size and an output array");
    return false;
  }
  if (!this->Prepare(ren, vol))
  {
    return false;
  }
  if (in.Store)
  {
    vtkErrorMacro("CompositeOnCPU draws from the image in memory, and the image names the "
                  "OME-Zarr store '"
      << in.StorePath
      << "': read its full resolution into an image without the store's field data");
    return false;
  }
  CompositeScene scene = in.Transfer;
  scene.GaussianPoints = this->PointFootprint == 1;
  if (in.HasIso && this->ShowSurface && this->SurfaceOpacity > 0.0)
  {
    for (int k = 0; k < 3; ++k)
    {
      scene.SurfaceRGBA[k] = this->SurfaceColor[k];
    }
    scene.SurfaceRGBA[3] = this->SurfaceOpacity;
  }
  // The compositor writes the picture into `rgba` itself.
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  std::string error;
  if (!in.Frame->Selected->SetShading(in.Shading, error) ||
    !in.Frame->Selected->SetGradientOpacity(in.GradientOpacity, error) ||
    !in.Frame->Selected->SetJittering(this->UseJittering != 0, error) ||
    !in.Frame->Selected->SetSampleDistance(this->ActualSampleDistance(), error) ||
    !in.Frame->Selected->SetScattering(in.ScatteringParameters, error) ||
    !in.Frame->Selected->Composite(*in.Octree, this->ModelCamera(ren), Bytes(in.Scalars),
      ByteCount(in.Scalars), in.Grid, scene, static_cast<std::size_t>(width),
      static_cast<std::size_t>(height), rgba->GetPointer(0), error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}
