/**
 * @file   vtkOpenGLHybridOctreeBrickDrawer.h
 * @brief  The bricks' slices, and the translucent surface in their slabs, drawn with OpenGL
 *         (private to the module).
 *
 * The Hybrid Octree, sections 3 and 4.1: a brick of level p is drawn as slices
 * every d = stride * d0 along the view, its texture sampled trilinearly at
 *
 *     u_a = clamp((x_a - lo_a) / (stride * spacing_a), 0, texels_a - 1)   (texels)
 *
 * (within 1/64 texel of the faces, in the brick's slot of a texture page:
 * vtkOpenGLHybridOctreeBrickPages)
 *
 * the value looked up in the transfer-function table and the opacity
 * corrected for the slice spacing, `a' = 1 - (1 - a)^(d / d0)`, blended
 * premultiplied back to front: `C = (c a', a') + (1 - a') C`. Exactly the CPU
 * compositor's sampling of the same DrawList.
 *
 * The vertices are made by the Rust core (vtkHybridOctreeBridge::
 * GetBrickGeometry(), src/plan/draw_geometry, with the CPU compositor's slab
 * rule); this class uploads and draws them. A translucent surface is drawn
 * inside the slabs between the slices. With
 * the brick's slices at depths S[0] > S[1] > ... > S[n-1] (back to front),
 * slab s = { z : S[s] <= z < S[s-1] } (slab 0 unbounded behind, slab n in
 * front), z = (x - eye) . forward. The DrawList names each brick's surface
 * triangles (its batches); each triangle goes, per view, into the slabs its
 * depth range [z_min, z_max] covers, slab(z) = #{ k : S[k] > z }: unclipped
 * when that is one slab, else once per slab, clipped to it with
 *
 *     gl_ClipDistance[0] = z - near,  gl_ClipDistance[1] = far - z.
 *
 * Per triangle rather than per batch: a batch (a terminal surface node) spans
 * as many slabs as its brick is deep, a triangle one or two. A brick's
 * vertices come in the order slab 0's triangles, slice 0, slab 1's
 * triangles, slice 1, ..., slab n's triangles, and the bricks of a run that
 * share a texture page are one draw call of one program (OpenGL keeps
 * primitive order within a draw); each vertex names its brick, whose
 * parameters the vertex shader reads from the frame's brick table. Surface fragments are shaded as
 * in the CPU compositor: headlight Lambert `rgb = colour |n . d|`, blended `(rgb a, a)`.
 *
 * Points of the hybrid representation (paper 3 section 4, "slices of points
 * are drawn interleaved with each pair of volumetric planes") are drawn in
 * the slab the DrawList buckets them into, with the slab's triangles, far
 * first (points at their depth, triangles at their centroid's); a brick
 * holding points is drawn as slices. Each point is a quad of
 * whole pixels around its projected centre c (window coordinates), its size
 * s = the projection of d0 (pixels), as the CPU compositor splats it
 * (crate::points::footprint):
 *
 *     square:   S = ceil(s) pixels across, from round(c - S/2), coverage s^2 / S^2
 *     Gaussian: sigma = max(s/2, 0.5), pixels within r = ceil(3 sigma) of floor(c),
 *               coverage exp(-|x - c|^2 / 2 sigma^2) s^2 / sum (the sum over those pixels)
 *
 * and its colour c_p and opacity a_p, what it adds over the textures
 * averaged over its voxel (crate::points::shade, computed in Rust per
 * transfer function, the CPU compositor's own):
 *
 *     a_p = (A_t - A_v) / (1 - A_v),   c_p = (C_t - C_v) / (A_t - A_v)
 *
 * drawn `(c_p a_p w, a_p w)` with coverage w; points adding nothing are not drawn.
 *
 * The DrawList's volume effects (src/plan/draw_list.rs) choose the program's
 * variant: HO_GRADIENTS (bordered textures, central-difference gradients) when
 * shading or gradient opacity take gradients, HO_SHADE for shading,
 * HO_GRADIENT_OPACITY for gradient opacity, a 1D table of a_grad(|g|)
 * multiplying the opacity before the slice-spacing correction
 * (src/transfer/gradient_opacity.rs), HO_TRANSFER_2D for the 2D transfer
 * function (colour and opacity from the value and the gradient magnitude).
 * A constant gradient opacity is the uniform opacityScale of every variant.
 *
 * Cropping and clipping planes (SetRegion(), the DrawList's Region, what
 * acts of the mapper's; src/plan/crop.rs): a volume sample at model
 * position x, in a slice or along a ray-marched brick, is transparent
 * unless its cropping region is kept and normal . (x - origin) >= 0 for
 * every plane; a removed sample is no sample in every blend mode (not
 * blended, not reduced, no isosurface). Only the program variants HO_CROP
 * and HO_CLIP test them, made when the list has the effect. Surfaces and points are drawn whole.
 */
#ifndef vtkOpenGLHybridOctreeBrickDrawer_h
#define vtkOpenGLHybridOctreeBrickDrawer_h

#include "vtkHybridOctreeBridge.h"
#include "vtkOpenGLHybridOctreeBrickPages.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

class vtkHybridOctreeScattering;
class vtkOpenGLHybridOctreeFloatTarget;
class vtkMatrix4x4;
class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;

class vtkOpenGLHybridOctreeBrickDrawer
{
public:
  vtkOpenGLHybridOctreeBrickDrawer();
  ~vtkOpenGLHybridOctreeBrickDrawer();

  /**
   * The vertices of every brick of a DrawList for this frame
   * (vtkHybridOctreeBridge::GetBrickGeometry()), drawn from the next Bind();
   * `pointSpacing` is d0, a point's size (the list's reference spacing).
   */
  void SetGeometry(vtkHybridOctreeBridge::BrickGeometry&& geometry, double pointSpacing);

  /// Whether brick i shows (some block visible): else nothing of its volume is drawn.
  bool IsDrawn(std::size_t i) const
  {
    return i < this->Geometry.Drawn.size() && this->Geometry.Drawn[i];
  }

  /**
   * Makes the program current: `mcdc` the model-to-clip matrix, `table` the
   * transfer-function table (RGBA over [lo, hi] in `entries` cells),
   * `target` the bound float target (its size, and its copy of the opaque
   * geometry's depth: fragments and ray samples behind it are dropped),
   * `eye`, `forward`, `parallel` the camera in model coordinates,
   * `surfaceRGBA` the surface's colour and opacity. Uploads the vertices of
   * the last SetGeometry() on the first call after it. False and `error` on failure.
   */
  bool Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc, vtkTextureObject* table,
    vtkOpenGLHybridOctreeFloatTarget& target, int entries, double lo, double hi,
    const double eye[3], const double forward[3], bool parallel, const double surfaceRGBA[4],
    std::string& error);

  /// The volume's shading, light directions in model coordinates (see
  /// ShadingDescription); Shade off: the unshaded program, no gradient.
  /// Shaded bricks' textures carry one border texel per side. Call before Bind().
  void SetShading(const vtkHybridOctreeBridge::ShadingDescription& shading)
  {
    this->Shading = shading;
  }

  /**
   * The blend mode's reduction (see the float target): 0 Composite (the
   * composite program), 1 maximum, 2 minimum, 3 average, 4 additive
   * intensity (the reducing program: every slice fragment and ray sample
   * writes its share of the reduction, surface triangles and points draw
   * nothing); `valueRange` what average and additive normalise by,
   * `averageRange` the values an average counts. Call before Bind().
   */
  void SetReduction(int mode, const double valueRange[2], const double averageRange[2])
  {
    this->ReduceMode = mode;
    for (int i = 0; i < 2; ++i)
    {
      this->ValueRange[i] = valueRange[i];
      this->AverageRange[i] = averageRange[i];
    }
  }

  /**
   * The isovalues of the Isosurface blend mode (increasing; empty for the
   * other modes): a sample shows the isovalue crossed since the sample one
   * step nearer the eye (src/plan/blend.rs), its textures bordered as
   * shaded ones. Call before Bind().
   */
  void SetIsosurfaces(const std::vector<double>& values) { this->Isosurfaces = values; }

  /**
   * The Slice blend mode (src/plan/slice.rs): the frame's geometry is the
   * plane's polygon in each brick, and each fragment is the sample there,
   * (a c, a), its opacity not corrected (the HO_SLICE variant). Call before Bind().
   */
  void SetSlice(bool slice) { this->Slice = slice; }

  /// The most isosurface values the Isosurface program takes.
  static constexpr int MaxIsosurfaces = 16;

  /**
   * The DrawList's opacity effects: `gradients` whether the samples take
   * gradients (the textures carry one border texel per side), `table` the
   * gradient opacity at magnitudes k `end` / (n - 1) (empty: none, the program
   * without it), `scale` every opacity's constant factor. Call before Bind().
   */
  void SetOpacityEffects(bool gradients, const std::vector<float>& table, double end, double scale);

  /**
   * The brick textures' decoding (DrawList::TexelScale, TexelBias): every
   * texture read t of the scalar is the value `bias + scale t` (R8 and R16
   * read normalized codes; 1 and 0 for R32F). Call before Bind().
   */
  void SetTexelDecode(double scale, double bias)
  {
    this->TexelDecode[0] = scale;
    this->TexelDecode[1] = bias;
  }

  /**
   * The 2D transfer function (the DrawList's effect "transfer-2d"): its
   * texture (an RGBA table, x the value, y the gradient magnitude; nullptr:
   * none, the program without it) and `axes`, the DrawList's Transfer2DAxes
   * (lo, hi, g_max). The HO_TRANSFER_2D variant classifies each sample by it
   * (src/transfer/transfer2d.rs). Call before Bind().
   */
  void SetTransfer2D(vtkTextureObject* table, const double axes[3]);

  /// Volumetric scattering (the HO_SCATTERING variant, with shading), its
  /// shadow volume activated; nullptr: none. Call before Bind().
  void SetScattering(const vtkHybridOctreeScattering* scattering) { this->Scattering = scattering; }

  /**
   * Two dependent fields (the DrawList's "dependent-components"): the
   * brick textures hold (colour, opacity) pairs; each sample's colour is the
   * table's at channel 0 over `colourRange`, its opacity the table's at
   * channel 1 over Bind()'s range (the HO_DEPENDENT2 program). Off: one
   * field. Call before Bind().
   */
  void SetDependent(bool on, const double colourRange[2])
  {
    this->Dependent = on;
    this->ColourRange[0] = colourRange[0];
    this->ColourRange[1] = colourRange[1];
  }

  /**
   * An RGBA volume (the DrawList's "rgba-components"): the brick textures
   * hold the four components; each sample's colour is channels r, g, b
   * read by `reading` (DrawList::RgbaReading: three scales, three biases,
   * then channel a's scale and bias, VTK 9.2's reading in texel units),
   * clamped after the shading, its opacity the table's at channel a's
   * value; channel r's value (TexelDecode) gives the gradient (the HO_RGBA
   * program). Off: not RGBA. Call before Bind().
   */
  void SetRgba(bool on, const std::vector<double>& reading)
  {
    this->Rgba = on && reading.size() == 8;
    for (std::size_t k = 0; k < 8; ++k)
    {
      this->RgbaReading[k] = k < reading.size() ? reading[k] : 0.0;
    }
  }

  /// The most lights the shaded program takes.
  static constexpr int MaxLights = 8;

  /// The cropping and clipping planes that act (the DrawList's Region, model
  /// coordinates); none: the programs without the test. Call before Bind().
  void SetRegion(const vtkHybridOctreeBridge::RegionDescription& region) { this->Region = region; }

  /// The most clipping planes the clipping program takes (the core's limit).
  static constexpr int MaxClippingPlanes = 8;

  /// Ray-marched bricks sample every max(d, factor d0) along the view (d
  /// their slice spacing; `factor` a power of two, 1 by default: the slice lattice).
  void SetSampleSpacing(int factor) { this->SampleSpacing = factor > 1 ? factor : 1; }

  /// Jittering (the list's effect "jittering", src/plan/jitter.rs): each
  /// ray-marched brick samples z = (k + frac(n P / s)) s, s its sample
  /// spacing, n the pixel's noise, P the largest s of the list. Interactive
  /// frames that widen the spacing jitter too. Call after
  /// SetSampleSpacing() and the geometry, before drawing.
  void SetJitter(bool on, const vtkHybridOctreeBridge::DrawList& list);

  /// Makes the program and vertices of the last Bind() current again
  /// (after another program drew).
  void Rebind(vtkOpenGLRenderWindow* window);

  /**
   * The frame's brick table: each brick's parameters (its box and texel
   * step, its texels and `slots[i]` in a texture page, its opacity ratio,
   * sample spacing and jitter), which the vertex shader reads by the brick
   * index of each vertex. Call after Bind(), SetSampleSpacing() and
   * SetJitter(), before DrawBricks(). False and `error` on bad sizes.
   */
  bool SetBricks(vtkOpenGLRenderWindow* window, const vtkHybridOctreeBridge::DrawList& list,
    const double spacing[3], const std::vector<const vtkOpenGLHybridOctreeBrickPages::Slot*>& slots,
    std::string& error);

  /**
   * Draws bricks [first, last) of the list in one call (OpenGL keeps the
   * primitives' order, so they composite in list order), all in the page of
   * `slot` (activated). A driver whose texture buffers hold fewer bricks
   * takes more calls. False and `error` when the brick table cannot load.
   */
  bool DrawBricks(std::size_t first, std::size_t last,
    const vtkOpenGLHybridOctreeBrickPages::Slot& slot, std::string& error);

  /// Draw calls since SetBricks().
  std::size_t GetNumberOfDraws() const { return this->Draws; }

  /// Whether brick i is drawn as its ray-marched box (else as slices).
  bool IsRayMarched(std::size_t i) const
  {
    return i < this->Geometry.RayMarched.size() && this->Geometry.RayMarched[i];
  }

  /// Unbinds the vertex arrays.
  void Unbind();

  /// Frees the buffers (the context is going away).
  void ReleaseGraphicsResources();

private:
  /// The shaded program's material and light uniforms.
  bool SetShadingUniforms(std::string& error);
  /// The cropping and clipping programs' uniforms.
  bool SetRegionUniforms(std::string& error);
  /// The gradient opacity table (uploaded when it changed), activated, and its uniforms.
  bool SetGradientOpacityUniforms(vtkOpenGLRenderWindow* window, std::string& error);
  /// The program's variant defines for this frame's effects.
  std::string VariantDefines() const;
  /// Loads the brick table's window from brick `first` (as many as fit).
  bool LoadBrickTable(std::size_t first, std::string& error);

  vtkOpenGLHybridOctreeBrickDrawer(const vtkOpenGLHybridOctreeBrickDrawer&) = delete;
  vtkOpenGLHybridOctreeBrickDrawer& operator=(const vtkOpenGLHybridOctreeBrickDrawer&) = delete;

  /// The vertices (11 floats each), per-brick ranges, flags and boxes.
  vtkHybridOctreeBridge::BrickGeometry Geometry;
  /// d0: a point's size.
  float PointSpacing = 1.0f;
  int SampleSpacing = 1;
  bool Jitter = false;
  /// P: the largest sample spacing of the list's bricks.
  double JitterPeriod = 0.0;
  /// Brick i's sample spacing along the view: max(d, SampleSpacing d0)
  /// ray-marched in a frame that widens it (SampleSpacing > 1), else d.
  double SampleSpacingOf(const vtkHybridOctreeBridge::DrawList& list, std::size_t i) const;
  vtkHybridOctreeBridge::ShadingDescription Shading;
  vtkHybridOctreeBridge::RegionDescription Region;
  int ReduceMode = 0;
  std::vector<double> Isosurfaces;
  bool Slice = false;
  double ValueRange[2] = { 0.0, 1.0 };
  double AverageRange[2] = { 0.0, 1.0 };
  bool Gradients = false;
  bool Dependent = false;
  double ColourRange[2] = { 0.0, 1.0 };
  bool Rgba = false;
  double RgbaReading[8] = { 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0 };
  double OpacityScale = 1.0;
  double TexelDecode[2] = { 1.0, 0.0 };
  std::vector<float> GradientOpacityTable;
  double GradientOpacityEnd = 1.0;
  bool GradientOpacityUploaded = false;
  vtkSmartPointer<vtkTextureObject> GradientOpacityTexture;
  vtkTextureObject* Transfer2DTable = nullptr;
  const vtkHybridOctreeScattering* Scattering = nullptr;
  double Transfer2DAxes[3] = { 0.0, 1.0, 1.0 };
  /// The frame's brick table (SetBricks()), RGBA floats; the window of it
  /// loaded, bricks [TableFirst, TableFirst + TableCount), at most TableCapacity.
  std::vector<float> BrickParameters;
  vtkSmartPointer<vtkOpenGLBufferObject> BrickTableBuffer;
  vtkSmartPointer<vtkTextureObject> BrickTable;
  std::size_t TableFirst = 0;
  std::size_t TableCount = 0;
  std::size_t TableCapacity = 0;
  std::size_t Draws = 0;
  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;
  vtkShaderProgram* Program = nullptr;
  bool Uploaded = false;
};

#endif
