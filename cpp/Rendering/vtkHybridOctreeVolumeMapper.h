/**
 * @class   vtkHybridOctreeVolumeMapper
 * @brief   Volume mapper that draws the Hybrid Octree's DrawList with OpenGL.
 *
 * On Render() the mapper takes its vtkImageData input (point scalars; a
 * multi-component array needs SetComponent()), builds the Volume Octree
 * through the Rust core (cached by the scalars' MTime and the image
 * geometry), selects bricks under BudgetMB and ErrorTolerance, skipping the
 * nodes over whose range the vtkVolumeProperty's scalar opacity is 0, and
 * asks the core for the DrawList of the active camera: bricks back to front,
 * per brick its slice depths back to front.
 *
 * Each brick's texels are uploaded once as a 3D R32F texture
 * (vtkOpenGLHybridOctreeBrickTextures: kept per (node, stride) across frames,
 * least recently drawn released first, resident bytes within BudgetMB). The
 * transfer function is a 1D RGBA float table (colour from the
 * vtkColorTransferFunction or a grey vtkPiecewiseFunction, opacity from the
 * scalar opacity) of TableSize entries over the scalars' range. An opaque
 * isosurface is drawn first with depth writes; then the bricks, back to
 * front, go into a float RGBA target (vtkOpenGLHybridOctreeFloatTarget; the
 * opaque depth stops them), one draw call each: a brick holding translucent
 * surface triangles this frame is drawn as its slices clipped to the box of
 * its visible blocks with the triangles of each slab between them, any
 * other brick is ray-marched front to back through its visible box on the
 * same slice lattice z = k d. The table's opacity is the scalar opacity per
 * ScalarOpacityUnitDistance U taken to d0 by VTK's rule for the blend mode
 * (vtkOpenGLVolumeOpacityTable): Composite 1 - (1 - a)^(d0 / U), Additive
 * a d0 / U, the other modes a as it is. Opacity is corrected a' = 1 - (1 - a)^(d / d0)
 * and blended premultiplied (GL_ONE, GL_ONE_MINUS_SRC_ALPHA); the target is
 * blended once over the window. Every GL state change goes through
 * vtkOpenGLState and is restored. docs/ARCHITECTURE.md ("The volume
 * mapper") has the details.
 *
 * CompositeOnCPU() runs the Rust CPU compositor on the same DrawList and
 * table: the reference the OpenGL picture is tested against.
 *
 * NaN samples are no data: a sample whose linear filter touches a NaN texel
 * is NaN and the shader skips it (transparent, as in the CPU compositor);
 * ranges and the blocks' occupancy leave NaN out. Infinite samples and an
 * image of NaN only are errors (reported, nothing drawn).
 *
 * With UsePoints, the points of the hybrid representation share the budget
 * and are drawn in the slabs between the slices (see SetUsePoints()).
 *
 * A volume on disk: an input image whose field data names an OME-Zarr store
 * (vtkHybridOctreeZarrReader's light output, vtkHybridOctreeStoreFieldData.h)
 * is drawn from the store, not from its own samples: the store is opened
 * once (again when its path or its folder's or metadata's modification time
 * change), its stored Volume Octree taken (a store written by another tool:
 * built from its full resolution read into memory, with LeafSize), and the
 * bricks' texels read from the level of their stride, the same texels as
 * from the full-resolution image in memory, bit for bit. GetBounds() is the
 * full resolution's; the transfer function table spans the octree's value
 * range. Selection, budgets, shading, gradient opacity, cropping, clipping,
 * the blend modes and the statistics are unchanged, except: the visibility
 * view selections (VISIBILITY, BOTH) weigh by screen space alone (one
 * warning: their estimate reads every sample); maximum and minimum intensity
 * need a budget at which every brick is at full resolution (coarse texels
 * keep peaks the levels do not store; a constant region's coarse brick is
 * drawn, its samples being its peaks), and draw no stand-ins while loading
 * asynchronously. What needs every sample in memory is
 * refused with an error naming the fix: points, the isosurface
 * (ShowSurface), volumetric scattering, a 2D transfer function, dependent
 * or RGBA components (also ParaView's separate opacity array), CompositeOnCPU().
 * The image must be a whole level of the store: a piece of it (each of
 * several MPI ranks gets one) is an error, parallel drawing from a store
 * being not supported yet. With AsynchronousLoading on, a store's bricks
 * are read by a thread in the background and a frame draws each brick not
 * read yet by a stand-in, the same node coarser (see
 * SetAsynchronousLoading()): the picture refines over the frames that follow.
 *
 * Drawn: Composite blending of one scalar component through the colour (RGB
 * or grey) and scalar opacity functions, shaded when the property asks,
 * cropped (SetCropping, SetCroppingRegionPlanes in the image's data
 * coordinates, SetCroppingRegionFlags) and clipped (SetClippingPlanes,
 * world coordinates, at most 8 planes) as VTK's GPU ray caster: a removed
 * sample is transparent, and bricks entirely removed get no texture; the
 * isosurface and the points are not cropped or clipped. Two dependent
 * components (IndependentComponentsOff on a 2-component array, Composite)
 * are drawn as VTK's GPU ray caster draws them: colour from component 0,
 * opacity from component 1 (SetComponent is then not read); so are four
 * (an RGBA volume): colour from components 0, 1, 2 as VTK 9.2 reads them,
 * opacity from component 3, gradient from component 0, RGBA8 textures for unsigned char
 * data. Settings asking for more (another blend mode, a 2D transfer
 * function, dependent components of 3-component arrays or under a reducing
 * blend mode) are drawn as off and
 * named in one warning each, given again when the setting changes.
 *
 * Interactive frames (the window's desired update rate above
 * InteractiveUpdateRate, as while the camera is dragged) draw the bricks of
 * the last still frame's selection, resident, without uploading any (a
 * selection under InteractiveBudgetMB only when there is none: before the
 * first still frame, or when its inputs changed), every brick ray-marched;
 * a translucent surface is drawn brick by brick (each of a brick's
 * triangles before or after that brick's volume, by the side of it the eye
 * is on, see vtkOpenGLHybridOctreeSurfaceDrawer) instead of in the slabs, and
 * points are left out. With AutoAdjustSampleDistances they also composite at a coarser
 * image sample distance and sample the rays more sparsely, as much as
 * keeps them within the volume's allocated render time
 * (vtkHybridOctreeInteractiveReduction). The next still frame draws the
 * full picture again.
 */
#ifndef vtkHybridOctreeVolumeMapper_h
#define vtkHybridOctreeVolumeMapper_h

#include "HybridOctreeRenderingModule.h" // for export macro
#include "vtkVolumeMapper.h"

#include <memory> // for std::unique_ptr
#include <string> // for LastPlan
#include <vector> // for selection keys

class vtkDataArray;
class vtkFloatArray;
class vtkImageData;
class vtkMatrix4x4;
class vtkOpenGLCamera;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkVolumeProperty;
struct vtkOpenGLHybridOctreeBrickResident;
#ifndef __VTK_WRAP__
namespace vtkHybridOctreeBridge
{
struct BrickGeometryInput;
struct CameraDescription;
struct DrawList;
class FrameTimer;
struct SelectDescription;
struct ViewDescription;
}
#endif

class HYBRIDOCTREERENDERING_EXPORT vtkHybridOctreeVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkHybridOctreeVolumeMapper* New();
  vtkTypeMacro(vtkHybridOctreeVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Texture budget in MB (10^6 bytes of f32 texels) of a still frame;
  /// default 64. Resident brick textures never exceed it. 0 is an error at Render().
  vtkSetClampMacro(BudgetMB, double, 0.0, 1.0e6);
  vtkGetMacro(BudgetMB, double);
  ///@}

  ///@{
  /// Texture budget in MB of an interactive frame (when the render window
  /// asks for more than InteractiveUpdateRate frames per second, as during
  /// camera interaction) that cannot draw the last still frame's resident
  /// textures: before the first still frame, or when an input of the
  /// selection changed while interacting; default 8. The next still frame
  /// refines to BudgetMB.
  vtkSetClampMacro(InteractiveBudgetMB, double, 0.0, 1.0e6);
  vtkGetMacro(InteractiveBudgetMB, double);

  /// The brick textures' texel format (VTK_HYBRID_OCTREE_TEXELS_*):
  /// AUTO (the default) uploads 8-bit data as R8 and 16-bit data as R16,
  /// as VTK's GPU ray caster does, and the rest as R32F; FLOAT16 (R16F),
  /// UNORM16 (R16) and UNORM8 (R8) quantize wider data to hold more bricks
  /// in BudgetMB, their quantization error added to every brick's
  /// (GetLastEstimatedError() includes it). Budgets and LastTextureBytes
  /// count the bytes as uploaded. Two dependent components are always
  /// float32; an RGBA volume RGBA8 for unsigned char data, else RGBA32F.
  enum
  {
    TEXELS_AUTO = 0,
    TEXELS_FLOAT32 = 1,
    TEXELS_FLOAT16 = 2,
    TEXELS_UNORM16 = 3,
    TEXELS_UNORM8 = 4
  };
  vtkSetClampMacro(TexelFormat, int, TEXELS_AUTO, TEXELS_UNORM8);
  vtkGetMacro(TexelFormat, int);
  ///@}

  ///@{
  /// Desired update rate (frames per second) above which a frame is
  /// interactive; default 1 (VTK's still update rate is 0.0001, its
  /// interactive one 15; ParaView's 0.002 and 5).
  vtkSetClampMacro(InteractiveUpdateRate, double, 0.0, 1.0e6);
  vtkGetMacro(InteractiveUpdateRate, double);
  ///@}

  ///@{
  /**
   * A frame-time target in milliseconds: the selection and its slice
   * spacing are chosen for the least estimated error whose drawing is
   * predicted within it, by a cost model calibrated on this mapper's own
   * frames (a few warm-up frames, then corrected from each measured one;
   * see src/ffi/timed.rs). BudgetMB stays the hard memory limit.
   * - 0 (the default): off; frames are made as described above.
   * - above 0: every frame, still and interactive, is made within it:
   *   the renderer's whole frame, so the drawing aims at the target less
   *   what the frames before spent outside it (the other props, the
   *   renderer's passes, this mapper's preparation, and the search when
   *   the frame selects again; LastDrawTargetMilliseconds).
   * - TARGET_FRAME_WINDOW (-1): interactive frames are made within the
   *   share of the volume's allocated render time the mapper's drawing
   *   gets (the window's desired update rate; see
   *   vtkHybridOctreeInteractiveReduction), still frames draw BudgetMB.
   * A still frame whose exact drawing (translucent surfaces sorted into
   * the slabs between the slices, points between them) is predicted
   * slower than the target even at its coarsest is drawn from the next
   * frame on as an interactive frame is (surfaces per brick, no points;
   * LastPlan says so), under that drawing's cost model, until the target
   * changes or a frame has no slab work.
   * Anything else (below 0, not a number, above ten minutes) is an error
   * at Render(). Interactive and still frames keep a cost model each (they
   * draw differently); the timed frames' AutoAdjustSampleDistances ladder
   * is left at its finest level (the target chooses the spacing).
   */
  static constexpr double TARGET_FRAME_WINDOW = -1.0;
  vtkSetMacro(TargetFrameMilliseconds, double);
  vtkGetMacro(TargetFrameMilliseconds, double);
  ///@}

  ///@{
  /// Whether interactive frames widen their image sample distance and the
  /// sample spacing along the rays to keep within the volume's allocated
  /// render time (as vtkGPUVolumeRayCastMapper's AutoAdjustSampleDistances);
  /// on by default. Off: interactive frames sample as still ones.
  vtkSetMacro(AutoAdjustSampleDistances, bool);
  vtkGetMacro(AutoAdjustSampleDistances, bool);
  vtkBooleanMacro(AutoAdjustSampleDistances, bool);
  ///@}

  ///@{
  /// Jittering (as vtkGPUVolumeRayCastMapper's UseJittering; off by
  /// default): each pixel's samples move along its ray by a fixed fraction
  /// of the slice spacing, the same lattice in every brick, so a coarse
  /// brick shows fine noise instead of wood-grain rings. The offset is a
  /// fixed hash of the pixel (src/plan/jitter.rs), not random: pictures are
  /// reproducible and the CPU compositor's the same. Not applied in Slice,
  /// nor with a translucent surface or points between the slices
  /// (LastEffects then has no "jittering").
  vtkSetMacro(UseJittering, vtkTypeBool);
  vtkGetMacro(UseJittering, vtkTypeBool);
  vtkBooleanMacro(UseJittering, vtkTypeBool);
  ///@}

  ///@{
  /**
   * What the selection weighs nodes by besides their error (src/plan/select/view.rs):
   * VIEW_SELECTION_DATA the data alone; SCREEN also the pixel area a sample
   * covers for the active camera (nodes outside the view count for nothing,
   * near ones more, and refinement stops where a texel is smaller than
   * MinTexelPixels pixels, default 0: never); VISIBILITY also an estimate of the
   * transmittance in front of each node (nodes behind opaque material or an
   * opaque isosurface count for little); BOTH (the default) both.
   * Visibility applies to Composite blending of one field with no cropping,
   * clipping planes or slice; elsewhere BOTH selects as SCREEN and
   * VISIBILITY as DATA (GetLastViewSelection() names what ran). A value
   * outside 0..3 is an error at Render().
   */
  enum
  {
    VIEW_SELECTION_DATA = 0,
    VIEW_SELECTION_SCREEN = 1,
    VIEW_SELECTION_VISIBILITY = 2,
    VIEW_SELECTION_BOTH = 3
  };
  vtkSetMacro(ViewSelection, int);
  vtkGetMacro(ViewSelection, int);
  void SetViewSelectionToData() { this->SetViewSelection(VIEW_SELECTION_DATA); }
  void SetViewSelectionToScreen() { this->SetViewSelection(VIEW_SELECTION_SCREEN); }
  void SetViewSelectionToVisibility() { this->SetViewSelection(VIEW_SELECTION_VISIBILITY); }
  void SetViewSelectionToBoth() { this->SetViewSelection(VIEW_SELECTION_BOTH); }
  ///@}

  ///@{
  /// Screen space: refinement stops where a texel would cover fewer than
  /// this many pixels along a side (>= 0; 0 never stops); default 1.
  vtkSetMacro(MinTexelPixels, double);
  vtkGetMacro(MinTexelPixels, double);
  ///@}

  ///@{
  /**
   * A view-dependent selection (ViewSelection other than DATA) is made for
   * the camera of the frame that made it, and a still frame selects again
   * only when the view moved more than ViewChangeDegrees from that camera
   * (the turn about the volume's centre, the change of aim or the zoom, in
   * degrees: vtkHybridOctreeBridge::ViewChangeDegrees) or the viewport
   * changed size; otherwise it draws the kept selection. Default 5; 0
   * selects again at every move; negative or NaN is an error at Render().
   */
  vtkSetMacro(ViewChangeDegrees, double);
  vtkGetMacro(ViewChangeDegrees, double);
  ///@}

  ///@{
  /**
   * Drawing from an OME-Zarr store (see above): with AsynchronousLoading on,
   * a frame does not wait for the bricks of its selection that are not
   * resident. A thread of the store's reads them in the background, the
   * most important first, and until a brick is read the frame draws its
   * stand-in: the same node two levels coarser (texels four times as far
   * apart, 1/64 of them; at most its coarsest, two a side), read at once
   * from the store's level of that stride. So the
   * picture has no hole, each frame shows what has arrived, and the frames
   * that follow refine it until LastBricksLoading is 0; render again until
   * then (a still picture for a file: loop Render() while
   * GetLastBricksLoading() > 0). Off (the default): each frame reads every
   * brick it draws and is the selection's whole picture. LoadingMemoryMB
   * bounds the host memory of bricks read and waiting for upload (the
   * texture budget's counterpart in RAM; the reader waits when it is full);
   * default 256. An image in memory is not affected.
   */
  vtkSetMacro(AsynchronousLoading, vtkTypeBool);
  vtkGetMacro(AsynchronousLoading, vtkTypeBool);
  vtkBooleanMacro(AsynchronousLoading, vtkTypeBool);
  vtkSetClampMacro(LoadingMemoryMB, double, 0.0, 1.0e9);
  vtkGetMacro(LoadingMemoryMB, double);
  ///@}

  ///@{
  /// Error tolerance, a fraction of the data range (0..1); default 0.
  vtkSetClampMacro(ErrorTolerance, double, 0.0, 1.0);
  vtkGetMacro(ErrorTolerance, double);
  ///@}

  ///@{
  /// Region of interest (The Hybrid Octree, section 3.2): bricks near the
  /// sphere of RoiCenter (world) and RoiRadius (world units) are refined
  /// first. Off by default.
  vtkSetMacro(UseRoi, bool);
  vtkGetMacro(UseRoi, bool);
  vtkBooleanMacro(UseRoi, bool);
  vtkSetVector3Macro(RoiCenter, double);
  vtkGetVector3Macro(RoiCenter, double);
  vtkSetClampMacro(RoiRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RoiRadius, double);
  ///@}

  ///@{
  /// The isosurface drawn with the volume: on with ShowSurface, at Isovalue,
  /// with SurfaceColor (RGB 0..1) and SurfaceOpacity (1: opaque, drawn
  /// first with depth; below 1: translucent, sorted into the slabs between
  /// the slices). Off by default.
  vtkSetMacro(ShowSurface, bool);
  vtkGetMacro(ShowSurface, bool);
  vtkBooleanMacro(ShowSurface, bool);
  vtkSetMacro(Isovalue, double);
  vtkGetMacro(Isovalue, double);
  vtkSetVector3Macro(SurfaceColor, double);
  vtkGetVector3Macro(SurfaceColor, double);
  vtkSetClampMacro(SurfaceOpacity, double, 0.0, 1.0);
  vtkGetMacro(SurfaceOpacity, double);
  ///@}

  ///@{
  /**
   * The sample distance (model units) at which a 2D transfer function's
   * alpha is a sample's opacity: VTK's ray caster takes it uncorrected at
   * its own sample distance, so its picture depends on that distance. Below
   * 0 (the default): vtkSmartVolumeMapper's still frames, ParaView's *Volume*
   * (LockSampleDistanceToInputSpacing: half the mean spacing, less below
   * 100 samples a side); give vtkGPUVolumeRayCastMapper's sample distance
   * to match that mapper (with AutoAdjustSampleDistances, the smallest
   * spacing).
   */
  vtkSetMacro(Transfer2DSampleDistance, double);
  vtkGetMacro(Transfer2DSampleDistance, double);
  ///@}

  ///@{
  /**
   * The ray sample distance (model units) of the effects whose
   * classification aliases at one sample a lattice step: the Isosurface
   * blend mode (crossings between consecutive samples) and the 2D transfer
   * function (the table's gradient rows). When it is below the reference
   * spacing d0, their slices are refined to it (LastEffects then has
   * "sample-distance"; src/plan/sampling.rs); other frames keep one slice a
   * lattice step. Below 0 (the default): vtkSmartVolumeMapper's still
   * frames, ParaView's *Volume* (half the mean spacing, less below 100
   * samples a side); 0: never refined; give vtkGPUVolumeRayCastMapper's
   * sample distance to match that mapper.
   */
  vtkSetMacro(SampleDistance, double);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * Volumetric scattering as vtkGPUVolumeRayCastMapper draws it (VTK 9.2;
   * src/transfer/scattering.rs), with the property's Shade on, a light, and
   * Composite blending: VolumetricScatteringBlending in [0, 2] (0 none, the
   * default; 1 a blend of gradient shading and scattered light; 2 scattered
   * light only), GlobalIlluminationReach in [0, 1] (the shadow rays'
   * length), the property's ScatteringAnisotropy (Henyey-Greenstein).
   * ScatteringSampleDistance is VTK's sample distance the model steps by
   * (below 0, the default: vtkSmartVolumeMapper's still frames', ParaView's
   * Volume; give vtkGPUVolumeRayCastMapper's to match that mapper).
   */
  vtkSetClampMacro(VolumetricScatteringBlending, double, 0.0, 2.0);
  vtkGetMacro(VolumetricScatteringBlending, double);
  vtkSetClampMacro(GlobalIlluminationReach, double, 0.0, 1.0);
  vtkGetMacro(GlobalIlluminationReach, double);
  vtkSetMacro(ScatteringSampleDistance, double);
  vtkGetMacro(ScatteringSampleDistance, double);
  ///@}

  ///@{
  /**
   * Points of the hybrid representation (paper 3): with UsePoints on, the
   * mapper also makes points where textures sampled every PointFactor (2, 4
   * or 8) samples underestimate the data by more than PointThreshold (a
   * fraction of the data range), or at the PointBudget largest such errors
   * when PointBudget > 0. The selection then spends BudgetMB on textures
   * and points together: a brick of stride PointFactor takes its points
   * when they remove more error per byte than refining it (6 bytes a point
   * on grids up to 256 samples per axis, 9 beyond). Points are drawn in the
   * slabs between their brick's slices, as squares of whole pixels
   * (PointFootprint 0, default) or Gaussian splats (1), with the opacity
   * that, over the textures, gives the representation's own averaged over
   * the point's voxel (see vtkOpenGLHybridOctreeBrickDrawer). Off by default.
   * Only points where the textures underestimate are made: elsewhere a
   * point could only add opacity the data does not have.
   */
  vtkSetMacro(UsePoints, bool);
  vtkGetMacro(UsePoints, bool);
  vtkBooleanMacro(UsePoints, bool);
  vtkSetClampMacro(PointFactor, int, 2, 8);
  vtkGetMacro(PointFactor, int);
  vtkSetClampMacro(PointThreshold, double, 0.0, 1.0);
  vtkGetMacro(PointThreshold, double);
  vtkSetClampMacro(PointBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(PointBudget, vtkIdType);
  vtkSetClampMacro(PointFootprint, int, 0, 1);
  vtkGetMacro(PointFootprint, int);
  void SetPointFootprintToSquare() { this->SetPointFootprint(0); }
  void SetPointFootprintToGaussian() { this->SetPointFootprint(1); }
  ///@}

  ///@{
  /// Cells per axis of a leaf brick; default 16.
  vtkSetClampMacro(LeafSize, int, 2, 128);
  vtkGetMacro(LeafSize, int);
  ///@}

  ///@{
  /// The component of a multi-component scalar array; -1 (default): none,
  /// allowed only for one-component arrays.
  vtkSetMacro(Component, int);
  vtkGetMacro(Component, int);
  ///@}

  ///@{
  /// Entries of the transfer function table; default 1024.
  vtkSetClampMacro(TableSize, int, 2, 65536);
  vtkGetMacro(TableSize, int);
  ///@}

  ///@{
  /// Statistics of the last frame: bricks drawn, bytes of resident brick
  /// textures and of those uploaded for this frame, slices drawn, surface
  /// triangles drawn, the passes that ran (comma-joined, e.g.
  /// "opaque-surface,volume"), wall-clock milliseconds of Render() from the
  /// end of what was drawn before it to the end of its own drawing (it waits
  /// for OpenGL with glFinish on both sides), the selection's estimated
  /// error (the largest nodal error of the bricks the scalar opacity does
  /// not hide, a fraction of the data range: 0 exactly when every visible
  /// brick draws the full-resolution field; the number `hybrid-octree
  /// render` prints), whether the frame was interactive, and whether it
  /// drew (false after an error).
  vtkGetMacro(LastBricks, int);
  vtkGetMacro(LastTextureBytes, vtkTypeInt64);
  vtkGetMacro(LastUploadedBytes, vtkTypeInt64);
  vtkGetMacro(LastSlices, vtkTypeInt64);
  vtkGetMacro(LastSurfaceTriangles, vtkTypeInt64);
  /// OpenGL draw calls of the last frame's bricks: a run of bricks in
  /// compositing order that share a texture page is one call.
  vtkGetMacro(LastBrickDraws, vtkTypeInt64);
  /// Points drawn in the last frame, and the bytes of the points the selection bought.
  vtkGetMacro(LastPoints, vtkTypeInt64);
  vtkGetMacro(LastPointBytes, vtkTypeInt64);
  const char* GetLastPlan() const { return this->LastPlan.c_str(); }
  /// The last frame's volume effects, comma-joined: "gradient-opacity" (the
  /// property's gradient opacity varies) or "opacity-scale" (it is a
  /// constant other than 1), then "shading", then "cropping", "clipping"
  /// (those on that remove part of the volume); empty for none.
  const char* GetLastEffects() const { return this->LastEffects.c_str(); }
  vtkGetMacro(LastFrameMilliseconds, double);
  vtkGetMacro(LastEstimatedError, double);
  /// NaN samples (no data: transparent) of the image drawn last.
  vtkGetMacro(LastNaNSamples, vtkTypeInt64);
  vtkGetMacro(LastInteractive, bool);
  vtkGetMacro(LastRenderOK, bool);
  /// The last frame's image sample distance (pixels per composited texel
  /// along x and y, 1 at full resolution) and sample spacing factor m (rays
  /// sampled every max(d, m d0); 1: every slice of the lattice).
  vtkGetMacro(LastImageSampleDistance, double);
  vtkGetMacro(LastSampleSpacing, int);
  /// Whether the last frame made its selection (false: it drew a kept one),
  /// the milliseconds that selection took (0 when kept), and the view
  /// importance of the selection it drew ("data", "screen", "visibility",
  /// "both"; see SetViewSelection()). LastUploadedBytes counts the bytes
  /// uploaded in the last frame only.
  vtkGetMacro(LastReselected, bool);
  vtkGetMacro(LastSelectMilliseconds, double);
  const char* GetLastViewSelection() const { return this->LastViewSelection.c_str(); }
  /// A frame within a time (TargetFrameMilliseconds): its target (0 for
  /// an untimed frame), the share of it the drawing aimed at (the target
  /// less what the renderer's frame spends outside this mapper's drawing,
  /// as measured on the frames before, and less the last time-budgeted
  /// selection's search when this frame searches again), the drawing time
  /// the cost model predicted for it, the drawing time measured (from its
  /// DrawList made to the end of its drawing, glFinish;
  /// LastFrameMilliseconds adds the selection and preparation), and the
  /// choice's outcome: "warm-up" (a calibration frame), "met", "full" (the
  /// whole budget fits), "below-fastest" (the coarsest frame is predicted
  /// slower than the target); "" untimed.
  vtkGetMacro(LastTargetMilliseconds, double);
  vtkGetMacro(LastDrawTargetMilliseconds, double);
  vtkGetMacro(LastPredictedMilliseconds, double);
  vtkGetMacro(LastDrawMilliseconds, double);
  const char* GetLastTimeOutcome() const { return this->LastTimeOutcome.c_str(); }
  /// The estimated RMS error of the last frame's selection: the visible
  /// bricks' squared nodal errors over their samples, a fraction of the
  /// data range (the price of a target or a budget, timed or not).
  vtkGetMacro(LastEstimatedRMSError, double);
  /// Drawing from a store (AsynchronousLoading): the last frame's bricks
  /// drawn by a stand-in because they were still loading (0: the selection's
  /// whole picture), and the bytes of samples read from the store since it
  /// was opened, by the frames and in the background, at the frame's end.
  vtkGetMacro(LastBricksLoading, int);
  vtkGetMacro(LastStoreBytesRead, vtkTypeInt64);
  /// Texture bytes of the last frame's bricks whose box lies inside
  /// `bounds` (xmin, xmax, ymin, ymax, zmin, zmax in the image's data
  /// coordinates): where the selection spent its budget.
  vtkTypeInt64 GetLastTextureBytesWithin(const double bounds[6]) const;
  ///@}

  /// Textures resident after the last frame (bricks kept for later frames included).
  vtkTypeInt64 GetResidentTextureCount() const;
  /// The 3D texture pages holding them (a brick pool: each brick in a slot
  /// of a page of its shape) and their bytes, free slots included.
  vtkTypeInt64 GetResidentTexturePageCount() const;
  vtkTypeInt64 GetResidentTexturePageBytes() const;

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  ///@{
  /// The input's bounds; for an image naming an OME-Zarr store (see above)
  /// the store's full-resolution volume's.
  double* GetBounds() VTK_SIZEHINT(6) override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }
  ///@}

  /// Whether the last Render() drew from an OME-Zarr store.
  bool GetLastDrawnFromStore() const;

  /**
   * The CPU compositor's picture of the DrawList the mapper draws for `ren`'s
   * active camera and `vol`'s property (Render() must have succeeded with
   * them): `width x height` premultiplied RGBA floats, rows from the top,
   * into `rgba` (4 components). False after a vtkErrorMacro.
   */
  bool CompositeOnCPU(vtkRenderer* ren, vtkVolume* vol, int width, int height, vtkFloatArray* rgba);

protected:
  vtkHybridOctreeVolumeMapper();
  ~vtkHybridOctreeVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Input, octree, transfer function table, selection and surface up to
  /// date for `ren` and `vol`; false after a vtkErrorMacro.
  bool Prepare(vtkRenderer* ren, vtkVolume* vol);
  /// Whether `ren`'s window asks for an interactive frame rate.
  bool IsInteractive(vtkRenderer* ren) const;
  /// Whether the selection of the last still frame is up to date (an
  /// interactive frame draws it when its textures are resident): made from
  /// `still`, DescribeSelection()'s at BudgetMB, with its `key`.
  bool IsStillSelectionCurrent(
    const vtkHybridOctreeBridge::SelectDescription& still, const std::vector<double>& key) const;
  /// The budget of a frame of `ren`: InteractiveBudgetMB (at most BudgetMB)
  /// when interactive, else BudgetMB.
  double FrameBudgetMB(vtkRenderer* ren) const;

  double BudgetMB = 64.0;
  double InteractiveBudgetMB = 8.0;
  int TexelFormat = TEXELS_AUTO;
  double InteractiveUpdateRate = 1.0;
  bool AutoAdjustSampleDistances = true;
  double TargetFrameMilliseconds = 0.0;
  vtkTypeBool UseJittering = 0;
  double ErrorTolerance = 0.0;
  int ViewSelection = VIEW_SELECTION_BOTH;
  double MinTexelPixels = 0.0;
  double ViewChangeDegrees = 5.0;
  vtkTypeBool AsynchronousLoading = 0;
  double LoadingMemoryMB = 256.0;
  bool UseRoi = false;
  double RoiCenter[3] = { 0.0, 0.0, 0.0 };
  double RoiRadius = 1.0;
  bool ShowSurface = false;
  double Isovalue = 0.0;
  double SurfaceColor[3] = { 1.0, 1.0, 1.0 };
  double SurfaceOpacity = 1.0;
  double Transfer2DSampleDistance = -1.0;
  double SampleDistance = -1.0;
  /// SampleDistance, its default resolved for the current input.
  double ActualSampleDistance() const;
  double VolumetricScatteringBlending = 0.0;
  double GlobalIlluminationReach = 0.0;
  double ScatteringSampleDistance = -1.0;
  bool UsePoints = false;
  int PointFactor = 2;
  double PointThreshold = 0.1;
  vtkIdType PointBudget = 0;
  int PointFootprint = 0;
  int LeafSize = 16;
  int Component = -1;
  int TableSize = 1024;
  int LastBricks = 0;
  vtkTypeInt64 LastTextureBytes = 0;
  vtkTypeInt64 LastUploadedBytes = 0;
  vtkTypeInt64 LastSlices = 0;
  vtkTypeInt64 LastSurfaceTriangles = 0;
  vtkTypeInt64 LastBrickDraws = 0;
  vtkTypeInt64 LastPoints = 0;
  vtkTypeInt64 LastPointBytes = 0;
  std::string LastPlan;
  std::string LastEffects;
  double LastFrameMilliseconds = 0.0;
  double LastEstimatedError = 0.0;
  vtkTypeInt64 LastNaNSamples = 0;
  bool LastInteractive = false;
  bool LastRenderOK = false;
  double LastImageSampleDistance = 1.0;
  int LastSampleSpacing = 1;
  bool LastReselected = false;
  double LastSelectMilliseconds = 0.0;
  std::string LastViewSelection;
  double LastTargetMilliseconds = 0.0;
  double LastDrawTargetMilliseconds = 0.0;
  double LastPredictedMilliseconds = 0.0;
  double LastDrawMilliseconds = 0.0;
  std::string LastTimeOutcome;
  double LastEstimatedRMSError = 0.0;
  int LastBricksLoading = 0;
  vtkTypeInt64 LastStoreBytesRead = 0;

private:
  vtkHybridOctreeVolumeMapper(const vtkHybridOctreeVolumeMapper&) = delete;
#ifndef __VTK_WRAP__
  /// The checked input image and its scalars (nullptr after a vtkErrorMacro).
  vtkDataArray* CheckInput(vtkImageData*& image);
  bool UpdateOctree(vtkImageData* image, vtkDataArray* scalars);
  /// UpdateOctree() for an image naming the store at `path` with the full
  /// resolution `dims`, `spacing`, `origin`.
  bool UpdateOctreeFromStore(const std::string& path, const double dims[3], const double spacing[3],
    const double origin[3], vtkDataArray* scalars);
  /// False after a vtkErrorMacro when a setting needs every sample in memory.
  bool CheckStoreSettings(vtkVolumeProperty* property);
  void UpdateModelMatrix(vtkImageData* image, vtkVolume* vol);
  bool UpdateTransferFunction(vtkVolumeProperty* property);
  bool UpdatePoints();
  /// The points' shades for the current transfer function table.
  bool UpdatePointShades();
  /// The selection of a still (BudgetMB) or an interactive frame
  /// (InteractiveBudgetMB) up to date and chosen for this frame.
  bool UpdateSelection(vtkVolumeProperty* property, bool interactive);
  /// Makes the selection of `select` (with `key`) for the still or the
  /// interactive slot, under `timer`'s time-budgeted search when one is given.
  bool Reselect(bool interactive, vtkHybridOctreeBridge::SelectDescription& select,
    const std::vector<double>& key, vtkHybridOctreeBridge::FrameTimer* timer);
  /// The frame-time target of a frame of `ren` in ms (0: untimed);
  /// false after a vtkErrorMacro (a bad TargetFrameMilliseconds).
  bool FrameTarget(vtkRenderer* ren, vtkVolume* vol, double& targetMs) const;
  /// Learns what the renderer's last frame spent outside this mapper's
  /// drawing and selection (vtkRenderer::GetLastRenderTimeInSeconds), when
  /// that frame was timed here.
  void ObserveFrameOverhead(vtkRenderer* ren);
  /// The selection of a frame within `targetMs`, drawn as an interactive
  /// frame is (`fast`) or exactly, each way with its own cost model, up to
  /// date and chosen for this frame; `followView`: made again when the view
  /// moved past ViewChangeDegrees (a still window's frames).
  bool UpdateTimedSelection(
    vtkVolumeProperty* property, bool fast, bool followView, double targetMs);
  /// Feeds the frame just drawn (`drawMs`) to its cost model.
  void ObserveTimedFrame(bool interactive, double drawMs);
  /// This frame's selection: the still one when it is current and `ren`
  /// is interactive, else UpdateSelection()'s.
  bool ChooseSelection(vtkRenderer* ren, vtkVolume* vol);
  /// What the selection of `budgetMB` is made from, with its cache key (the
  /// camera is not in it: see IsViewCurrent()).
  vtkHybridOctreeBridge::SelectDescription DescribeSelection(
    vtkVolumeProperty* property, double budgetMB, std::vector<double>& key) const;
  /// The view of `ren` a selection is made for (DescribeSelection() leaves
  /// it at Data); false after a vtkErrorMacro (a bad ViewChangeDegrees).
  bool DescribeView(vtkRenderer* ren, vtkVolumeProperty* property);
  /// Whether a selection made for the view `made`, whose view importance
  /// `applied` ran, still serves this frame's view: always when "data" ran,
  /// else when the view moved at most ViewChangeDegrees and the viewport
  /// kept its size.
  bool IsViewCurrent(
    const vtkHybridOctreeBridge::ViewDescription& made, const std::string& applied) const;
  bool UpdateSurface();
  /// The active camera in the octree's frame (through the inverse model matrix).
  vtkHybridOctreeBridge::CameraDescription ModelCamera(vtkRenderer* ren) const;
  bool GetFrameDrawList(vtkRenderer* ren, vtkHybridOctreeBridge::DrawList& list);
  /// Drawing from a store with AsynchronousLoading: asks the store's reader
  /// for the frame's bricks not resident and has those not read yet drawn by
  /// stand-ins; otherwise the frame draws its selection's own bricks.
  bool PlanLoading();
  /// Executes `list`: textures, table, opaque surface, slices and batches;
  /// interactive: resident textures, bricks ray-marched at `level` of
  /// vtkHybridOctreeInteractiveReduction, a translucent surface per brick.
  bool DrawFrame(vtkRenderer* ren, vtkOpenGLRenderWindow* window, vtkOpenGLCamera* camera,
    const vtkHybridOctreeBridge::DrawList& list, bool interactive, int level);
  /// The textures of `list`'s bricks: resident ones reused, the rest uploaded
  /// within the budget the points bought leave; each brick's block ranges
  /// into `geometry`.
  bool AcquireBrickTextures(vtkOpenGLRenderWindow* window,
    const vtkHybridOctreeBridge::DrawList& list,
    std::vector<const vtkOpenGLHybridOctreeBrickResident*>& textures,
    vtkHybridOctreeBridge::BrickGeometryInput& geometry);
  /// The transfer function table's texture, uploaded when it changed.
  bool UploadTable(vtkOpenGLRenderWindow* window);
  /// The frame's vertices from the core (plan::draw_geometry) handed to the
  /// drawer; the bricks, slices, triangles and points drawn.
  bool MakeBrickGeometry(const vtkHybridOctreeBridge::DrawList& list,
    const vtkHybridOctreeBridge::CameraDescription& cam, bool interactive, double sampleSpacing,
    vtkHybridOctreeBridge::BrickGeometryInput& geometry);
  /// The opaque surface pass, depth written, before the volume.
  bool DrawOpaqueSurface(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
    const vtkHybridOctreeBridge::CameraDescription& cam,
    const vtkHybridOctreeBridge::DrawList& list, const double rgba[4]);
  /// The bricks back to front into the float target, then blended over the
  /// window; interactive frames draw a translucent surface brick by brick.
  bool DrawBricks(vtkRenderer* ren, vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
    const vtkHybridOctreeBridge::CameraDescription& cam,
    const vtkHybridOctreeBridge::DrawList& list,
    const std::vector<const vtkOpenGLHybridOctreeBrickResident*>& textures, bool interactive,
    double imageSampleDistance, double sampleSpacing, const double rgba[4]);
  /// Draws the translucent triangles between brick i - 1's volume and brick
  /// i's into the bound float target (vtkOpenGLHybridOctreeSurfaceDrawer::
  /// GetTrianglesBefore()); returns how many.
  std::size_t DrawSurfaceBefore(vtkOpenGLRenderWindow* window, std::size_t i);
  /// Whether translucent triangles lie between brick i - 1's volume and brick i's.
  bool HasSurfaceBefore(std::size_t i) const;
  /// The normalized device box (xmin, xmax, ymin, ymax) of the boxes
  /// `bounds[6i .. 6i+6]` (model coordinates) for the model-to-clip matrix
  /// `mcdc`; all of it when one reaches behind the eye.
  void ScreenRegion(vtkMatrix4x4* mcdc, const std::vector<double>& bounds, double region[4]) const;
  /// Whether the transfer function is more opaque above the isovalue than below it.
  bool IsInsideOpaque() const;
#endif
  void operator=(const vtkHybridOctreeVolumeMapper&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
