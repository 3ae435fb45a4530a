/**
 * @file   vtkHybridOctreeBridge.h
 * @brief  Plain C++ view of the Rust Hybrid Octree core (private to the module).
 *
 * The VTK classes of this module call the Rust crate only through this
 * header. It holds no cxx type: vtkHybridOctreeBridge.cxx is the only file
 * that includes the cxx-generated `hybrid-octree/src/ffi/mod.rs.h`, converts
 * between these structs and the bridge's, and turns every `rust::Error`
 * (a `std::exception`) into an error string the caller reports with
 * vtkErrorMacro. The enums are the bridge's own (vtkHybridOctreeBridgeEnums.h).
 *
 * Volume samples cross borrowed: Build() and IntegrateSurface() read the
 * caller's buffer while they run and keep no pointer to it. Large outputs
 * go the other way into the caller's memory (a VTK array's WritePointer(),
 * a texture's staging buffer): the caller sizes it from a summary and the
 * Rust core writes into it, nothing is copied twice.
 */
#ifndef vtkHybridOctreeBridge_h
#define vtkHybridOctreeBridge_h

#include "vtkHybridOctreeBridgeEnums.h"
#include "vtkType.h" // vtkIdType

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkPiecewiseFunction;

namespace vtkHybridOctreeBridge
{

/// Scalar types the Rust core reads (VTK_UNSIGNED_CHAR -> U8, ...).
using ScalarType = hybrid_octree::ScalarType;

/// Which isosurface the Hybrid Octree keeps: Discretized (DiscMC, coplanar
/// facets merged, lossless) or Interpolated (classic Marching Cubes).
using SurfaceMode = hybrid_octree::SurfaceMode;

/// The owner of one Rust handle of `Object`, defined in
/// vtkHybridOctreeBridge.cxx (the only file that sees cxx types).
template <class Object>
struct RustHandle;

/// Layout of a borrowed image: point dims, spacing, origin of the first
/// sample, components per tuple and the chosen component (-1: none, allowed
/// only for 1-component arrays).
struct GridDescription
{
  ScalarType Type = ScalarType::F32;
  std::size_t Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  std::size_t Components = 1;
  int Component = -1;
};

/// Summary of a built Volume Octree (see OctreeSummary in src/ffi/mod.rs).
struct OctreeSummary
{
  std::uint64_t NodeCount = 0;
  std::uint64_t TerminalCount = 0;
  std::uint64_t HomogeneousCount = 0;
  std::uint32_t Levels = 0;
  std::uint32_t LeafSize = 0;
  std::uint32_t RootSize = 0;
  std::uint64_t OctreeBytes = 0;
  std::uint64_t InputBytes = 0;
  double BuildMilliseconds = 0.0;
  double ValueMin = 0.0;
  double ValueMax = 0.0;
  std::uint64_t NaNSamples = 0; ///< NaN samples: no data (transparent, outside every isosurface)
};

/// The boxes of an octree cut, one entry per node, in world coordinates.
/// `Bounds` holds 6 values per node in VTK order (xmin, xmax, ymin, ymax,
/// zmin, zmax); every other vector holds one value per node.
struct CutBoxes
{
  std::vector<double> Bounds;
  std::vector<std::uint32_t> NodeId; ///< id in the level-by-level numbering
  std::vector<std::uint32_t> Level;
  std::vector<float> NodalError; ///< E_0 normalised by the data range
  std::vector<double> Min;
  std::vector<double> Max;

  std::size_t GetNumberOfBoxes() const { return this->Level.size(); }
};

/// An isosurface integrated into a HybridOctree (see SurfaceSummary in
/// src/ffi/mod.rs): its sizes, for the caller's arrays, and what extracting
/// it took. Polygons are triangles: the merged coplanar faces triangulated
/// with their own vertices.
struct SurfaceSummary
{
  std::size_t Vertices = 0;
  std::size_t Polygons = 0;
  std::size_t Connectivity = 0;            ///< 3 per polygon
  std::uint64_t Faces = 0;                 ///< merged coplanar faces
  std::uint64_t Triangles = 0;             ///< triangles in the output (= Polygons)
  std::uint64_t UncompressedTriangles = 0; ///< before coplanar facets are merged
  std::uint64_t BoundaryEdges = 0;         ///< edges of one polygon only (0: closed surface)
  double ExtractMilliseconds = 0.0;
  double CompressMilliseconds = 0.0;
  double DistanceMean = -1.0; ///< DiscMC to interpolated surface, voxels; -1: not measured
  double DistanceMax = -1.0;
};

/**
 * The caller's arrays a surface mesh is written into, world coordinates,
 * sized from the SurfaceSummary: `Points` and `Normals` 3 values per vertex
 * (unit normals, from values >= isovalue towards values below); polygon `i`
 * uses `Connectivity[Offsets[i] .. Offsets[i + 1]]` (`Polygons + 1`
 * offsets from 0); per polygon the terminal node holding it (level-by-level
 * id), its level (0 = root) and the merged coplanar face it belongs to.
 */
struct SurfaceMeshBuffers
{
  double* Points = nullptr;
  float* Normals = nullptr;
  vtkIdType* Offsets = nullptr;
  vtkIdType* Connectivity = nullptr;
  int* PolygonNode = nullptr;
  int* PolygonLevel = nullptr;
  vtkIdType* PolygonFace = nullptr;
};

/// VTK's cropping and clipping planes (see RegionDesc in src/ffi/mod.rs), in
/// the octree's frame (the image's origin + index * spacing): a sample is
/// kept when the cropping's region flags keep its region and it is on the
/// kept side, normal . (x - origin) >= 0, of every plane.
struct RegionDescription
{
  bool Cropping = false; ///< vtkVolumeMapper::GetCropping(); off: planes and flags are not read
  double CroppingPlanes[6] = { 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0 };                              ///< xmin, xmax, ymin, ymax, zmin, zmax
  std::uint32_t CroppingFlags = 0x2000; ///< bit i + 3 j + 9 k keeps region (i, j, k)
  /// 6 per plane: origin x, y, z, normal x, y, z; at most 8 planes.
  std::vector<double> ClippingPlanes;
};

/// A camera as vtkCamera describes it.
struct CameraDescription
{
  double Position[3] = { 0.0, 0.0, 1.0 };
  double FocalPoint[3] = { 0.0, 0.0, 0.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };
  bool Parallel = false;
  double ParallelScale = 1.0; ///< half the view height, world units
  double ViewAngle = 30.0;    ///< full vertical angle, degrees
};

/**
 * The view a selection weighs nodes by (see ViewDesc in src/ffi/mod.rs and
 * src/ffi/view.rs): what the camera sees of each node on the viewport.
 */
struct ViewDescription
{
  /// 0 data (the camera and viewport are checked, not read), 1 screen
  /// space, 2 visibility, 3 both (vtkHybridOctreeVolumeMapper's VIEW_SELECTION_*).
  int ViewSelection = 0;
  CameraDescription Camera;           ///< in the octree's frame (the DrawList's)
  std::size_t Viewport[2] = { 1, 1 }; ///< pixels, at least 1 x 1
  double MinTexelPixels = 0.0;        ///< refinement stops below texels this small (>= 0; 0 never)
  double SurfaceOpacity = 0.0;        ///< the isosurface drawn (HasIsovalue): what it hides
  double OpacityUnitDistance = 1.0;   ///< OpacityPoints' distance (ScalarOpacityUnitDistance), > 0
};

/// What to select for drawing (see SelectDesc in src/ffi/mod.rs).
struct SelectDescription
{
  std::size_t BudgetBytes = 0; ///< texture budget (f32 texels), > 0
  double Tolerance = 0.0;      ///< error tolerance, fraction of the data range, >= 0
  bool HasRoi = false;
  double RoiCenter[3] = { 0.0, 0.0, 0.0 }; ///< world coordinates
  double RoiRadius = 1.0; ///< world units (divided by the smallest spacing in index space)
  /// The scalar opacity, (value, opacity) pairs flattened (see OpacityPoints());
  /// nodes over whose range it is 0 get no texture. Empty: every node shows.
  std::vector<double> OpacityPoints;
  bool HasIsovalue = false; ///< nodes holding the isovalue always show
  double Isovalue = 0.0;
  /// Count one border texel per side of each brick in its bytes (a shaded
  /// volume's gradient reads them).
  bool GradientBorder = false;
  /// vtkVolumeMapper::BlendModes value, 0 (composite) to 6 (slice); it
  /// changes which nodes show and the texels of coarse MIP/MinIP bricks.
  int BlendMode = 0;
  /// vtkVolumeMapper's AverageIPScalarRange: the values an average counts.
  double AverageRange[2] = { -1.0e300, 1.0e300 };
  /// The brick texel format (src/plan/texel_format.rs): 0 auto (the data's
  /// own width: 8-bit data as R8, 16-bit as R16, the rest R32F), 1 float32,
  /// 2 float16, 3 unorm16, 4 unorm8. The budget counts its bytes.
  int TexelFormat = 0;
  /// The isosurface values of blend mode 5 (1 to 16).
  std::vector<double> IsosurfaceValues;
  /// vtkVolumeProperty's GradientOpacity as VTK's GPU ray caster reads it
  /// (OpacityPoints() of it: magnitudes per mean voxel spacing, VTK's
  /// convention), (magnitude, opacity) pairs flattened;
  /// empty: none. One that is 0 everywhere hides every node; one that is
  /// not constant counts the gradient border as GradientBorder does.
  std::vector<double> GradientOpacityPoints;
  /// Cropping and clipping planes: nodes whose box they remove get no
  /// texture (counted as skipped); the selection's DrawLists keep only their samples.
  RegionDescription Region;
  /// vtkVolumeProperty's TransferFunction2D in TF_2D mode (Composite): its
  /// dimensions (0, 0: none), its texels (4 floats each, row-major, x the
  /// scalar value, y the gradient magnitude) and the data array's finite
  /// range its x axis spans (the y axis is VTK's, see src/transfer/transfer2d.rs).
  /// Nodes over whose range it is 0 at every gradient are skipped.
  std::size_t Transfer2DSize[2] = { 0, 0 };
  std::vector<float> Transfer2DRGBA;
  double Transfer2DRange[2] = { 0.0, 1.0 };
  /// The plane of blend mode 6 (vtkVolumeProperty's SliceFunction, a
  /// vtkPlane) in the octree's frame: origin x, y, z, normal x, y, z. Only
  /// nodes whose box it cuts get a texture (src/plan/slice.rs).
  double SlicePlane[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 1.0 };
  /// The view the selection is made for (default: Data, no view).
  ViewDescription View;
};

/// The volume's shading (see ShadingDesc in src/ffi/mod.rs): vtkVolumeProperty's
/// Shade, Ambient, Diffuse, Specular, SpecularPower and the renderer's lights.
struct ShadingDescription
{
  bool Shade = false; ///< off: nothing else is read
  double Ambient = 0.1;
  double Diffuse = 0.7;
  double Specular = 0.2;
  double SpecularPower = 10.0;
  bool TwoSided = true; ///< vtkRenderer's TwoSidedLighting
  /// VTK's default lighting (one headlight of intensity 1): the first light's
  /// diffuse and specular colours are used, its direction and ambient are not.
  bool Headlight = true;
  std::vector<double> LightDirections; ///< 3 per light: focal point - position, world
  std::vector<double> LightAmbient;    ///< 3 per light: colour x intensity
  std::vector<double> LightDiffuse;    ///< 3 per light: colour x intensity
  std::vector<double> LightSpecular;   ///< 3 per light: colour x intensity
  int LightsOn = 1; ///< the renderer's switched-on lights (0: one black light is described)
};

/// Volumetric scattering (see ScatteringDesc in src/ffi/mod.rs): the mapper's
/// VolumetricScatteringBlending [0, 2] and GlobalIlluminationReach [0, 1],
/// vtkVolumeProperty's ScatteringAnisotropy [-1, 1], the headlight's ambient
/// colour x intensity, VTK's sample distance (0: the reference spacing).
struct ScatteringDescription
{
  double Blending = 0.0;
  double Reach = 0.0;
  double Anisotropy = 0.0;
  double HeadlightAmbient[3] = { 1.0, 1.0, 1.0 };
  double SampleDistance = 0.0;
};

/// What the brick shader's HO_SCATTERING variant reads (see
/// ScatteringFrameDesc in src/ffi/mod.rs and src/render/scattering.rs).
struct ScatteringFrame
{
  double Blending = 0.0;
  double Anisotropy = 0.0;
  double HeadlightAmbient[3] = { 0.0, 0.0, 0.0 };
  double GradientScale = 0.0;     ///< 2 / (hi - lo): VTK's gradient length per world gradient
  double TextureCorner[3] = {};   ///< octree frame position of VTK's texture point 0
  double TextureSize[3] = {};     ///< the texture cube's size
  double Extent = 0.0;            ///< the shadow rays' reach, texture units
  double Distance = 0.0;          ///< VTK's sample distance d
  double ToVtk = 1.0;             ///< d / d0
  std::size_t ShadowDims[3] = {}; ///< the shadow volume's points per axis
  double ShadowScale[3] = {};     ///< its texture coordinate: t * scale + shift
  double ShadowShift[3] = {};
  std::size_t MaxSteps = 0; ///< the most samples a shadow ray takes
};

/// Summary of a selection (see SelectionSummary in src/ffi/mod.rs).
struct SelectionSummary
{
  std::uint64_t Bricks = 0;
  std::uint64_t TextureBytes = 0;
  std::uint64_t BudgetBytes = 0;
  double EstimatedError = 0.0; ///< largest e_p of the visible bricks, fraction of the data range
  /// The visible bricks' squared nodal errors over their samples, a
  /// fraction of the data range: what a picture's RMS error is estimated from.
  double EstimatedRmsError = 0.0;
  std::uint64_t Skipped = 0;    ///< nodes left out as fully transparent
  std::string Warning;          ///< empty when none
  std::uint64_t Points = 0;     ///< points of the hybrid representation bought (0 without)
  std::uint64_t PointBytes = 0; ///< their bytes, counted in the budget with the textures
  /// The view importance that ran: "data", "screen", "visibility" or "both"
  /// (the one asked for, without visibility where it does not apply).
  std::string ViewSelection;
};

/**
 * A DrawList for one camera (see DrawListOutput in src/ffi/mod.rs): the volume
 * bricks in drawing order, back to front. Per brick `i`: `Brick[i]` (its
 * index in the selection, for GetBrickTexels()), `NodeId[i]`,
 * `Bounds[6i .. 6i+6]` (world, VTK order), `Texels[3i .. 3i+3]`,
 * `Stride[i]` (cells between texels), `SliceSpacing[i]` (d, world),
 * `OpacityRatio[i]` (d / d0: a' = 1 - (1 - a)^(d/d0)), and its slices
 * `Slices[SliceOffsets[i] .. SliceOffsets[i+1]]`: view depths back to front,
 * the plane of depth z being {x : (x - camera position) . Forward = z}.
 * Texture coordinate along axis a, in texels: (x - min_a) / (Stride * spacing_a),
 * clamped to [0, texels - 1].
 *
 * With a translucent surface, brick `i`'s triangle batches are
 * `BatchOffsets[i] .. BatchOffsets[i+1]`, back to front: batch `k` draws the
 * surface triangles `BatchFirst[k] .. BatchEnd[k]` (polygon ids of
 * HybridOctree::GetSurfaceTriangles()) in slab `BatchSlab[k]` (between slices s-1 and s),
 * clipped to view depths `BatchClip[2k] <= depth < BatchClip[2k+1]`
 * (infinite: no clip needed). With an opaque surface, triangles
 * `0 .. OpaqueTriangles` are drawn first (depth write), then the bricks.
 */
struct DrawList
{
  std::vector<std::size_t> Brick;
  std::vector<std::uint32_t> NodeId;
  std::vector<double> Bounds;
  std::vector<std::size_t> Texels;
  std::vector<std::size_t> Stride;
  std::vector<double> SliceSpacing;
  std::vector<double> OpacityRatio;
  std::vector<std::size_t> SliceOffsets;
  std::vector<double> Slices;
  std::string Passes; ///< comma-joined, e.g. "volume"; empty without bricks
  /// The volume's effects in order, comma-joined: "transfer-2d", "gradient-opacity" or
  /// "opacity-scale", then "shading", then what removes samples,
  /// "cropping", "clipping"; empty for none.
  std::string Effects;
  /// The samples take gradients (shading or gradient opacity): the brick
  /// textures carry the gradient border (GetBrickTexelsBordered()).
  bool Gradients = false;
  /// The brick textures carry one border texel per side
  /// (GetBrickTexelsBordered()): with gradients, or Isosurface blending.
  bool Bordered = false;
  /// The volume's blend mode as drawn (vtkVolumeMapper::BlendModes).
  int BlendMode = 0;
  bool Shading = false; ///< the samples are shaded
  /// The brick textures' texel format as resolved (1 float32: R32F, 2
  /// float16: R16F, 3 unorm16: R16, 4 unorm8: R8; GetBrickTexelsEncoded())
  /// and its decoding: a texture read t is the value TexelBias + TexelScale t.
  int TexelFormat = 1;
  double TexelScale = 1.0;
  double TexelBias = 0.0;
  std::size_t TexelBytes = 4; ///< bytes of one texel on the GPU (all channels)
  /// With "rgba-components" (an RGBA volume; TexelFormat 4 for RGBA8, 1 for
  /// RGBA32F, TexelScale decoding channel r, the gradient's): VTK 9.2's
  /// reading of a texture read t: channels r, g, b as s = scale t + bias,
  /// the three scales, then the three biases; then channel a as the opacity
  /// function's value v' = scale t + bias. Empty otherwise.
  std::vector<double> RgbaReading;
  double OpacityScale = 1.0; ///< every opacity times this before the correction
  /// With "gradient-opacity": the function at magnitudes k End / (n - 1),
  /// k = 0 .. n (data units per model unit), held past the ends; else empty.
  std::vector<float> GradientOpacityTable;
  double GradientOpacityEnd = 0.0;
  /// With "transfer-2d" (the first effect): the table's axes, the scalar
  /// range lo, hi and the gradient magnitude of its last row (data units per
  /// model unit); zeros otherwise.
  double Transfer2DAxes[3] = { 0.0, 0.0, 0.0 };
  /// The cropping and planes that act (those that remove part of the volume).
  RegionDescription Region;
  /// Under the Slice blend mode ("volume-slice"): its plane, origin x, y, z,
  /// normal x, y, z; empty otherwise.
  std::vector<double> SlicePlane;
  double ReferenceSpacing = 0.0;          ///< d0, world units
  double Forward[3] = { 0.0, 0.0, -1.0 }; ///< unit view direction
  std::vector<std::size_t> BatchOffsets;  ///< bricks + 1 values
  std::vector<std::size_t> BatchSlab;
  std::vector<std::uint32_t> BatchFirst;
  std::vector<std::uint32_t> BatchEnd;
  std::vector<double> BatchClip; ///< 2 per batch
  std::size_t OpaqueTriangles = 0;
  /// Points (a selection made with points; empty lists otherwise): brick i's
  /// buckets are BucketOffsets[i] .. BucketOffsets[i + 1] (bricks + 1
  /// values), bucket k lies in slab BucketSlab[k] of its brick (as
  /// BatchSlab) and draws the points BucketPoints[BucketPointOffsets[k] ..
  /// BucketPointOffsets[k + 1]] (ids into HybridOctree::GetPointsDrawing()'s arrays).
  std::vector<std::size_t> BucketOffsets;
  std::vector<std::size_t> BucketSlab;
  std::vector<std::size_t> BucketPointOffsets;
  std::vector<std::uint32_t> BucketPoints;

  std::size_t GetNumberOfBricks() const { return this->Brick.size(); }
};

/// What Selection::Composite() draws besides the bricks' texels.
struct CompositeScene
{
  std::vector<double> ColorPoints;   ///< (value, r, g, b) flattened
  std::vector<double> OpacityPoints; ///< (value, opacity) flattened
  /// The octree's isosurface's colour and opacity; opacity 0 hides it.
  double SurfaceRGBA[4] = { 1.0, 1.0, 1.0, 0.0 };
  bool GaussianPoints = false; ///< footprint of the selection's points: Gaussian, else square
};

/// Points of the hybrid representation: how many, and what making them took.
struct PointsSummary
{
  std::size_t Points = 0;
  std::size_t Factor = 0;         ///< the low-resolution stride the points complete
  std::size_t PointBytes = 0;     ///< all the points as stored
  std::size_t Underestimates = 0; ///< points with e > 0
  double GenerateMs = 0.0;
};

/// Points of the hybrid representation as the renderer draws them.
struct PointsDrawing
{
  std::vector<float> Position; ///< 3 per point: the sample's world position (the grid's frame)
  std::vector<float> Value;    ///< original value f
  std::vector<float> Error;    ///< e = f - T_f: the textures show f - e there
  std::size_t Factor = 0;      ///< the texture stride the points complete
  std::size_t PointBytes = 0;  ///< all the points as stored
};

/**
 * What the OpenGL mapper draws of `List` for one camera, computed by the Rust
 * core (src/plan/draw_geometry, the CPU compositor's rules; see
 * GetBrickGeometry()). `Eye` and `ViewUp` are the camera in the list's frame,
 * `Spacing` the image's, `Table` the transfer function's table (4 floats a
 * cell over [TableLo, TableHi], as the shader samples it), `BlockRanges[i]`
 * brick i's block value ranges (MeasureBlockRanges() of its texels). With
 * `SurfaceVertices` and `SurfaceTriangles` (the translucent surface as
 * uploaded: 6 floats a vertex, position and normal; 3 vertex ids a
 * triangle) the list's batches are drawn in the slabs; with
 * `PointPositions` (3 a point) and `PointShades` (4 a point: straight colour,
 * opacity a_p) its point buckets are.
 */
struct BrickGeometryInput
{
  const DrawList* List = nullptr;
  double Eye[3] = { 0.0, 0.0, 0.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  const std::vector<float>* Table = nullptr;
  double TableLo = 0.0;
  double TableHi = 1.0;
  std::vector<const std::vector<float>*> BlockRanges;
  const std::vector<float>* SurfaceVertices = nullptr;
  const std::vector<unsigned int>* SurfaceTriangles = nullptr;
  const std::vector<float>* PointPositions = nullptr;
  const std::vector<float>* PointShades = nullptr;
  bool GaussianPoints = false;
};

/**
 * The vertices of every brick of a DrawList (see BrickGeometryOutput in
 * src/ffi/mod.rs): `VertexFloats` floats at `Vertices`, 11 a vertex
 * (position, normal, clip interval near and far, primitive kind: 0 slice, 1
 * surface triangle, 2 ray-marched box, 3 square point, 4 Gaussian point;
 * point opacity; the index of its brick in the list), kept by `Storage` (the Rust core's own
 * buffer, not copied); brick i's vertices `BrickFirst[i] .. BrickFirst[i + 1]`, `RayMarched[i]`
 * (drawn as its box), `Drawn[i]` (some block visible), `Boxes[6i .. 6i+6]` (the box its slices are
 * clipped to, VTK order), `PointUp` (a point quad's up).
 */
struct BrickGeometry
{
  const float* Vertices = nullptr;
  std::size_t VertexFloats = 0;
  std::shared_ptr<const void> Storage;
  std::vector<std::size_t> BrickFirst;
  std::vector<char> RayMarched;
  std::vector<char> Drawn;
  std::vector<double> Boxes;
  float PointUp[3] = { 0.0f, 1.0f, 0.0f };
  std::size_t TrianglesPlaced = 0; ///< surface triangle copies (one per slab drawn in)
  std::size_t PointsPlaced = 0;
};

/**
 * The OpenGL mapper's vertices of `input.List` into `geometry` (replaced):
 * per brick its slices clipped to the box of its visible blocks, the
 * surface triangles and points in the slabs between them, or, with none,
 * its ray-marched box. False and `error` on failure (inputs that do not
 * match the list).
 */
bool GetBrickGeometry(const BrickGeometryInput& input, BrickGeometry& geometry, std::string& error);

/**
 * A brick's block value ranges (per block of 4^3 cells its texels' [min,
 * max], NaN left out) from its `count` texels at `texels` (`dims` per axis,
 * x fastest), into `ranges` (resized): measured once, when the texels are
 * made. False and `error` on failure.
 */
bool MeasureBlockRanges(const float* texels, std::size_t count, const std::size_t dims[3],
  std::vector<float>& ranges, std::string& error);

/**
 * The nodes of a scalar opacity function as (value, opacity) pairs,
 * flattened, opacities clamped to [0, 1]. With clamping off, the opacity
 * steps to 0 outside the nodes (a 0 point is added at each end). Midpoint and
 * sharpness are not carried: the function is taken piecewise linear, which
 * leaves the "zero over a range" test unchanged except for sharpness-1 steps.
 */
std::vector<double> OpacityPoints(vtkPiecewiseFunction* function);

/**
 * How far the view moved from camera `a` to camera `b` around `centre`, in
 * degrees (src/plan/select/view.rs): the turn about `centre`, the change of
 * aim or the zoom (|ln| of the distance or parallel scale ratio, in
 * radians), whichever is larger. False and `error` for a camera that is not one.
 */
bool ViewChangeDegrees(const CameraDescription& a, const CameraDescription& b,
  const double centre[3], double& degrees, std::string& error);

class Selection;
struct PointsOptions;

/// What an open OME-Zarr image holds (see StoreSummary in src/ffi/mod.rs).
struct StoreSummary
{
  std::size_t Dims[3] = { 0, 0, 0 }; ///< samples per axis of the full resolution (x, y, z)
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  ScalarType Type = ScalarType::F32;
  /// Resolution levels: level p holds the samples min(i 2^p, n - 1) per axis.
  std::size_t Levels = 0;
  std::vector<std::size_t> LevelDims; ///< 3 a level (x, y, z)
  bool HasOctree = false; ///< written by hybrid-octree convert: the Volume Octree is stored
  std::string Name;
  std::string Version;  ///< the NGFF version its metadata declares
  std::string Warnings; ///< what the reader left out or assumed ("" when nothing)
};

/// A frame's loading from a store in the background (Selection::PlanLoading(); see
/// LoadingSummary in src/ffi/mod.rs).
struct LoadingSummary
{
  std::size_t StandIns = 0;     ///< bricks drawn by a stand-in: still loading
  std::size_t Loaded = 0;       ///< bricks read in the background, waiting for upload
  std::size_t Queued = 0;       ///< bricks the background reader has still to read
  std::size_t WaitingBytes = 0; ///< bytes of the read bricks waiting for upload
  std::uint64_t BytesRead = 0;  ///< bytes of samples read from the store so far
};

/**
 * An open OME-Zarr image on disk (it owns the Rust handle; see
 * src/store/open.rs): its summary, its levels read into the caller's
 * memory, the Hybrid Octree made from it (HybridOctree::BuildFromStore())
 * and brick texels read from it (Selection::GetBrickTexelsFromStore()).
 */
class OmeZarrStore
{
public:
  explicit OmeZarrStore(std::unique_ptr<RustHandle<OmeZarrStore>> handle);
  ~OmeZarrStore();
  OmeZarrStore(const OmeZarrStore&) = delete;
  OmeZarrStore& operator=(const OmeZarrStore&) = delete;

  /// Opens the OME-Zarr image in the folder `path` (NGFF 0.4 or 0.5).
  /// nullptr and `error` (the core's message, naming the fix) on failure.
  static std::unique_ptr<OmeZarrStore> Open(const std::string& path, std::string& error);

  /// Its dims, spacing, origin, type, levels, name. False and `error` on failure.
  bool GetSummary(StoreSummary& summary, std::string& error) const;

  /**
   * The closed box `lo ..= hi` (level indices, x, y, z) of level `level`
   * into the caller's `byteCount` bytes at `bytes` (x fastest, native byte
   * order, the store's scalar type). False and `error` on failure (a box
   * outside the level, a missing or damaged chunk, too much memory).
   */
  bool ReadLevel(std::size_t level, const std::size_t lo[3], const std::size_t hi[3], void* bytes,
    std::size_t byteCount, std::string& error) const;

  /// Bytes of samples read from the store so far: brick texels, by the frames and by the
  /// background reader of Selection::PlanLoading().
  std::uint64_t GetBytesRead() const;

private:
  friend class HybridOctree;
  friend class Selection;
  std::unique_ptr<RustHandle<OmeZarrStore>> Impl;
};

/**
 * The Hybrid Octree owned on the C++ side (it owns the Rust handle): the
 * Volume Octree, and the isosurface and points integrated into it.
 */
class HybridOctree
{
public:
  explicit HybridOctree(std::unique_ptr<RustHandle<HybridOctree>> handle);
  ~HybridOctree();
  HybridOctree(const HybridOctree&) = delete;
  HybridOctree& operator=(const HybridOctree&) = delete;

  /**
   * Builds the Volume Octree of `byteCount` bytes at `bytes` laid out as
   * `grid`, with leaf bricks of `leafSize` cells per axis (no surface, no
   * points yet). Returns nullptr and sets `error` to the core's message on
   * failure.
   */
  static std::unique_ptr<HybridOctree> Build(const void* bytes, std::size_t byteCount,
    const GridDescription& grid, unsigned int leafSize, std::string& error);

  /**
   * Build() reporting progress: `progress(fraction)` is called on this
   * thread between chunks of leaf bricks, fractions increasing to 1; its
   * false cancels the build (nullptr, `error` names the cancel, nothing is
   * kept). An exception from `progress` cancels too.
   */
  static std::unique_ptr<HybridOctree> Build(const void* bytes, std::size_t byteCount,
    const GridDescription& grid, unsigned int leafSize, const std::function<bool(double)>& progress,
    std::string& error);

  /**
   * Builds the octrees of a 2-component image with dependent components
   * (`grid.Components` 2; `grid.Component` is not read): colour from
   * component 0, opacity from component 1 (vtkVolumeProperty's
   * IndependentComponentsOff; ParaView's Use Separate Opacity Array). Its
   * selections count 8 bytes a texel and are read with
   * Selection::GetBrickTexelsDependent(); their DrawLists' Effects start
   * with "dependent-components" (Composite). The summary's value range is
   * the colour field's. A 4-component image is an RGBA volume
   * (IndependentComponentsOff on 4 components): colour from components 0,
   * 1, 2 as VTK 9.2 reads them, opacity from component 3, gradient from component 0; its
   * selections count 4 bytes a texel for unsigned char data (RGBA8) and 16
   * otherwise (RGBA32F), are read with Selection::GetBrickTexelsRgba(),
   * and their DrawLists' Effects start with "rgba-components"; the
   * summary's value range is component 3's. nullptr and `error` on failure
   * (another component count, and Build()'s errors).
   */
  static std::unique_ptr<HybridOctree> BuildDependent(const void* bytes, std::size_t byteCount,
    const GridDescription& grid, unsigned int leafSize, std::string& error);

  /**
   * The Hybrid Octree of `store`: its stored Volume Octree (with its own
   * leaf size; `leafSize` is not read), or, for an image written by another
   * tool, the one built by a streaming pass over its full resolution
   * (never whole in memory) with leaves of `leafSize` cells. Its grid is the store's full
   * resolution. nullptr and `error` on failure (damaged octree arrays, too much memory).
   */
  static std::unique_ptr<HybridOctree> BuildFromStore(
    const OmeZarrStore& store, unsigned int leafSize, std::string& error);

  /// Node counts, levels, memory and build time. False and `error` on failure.
  bool GetSummary(OctreeSummary& summary, std::string& error) const;

  /// The cut at normalised error tolerance `tolerance` (0..1), replacing the
  /// contents of `boxes`. False and `error` on failure.
  bool GetCutBoxes(double tolerance, CutBoxes& boxes, std::string& error) const;

  /**
   * Surface data integration: extracts the isosurface at `isovalue` of the
   * image the octree was built from (`bytes`, `byteCount` and `grid` as in
   * Build()) and keeps it, replacing any; `measureDistance` also measures
   * the distance between the discretized and the interpolated surface. An
   * isovalue outside the data range gives an empty surface; a non-finite
   * isovalue or a grid that does not match the octree's returns false, sets
   * `error` and leaves no surface.
   */
  bool IntegrateSurface(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    double isovalue, SurfaceMode mode, bool measureDistance, SurfaceSummary& summary,
    std::string& error);

  /// Drops the isosurface.
  void RemoveSurface();

  /// The isosurface as a mesh into `mesh`'s arrays, sized from its
  /// SurfaceSummary. False and `error` on failure (no surface, a node id
  /// beyond an int).
  bool GetSurfaceMesh(const SurfaceMeshBuffers& mesh, std::string& error) const;

  /**
   * The isosurface as the GPU draws it, into the caller's buffers:
   * `vertices` 6 floats a vertex (world position, then unit normal),
   * `indices` 3 a triangle (the DrawList's triangle ids are their
   * positions); both resized from the SurfaceSummary. False and `error` on
   * failure.
   */
  bool GetSurfaceTriangles(
    std::vector<float>& vertices, std::vector<unsigned int>& indices, std::string& error) const;

  /**
   * Points data integration: the points completing stride-`options.Factor`
   * textures of the image the octree was built from (`bytes`, `byteCount`,
   * `grid` as in Build()), kept for Select(), replacing any.
   * `options.MaxOverestimate` must be < 0 (the textures are the image
   * itself). False, `error` and no points on failure.
   */
  bool IntegratePoints(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    const PointsOptions& options, PointsSummary& summary, std::string& error);

  /// Drops the points.
  void RemovePoints();

  /// The points' positions, values and errors, `drawing`'s arrays resized
  /// to the points. False and `error` on failure.
  bool GetPointsDrawing(PointsDrawing& drawing, std::string& error) const;

  /**
   * What each point adds under the transfer function of `colorPoints`
   * ((value, r, g, b) flattened) and `opacityPoints` ((value, opacity)
   * flattened): 4 floats a point into `shades` (resized), its straight
   * colour and opacity, averaged over its voxel (see src/points/shade.rs).
   * `bytes`, `byteCount` and `grid`: the image the points were made from.
   * False and `error` on failure.
   */
  bool GetPointShades(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    const std::vector<double>& colorPoints, const std::vector<double>& opacityPoints,
    std::vector<float>& shades, std::string& error) const;

  /**
   * Selects bricks (nodes and texture levels) within the budget; with points
   * integrated, the budget goes to textures and points (a brick at the
   * points' stride takes its points when they remove more error per byte
   * than refining it; the DrawLists bucket the points bought into their
   * slabs). Returns nullptr and sets `error` on failure (budget 0, a bad
   * tolerance, ROI or opacity points).
   */
  std::unique_ptr<Selection> Select(const SelectDescription& options, std::string& error) const;

  /**
   * What a Select() of `options` with the visibility importance
   * (options.View: VISIBILITY or BOTH, where it applies) needs from the
   * image the octree was built from (`bytes`, `grid` as in Build()): the
   * medium the estimate marches through, made once per transfer function
   * and kept (src/ffi/view.rs). Nothing for the other selections. False
   * and `error` on failure (a bad view, another image).
   */
  bool PrepareView(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    const SelectDescription& options, std::string& error) const;

private:
  friend class Selection;
  friend class FrameTimer;
  std::unique_ptr<RustHandle<HybridOctree>> Impl;
  std::size_t SurfaceVertices = 0; ///< of the surface held
  std::size_t SurfacePolygons = 0; ///< of the surface held
  std::size_t SurfaceIndices = 0;  ///< connectivity entries of the surface held
  std::size_t Points = 0;          ///< points held
  std::size_t PointsFactor = 0;    ///< their stride
  std::size_t PointsBytes = 0;     ///< their bytes as stored
};

/// A selection of a HybridOctree (it owns the Rust handle).
class Selection
{
public:
  explicit Selection(std::unique_ptr<RustHandle<Selection>> handle);
  ~Selection();
  Selection(const Selection&) = delete;
  Selection& operator=(const Selection&) = delete;

  /// Bricks, bytes, error, skipped nodes, warning. False and `error` on failure.
  bool GetSummary(SelectionSummary& summary, std::string& error) const;

  /**
   * The DrawList for `camera`, with the octree's surface, when it holds one,
   * at `surfaceOpacity`: 1 opaque (drawn first), (0, 1) translucent (batches
   * in the slabs, made on the first call for a surface and kept), 0 hidden.
   * `octree` must be the one Select() was called on. Replaces the contents
   * of `list`. False and `error` on failure.
   */
  bool GetDrawList(const HybridOctree& octree, const CameraDescription& camera,
    double surfaceOpacity, DrawList& list, std::string& error) const;

  /**
   * Brick `brick`'s texels (x fastest; texel (i, j, k) is the image at
   * min(lo + (i, j, k) * stride, hi)) as float: exact for 8/16-bit and float
   * images, rounded to nearest for double and 32-bit integers, written into
   * the caller's `texels` (`count`, the brick's texel count). `bytes`,
   * `byteCount` and `grid` describe the image the octree was built from.
   * False and `error` on failure.
   */
  bool GetBrickTexels(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    std::size_t brick, float* texels, std::size_t count, std::string& error) const;

  /**
   * GetBrickTexels() with the gradient border of a shaded volume: (texels +
   * 2) per axis, texel i at clamp(lo + (i - 1) stride, 0, dims - 1); a world
   * point's texture coordinate is then (x - xmin) / (stride * spacing) + 1
   * texels. False and `error` on failure.
   */
  bool GetBrickTexelsBordered(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    std::size_t brick, float* texels, std::size_t count, std::string& error) const;

  /**
   * Brick `brick`'s texels in the selection's texel format
   * (DrawList::TexelFormat), with the gradient border when `bordered`:
   * `decoded` gets the `count` values they decode to, `encoded` the
   * `encodedBytes` the GPU uploads (`count` bytes for unorm8, unsigned
   * shorts for unorm16, floats for float16, each a half float's exact value,
   * and for float32). False and `error` on failure.
   */
  bool GetBrickTexelsEncoded(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    std::size_t brick, bool bordered, float* decoded, std::size_t count, unsigned char* encoded,
    std::size_t encodedBytes, std::string& error) const;

  /**
   * Brick `brick`'s texels read from `store`, the volume the octree was
   * built from (HybridOctree::BuildFromStore()): with `encoded` nullptr,
   * GetBrickTexelsBordered()'s (`bordered`) or GetBrickTexels()'s floats
   * into `texels`; else GetBrickTexelsEncoded()'s decoded values and GPU
   * bytes. The same texels as from the image in memory, bit for bit.
   * `octree` is the one Select() was called on: the brick's samples must lie
   * in its node's stored range (a chunk missing from the store reads as the
   * fill value, found so). False and `error` on failure (dependent or RGBA
   * selections, coarse bricks of a maximum or minimum intensity, a chunk
   * missing or damaged).
   */
  bool GetBrickTexelsFromStore(const HybridOctree& octree, const OmeZarrStore& store,
    std::size_t brick, bool bordered, float* texels, std::size_t count, unsigned char* encoded,
    std::size_t encodedBytes, std::string& error) const;

  /**
   * Plans a frame's loading from `store` in the background (src/ffi/loading.rs): the
   * selected bricks above two texels a side whose textures are not resident
   * (`residentNodes[i]`, `residentStrides[i]`) are read by the store's thread, most important
   * first, holding at most `memoryBytes` of read bricks waiting for upload. Until a brick is
   * read, the draw lists and brick texels got after this call draw it by its stand-in: the
   * same node two levels coarser (1/64 of the texels), read at once, so the picture has no
   * hole. False and `error`
   * on failure (another octree or store, a background read that failed).
   */
  bool PlanLoading(const HybridOctree& octree, const OmeZarrStore& store,
    const std::vector<std::uint32_t>& residentNodes,
    const std::vector<std::size_t>& residentStrides, std::size_t memoryBytes,
    LoadingSummary& summary, std::string& error) const;

  /// The draw lists and brick texels got after this call draw the selected bricks themselves
  /// (no stand-ins).
  void DrawSelected() const;

  /**
   * Brick `brick`'s texels of both fields of a selection made from
   * HybridOctree::BuildDependent()'s octree: (colour, opacity) float pairs,
   * texels x fastest, `count` = 2 x the texel count, with the gradient
   * border of GetBrickTexelsBordered() when `bordered`. False and `error` on failure.
   */
  bool GetBrickTexelsDependent(const void* bytes, std::size_t byteCount,
    const GridDescription& grid, std::size_t brick, bool bordered, float* texels, std::size_t count,
    std::string& error) const;

  /**
   * Brick `brick`'s texels of the four components of a selection made from
   * an RGBA volume's octree (HybridOctree::BuildDependent() of a
   * 4-component image), texels x fastest, with the gradient border of
   * GetBrickTexelsBordered() when `bordered`: `decoded` gets `count` = 4 x
   * the texel count floats (the values), and for unsigned char data
   * `encoded` the `encodedBytes` (= `count`) RGBA8 bytes the GPU uploads
   * (nullptr and 0 for other types, uploaded as RGBA32F from `decoded`).
   * False and `error` on failure.
   */
  bool GetBrickTexelsRgba(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    std::size_t brick, bool bordered, float* decoded, std::size_t count, unsigned char* encoded,
    std::size_t encodedBytes, std::string& error) const;

  /**
   * The shading of the DrawLists and pictures made after this call; the
   * plan then says "volume-shaded" unless the shading changes no colour.
   * False and `error` on failure (a bad number, no light, lights not in threes).
   */
  bool SetShading(const ShadingDescription& shading, std::string& error) const;

  /**
   * The gradient opacity of the DrawLists and pictures made after this call:
   * `points` as SelectDescription::GradientOpacityPoints (empty: none). The
   * plan's effects then say "gradient-opacity" (or "opacity-scale" for a
   * constant other than 1). False and `error` on failure (an odd count,
   * magnitudes not finite or decreasing, opacities outside [0, 1]).
   */
  bool SetGradientOpacity(const std::vector<double>& points, std::string& error) const;

  /**
   * Jittering (VTK's UseJittering) of the DrawLists and pictures made after
   * this call: each pixel's samples move along its ray by a fixed fraction of
   * the slice spacing (src/plan/jitter.rs); the plan's effects then end with
   * "jittering" when it applies (a volume not in Slice, no translucent
   * surface or points between the slices). False and `error` on failure.
   */
  bool SetJittering(bool on, std::string& error) const;

  /**
   * The ray sample distance (model units; VTK's SampleDistance) of the
   * DrawLists and pictures made after this call: the Isosurface blend mode
   * and the 2D transfer function slice every distance / d0 of a lattice step
   * when it is below d0 (effect "sample-distance", src/plan/sampling.rs); 0:
   * one slice a lattice step. False and `error` for a negative distance.
   */
  bool SetSampleDistance(double distance, std::string& error) const;

  /**
   * The volumetric scattering of the DrawLists and pictures made after this
   * call (the plan's effects then say "volume-scattering" when it runs: Shade
   * with a light, Composite, blending above 0). False and `error` on failure
   * (a value out of its range).
   */
  bool SetScattering(const ScatteringDescription& scattering, std::string& error) const;

  /// What the brick shader reads for the scattering last set. False and `error` on failure.
  bool GetScatteringFrame(ScatteringFrame& frame, std::string& error) const;

  /**
   * The shadow volume of the image the octree was built from (`bytes`,
   * `byteCount`, `grid`): the product of ScatteringFrame::ShadowDims floats,
   * x fastest, into `texels` (`count` of them). False and `error` on failure.
   */
  bool GetShadowVolume(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    float* texels, std::size_t count, std::string& error) const;

  /**
   * The CPU compositor's picture of the DrawList (GetDrawList(octree,
   * camera, scene.SurfaceRGBA[3])) into the caller's `rgba`: `width x
   * height` premultiplied RGBA floats (4 a pixel), rows from the top, with
   * the transfer function of `scene.ColorPoints` ((value, r, g, b)
   * flattened) and `scene.OpacityPoints` ((value, opacity) flattened),
   * piecewise linear; the octree's surface, when it holds one and
   * `scene.SurfaceRGBA[3]` > 0, headlight-shaded, `rgb |n . d|`. `bytes`,
   * `byteCount` and `grid`: the image the octree was built from. The
   * reference vtkHybridOctreeVolumeMapper's OpenGL output is tested against.
   */
  bool Composite(const HybridOctree& octree, const CameraDescription& camera, const void* bytes,
    std::size_t byteCount, const GridDescription& grid, const CompositeScene& scene,
    std::size_t width, std::size_t height, float* rgba, std::string& error) const;

private:
  friend class FrameTimer;
  std::unique_ptr<RustHandle<Selection>> Impl;
};

/// A frame to draw within a time (see TimedFrameDesc in src/ffi/mod.rs): its
/// target and what its DrawList is planned with, as the mapper plans it.
struct TimedFrameDescription
{
  double TargetMilliseconds = 0.0; ///< above 0, at most ten minutes
  CameraDescription Camera;        ///< in the octree's frame
  std::size_t Width = 1;           ///< the viewport, pixels
  std::size_t Height = 1;
  double SurfaceOpacity = 0.0; ///< the octree's surface drawn at (0: hidden)
  ShadingDescription Shading;
  std::vector<double> GradientOpacityPoints;
  bool Jittering = false;
  double SampleDistance = 0.0;
  ScatteringDescription Scattering;
};

/// What a FrameTimer chose for its last frame (see TimedSummary in src/ffi/mod.rs).
struct TimedSummary
{
  double TargetMilliseconds = 0.0;
  double PredictedMilliseconds = 0.0; ///< the chosen frame's predicted drawing time
  double MeasuredMilliseconds = 0.0;  ///< the last observed frame's drawing time
  std::uint64_t BudgetBytes = 0;      ///< the budget the chosen selection was made under
  std::uint32_t SliceFactor = 1;      ///< its slices' least spacing, multiples of d0
  /// "warm-up", "met", "full" or "below-fastest".
  std::string Outcome;
  std::uint64_t Evaluations = 0;
  double EstimatedRmsError = 0.0;
  std::uint64_t WarmUpLeft = 0;
  double Ratio = 1.0; ///< the online correction, measured over modelled time
  std::string Note;   ///< said when the target is below the fastest frame
};

/**
 * The model of what a frame costs on this machine (it owns the Rust
 * handle; see src/ffi/timed.rs): calibrated on warm-up frames, corrected
 * online from each measured one, and the time-budgeted selection under it.
 */
class FrameTimer
{
public:
  FrameTimer();
  ~FrameTimer();
  FrameTimer(const FrameTimer&) = delete;
  FrameTimer& operator=(const FrameTimer&) = delete;

  /**
   * The selection of `options` (its budget the hard memory limit) of least
   * estimated error whose frame is predicted within `frame`'s target; during
   * the warm-up, the next calibration budget's. nullptr and `error` on
   * failure (a bad target or viewport, and Select()'s errors).
   */
  std::unique_ptr<Selection> Select(const HybridOctree& octree, const SelectDescription& options,
    const TimedFrameDescription& frame, std::string& error);

  /**
   * Feeds a frame drawn from `selection` (made by Select() for `frame`)
   * that uploaded `uploadedBytes` and took `milliseconds` to draw; `again`
   * says whether the next frame should select again. False and `error` on failure.
   */
  bool Observe(const Selection& selection, const HybridOctree& octree,
    const TimedFrameDescription& frame, std::size_t uploadedBytes, double milliseconds, bool& again,
    std::string& error);

  /// What the last Select() chose and the last frame took.
  TimedSummary GetSummary() const;

private:
  std::unique_ptr<RustHandle<FrameTimer>> Impl;
};

/// What FtbDisplay() draws (paper 2's display; see FtbDesc in src/ffi/mod.rs).
struct FtbOptions
{
  double Isovalue = 0.0; ///< inside: value >= Isovalue ...
  bool UseLabel = false; ///< ... or value == Label
  double Label = 0.0;
  double Vpn[3] = { 1.0, -1.0, 1.0 }; ///< view plane normal, towards the viewer
  std::size_t ImageSize = 512;
  bool BackToFront = false; ///< Meagher's display instead of FTB with blocking quadtrees
};

/// The caller's `ImageSize^2` pixels a depth image is drawn into, rows from
/// the bottom (VTK's image order).
struct FtbImageBuffers
{
  float* Depth = nullptr;         ///< NaN where nothing was painted
  std::uint8_t* Face = nullptr;   ///< 0 nothing, 1 + axis of the face painted
  std::uint8_t* Shaded = nullptr; ///< RGB, 3 a pixel
};

/// What drawing a depth image took.
struct FtbResult
{
  std::size_t WhiteVisited = 0, BlackVisited = 0, GrayVisited = 0;
  std::size_t Faces = 0, Scanlines = 0, Pixels = 0;
  double DisplayMs = 0.0, BuildMs = 0.0;
  std::size_t BitmapBytes = 0;
  std::size_t WhiteOctants = 0, BlackOctants = 0, GrayOctants = 0;
  unsigned int Resolution = 0;
  std::string ViewCase;
};

/**
 * Builds the binary octree of `byteCount` bytes at `bytes` laid out as
 * `grid` and draws its depth image into `image` (`options.ImageSize^2`
 * pixels). False and `error` on failure (a zero VPN, a non-finite isovalue,
 * an image size outside 8..8192, bad samples).
 */
bool FtbDisplay(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const FtbOptions& options, const FtbImageBuffers& image, FtbResult& result, std::string& error);

/// What GeneratePoints() makes (paper 3's points; see PointsDesc in src/ffi/mod.rs).
struct PointsOptions
{
  std::size_t Factor = 4; ///< low resolution: every 2, 4 or 8 samples
  double Threshold = 0.1; ///< |error| above this fraction of the data range ...
  bool UseBudget = false; ///< ... or the Budget largest errors
  std::size_t Budget = 0;
  bool UnderestimatesOnly = false; ///< only where the low resolution underestimates
  double MaxOverestimate = -1.0;   ///< optimized low resolution's bound (fraction); < 0: off
  std::string FileName;            ///< also write the point file (empty: do not)
};

/// The caller's arrays the points are written into (one entry a point, 3 for
/// `Ijk` and `Normal`), dequantised as stored.
struct PointsBuffers
{
  std::uint32_t* Ijk = nullptr; ///< grid index
  float* Value = nullptr;
  float* Error = nullptr;
  float* Normal = nullptr; ///< unit, from the 256-direction table
};

/**
 * The points completing the stride-`Factor` low resolution of `byteCount`
 * bytes at `bytes` laid out as `grid`: `allocate(summary)` is called once
 * their count is known and returns the caller's arrays, which are then
 * filled. False and `error` on failure (a bad factor, threshold or bound, a
 * grid too small, a file not written, an array missing).
 */
bool GeneratePoints(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const PointsOptions& options, const std::function<PointsBuffers(const PointsSummary&)>& allocate,
  PointsSummary& summary, std::string& error);

} // namespace vtkHybridOctreeBridge

#endif
