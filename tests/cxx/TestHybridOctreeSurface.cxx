// Scenarios of the isosurface on output port 1 of vtkHybridOctreeFilter. Usage:
//   HybridOctreeCxxTests TestHybridOctreeSurface <scenario>
// Scenarios: discretized, interpolated (the output contract on sphere distance
// fields), flying_edges (triangle counts and vertices against
// vtkFlyingEdges3D), outside_range, cache.
#include "HybridOctreeTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkHybridOctreeFilter.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStaticPointLocator.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <utility>

namespace
{
constexpr double Isovalue = 10.0;

/// An image and the index-space center of its distance field.
struct Sphere
{
  vtkSmartPointer<vtkImageData> Image;
  double Center[3];
};

/// A float image of `dims` points whose value is the distance, in voxels
/// (index units), to the index-space point `center`: its isosurface at 10 is
/// a closed sphere of radius 10 voxels when the center is far enough from the
/// border. Spacing 2 and a shifted extent make world and index coordinates
/// differ, so a mix-up shows.
Sphere MakeSphere(const int dims[3], const double center[3])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(-3, dims[0] - 4, 0, dims[1] - 1, 5, dims[2] + 4);
  image->SetSpacing(2.0, 2.0, 2.0);
  image->SetOrigin(1.0, -7.0, 0.5);
  vtkNew<vtkFloatArray> distance;
  distance->SetName("distance");
  distance->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const double d[3] = { i - center[0], j - center[1], k - center[2] };
        distance->SetValue(id++, static_cast<float>(vtkMath::Norm(d)));
      }
    }
  }
  image->GetPointData()->SetScalars(distance);
  return { image, { center[0], center[1], center[2] } };
}

/// The 33^3 sphere of the issue: radius 10 around the middle sample.
Sphere MakeCubeSphere()
{
  const int dims[3] = { 33, 33, 33 };
  const double center[3] = { 16.0, 16.0, 16.0 };
  return MakeSphere(dims, center);
}

/// A non-cubic, non-power-of-two grid (the root is padded virtually) with an
/// off-grid center.
Sphere MakeOddSphere()
{
  const int dims[3] = { 37, 30, 26 };
  const double center[3] = { 18.3, 14.6, 12.4 };
  return MakeSphere(dims, center);
}

/// Index coordinates (relative to the first sample) of world point `p`.
std::array<double, 3> ToIndex(vtkImageData* image, const double p[3])
{
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  const int* extent = image->GetExtent();
  std::array<double, 3> index;
  for (int a = 0; a < 3; ++a)
  {
    index[a] = (p[a] - origin[a]) / spacing[a] - extent[2 * a];
  }
  return index;
}

/// Id, in the level-by-level numbering (docs/ARCHITECTURE.md, "Levels and
/// numbering"), of the node at `level` whose box starts at index `lo`:
/// offset(level) + i + nx * (j + ny * k), level m having ceil(cells / S_m)
/// nodes per axis with S_m = rootSize >> m cells.
std::int64_t NodeId(const std::array<double, 3>& lo, int level, int rootSize, const int cells[3])
{
  std::int64_t offset = 0;
  for (int m = 0; m < level; ++m)
  {
    const int s = rootSize >> m;
    offset += static_cast<std::int64_t>((cells[0] + s - 1) / s) * ((cells[1] + s - 1) / s) *
      ((cells[2] + s - 1) / s);
  }
  const int s = rootSize >> level;
  const std::int64_t nx = (cells[0] + s - 1) / s;
  const std::int64_t ny = (cells[1] + s - 1) / s;
  std::int64_t c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = std::llround(lo[a]) / s;
  }
  return offset + c[0] + nx * (c[1] + ny * c[2]);
}

/// The field data string "surface_mode", or "" when missing.
std::string SurfaceModeName(vtkPolyData* surface)
{
  auto* mode =
    vtkStringArray::SafeDownCast(surface->GetFieldData()->GetAbstractArray("surface_mode"));
  return mode && mode->GetNumberOfValues() == 1 ? mode->GetValue(0) : "";
}

bool IsInteger(double v)
{
  return std::abs(v - std::round(v)) < 1e-6;
}

/// Fraction part 0.5: an edge midpoint coordinate.
bool IsHalfInteger(double v)
{
  return std::abs(v - std::floor(v) - 0.5) < 1e-6;
}

/// Counts edges used by exactly one polygon.
vtkIdType CountBoundaryEdges(vtkPolyData* surface)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> uses;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    surface->GetCellPoints(c, ids);
    const vtkIdType n = ids->GetNumberOfIds();
    for (vtkIdType e = 0; e < n; ++e)
    {
      const vtkIdType a = ids->GetId(e);
      const vtkIdType b = ids->GetId((e + 1) % n);
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  vtkIdType boundary = 0;
  for (const auto& edge : uses)
  {
    boundary += edge.second == 1 ? 1 : 0;
  }
  return boundary;
}

/// Shape of a polygon: convex (every turn, the cross product of consecutive
/// edges, points the same way; straight vertices, which the compression keeps
/// to avoid T-junctions, are allowed), degenerate (no turn at all: zero area)
/// or not convex.
enum class PolygonShape
{
  Convex,
  Degenerate,
  NotConvex
};

PolygonShape ShapeOf(vtkPolyData* surface, vtkIdList* ids)
{
  const vtkIdType n = ids->GetNumberOfIds();
  double reference[3] = { 0.0, 0.0, 0.0 };
  bool turned = false;
  for (vtkIdType v = 0; v < n; ++v)
  {
    double p0[3], p1[3], p2[3], e0[3], e1[3], turn[3];
    surface->GetPoint(ids->GetId(v), p0);
    surface->GetPoint(ids->GetId((v + 1) % n), p1);
    surface->GetPoint(ids->GetId((v + 2) % n), p2);
    vtkMath::Subtract(p1, p0, e0);
    vtkMath::Subtract(p2, p1, e1);
    vtkMath::Cross(e0, e1, turn);
    if (vtkMath::Norm(turn) <= 1e-9 * vtkMath::Norm(e0) * vtkMath::Norm(e1))
    {
      continue; // a straight (or repeated) vertex
    }
    vtkMath::Normalize(turn);
    if (!turned)
    {
      std::copy(turn, turn + 3, reference);
      turned = true;
    }
    else if (vtkMath::Dot(turn, reference) < 1.0 - 1e-6)
    {
      return PolygonShape::NotConvex;
    }
  }
  return turned ? PolygonShape::Convex : PolygonShape::Degenerate;
}

/// True when every point of polygon `ids` lies in `bounds` (VTK order), 1e-9 slack.
bool IsInBox(vtkPolyData* surface, vtkIdList* ids, const std::array<double, 6>& bounds)
{
  for (vtkIdType v = 0; v < ids->GetNumberOfIds(); ++v)
  {
    double x[3];
    surface->GetPoint(ids->GetId(v), x);
    for (int a = 0; a < 3; ++a)
    {
      if (x[a] < bounds[2 * a] - 1e-9 || x[a] > bounds[2 * a + 1] + 1e-9)
      {
        return false;
      }
    }
  }
  return true;
}

/// Runs the filter on `sphere` in `mode` at the isovalue and leaf size 4 with
/// tolerance 0 (port 0 = the terminal nodes), and checks the whole contract of
/// port 1.
void CheckSurface(Checker& t, const Sphere& sphere, int mode, const std::string& name)
{
  vtkImageData* image = sphere.Image;
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  filter->SetLeafSize(4);
  filter->SetErrorTolerance(0.0);
  filter->SetIsovalue(Isovalue);
  filter->SetSurfaceMode(mode);
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  filter->Update();
  if (!t.Check(errors->Errors.empty(), name + ": no error:\n" + errors->AllErrors()))
  {
    return;
  }
  vtkPolyData* boxes = filter->GetOutput(0);
  vtkPolyData* surface = filter->GetOutput(1);
  const bool interpolated = mode == vtkHybridOctreeFilter::SURFACE_MODE_INTERPOLATED;

  // Field data.
  const double polygons = FieldValue(surface, "polygons");
  const double triangles = FieldValue(surface, "triangles");
  const double uncompressed = FieldValue(surface, "uncompressed_triangles");
  const double vertices = FieldValue(surface, "vertices");
  const double boundaryEdges = FieldValue(surface, "boundary_edges");
  const double distanceMean = FieldValue(surface, "distance_mean");
  const double distanceMax = FieldValue(surface, "distance_max");
  std::cout << name << ": " << polygons << " polygons, " << triangles << " triangles, "
            << uncompressed << " uncompressed triangles, " << vertices << " vertices, "
            << "extract " << FieldValue(surface, "extract_ms") << " ms, compress "
            << FieldValue(surface, "compress_ms") << " ms, distance mean " << distanceMean
            << " max " << distanceMax << " voxels\n";
  t.Check(FieldValue(surface, "isovalue") == Isovalue, name + ": field isovalue");
  t.Check(SurfaceModeName(surface) == (interpolated ? "interpolated" : "discretized"),
    name + ": field surface_mode is '" + SurfaceModeName(surface) + "'");
  t.Check(polygons > 0, name + ": the sphere has polygons");
  t.Check(surface->GetNumberOfPolys() == polygons && surface->GetNumberOfCells() == polygons,
    name + ": one polygon cell per polygon, nothing else");
  t.Check(surface->GetNumberOfPoints() == vertices, name + ": one point per vertex");
  t.Check(boundaryEdges == 0, name + ": the sphere is closed (boundary_edges 0)");
  t.Check(CountBoundaryEdges(surface) == 0, name + ": no edge is used by one polygon only");
  t.Check(FieldValue(surface, "extract_ms") >= 0 && FieldValue(surface, "compress_ms") >= 0,
    name + ": timings");
  const double bound = 0.5 * std::sqrt(3.0);
  t.Check(distanceMax > 0 && distanceMax <= bound,
    name + ": 0 < distance_max <= sqrt(3)/2 voxel: " + std::to_string(distanceMax));
  t.Check(distanceMean > 0 && distanceMean <= distanceMax,
    name + ": 0 < distance_mean <= distance_max: " + std::to_string(distanceMean));
  if (interpolated)
  {
    t.Check(triangles == uncompressed && triangles == polygons,
      name + ": interpolated: triangles == uncompressed_triangles == polygons");
  }
  else
  {
    t.Check(triangles < uncompressed, name + ": merging facets removes triangles");
    t.Check(polygons == triangles && FieldValue(surface, "faces") < triangles,
      name + ": the output cells are triangles, fewer faces than triangles (merged facets)");
  }

  // Normals: the active normals, float, unit, pointing towards lower values
  // (the center of the distance field); vertices on grid edges.
  vtkDataArray* normals = surface->GetPointData()->GetNormals();
  if (!t.Check(normals && normals->GetName() && std::string(normals->GetName()) == "Normals" &&
          vtkFloatArray::SafeDownCast(normals) && normals->GetNumberOfComponents() == 3 &&
          normals->GetNumberOfTuples() == vertices,
        name + ": point array 'Normals' (float, 3 components) is the active normals"))
  {
    return;
  }
  const int* dims = image->GetDimensions();
  const double* center = sphere.Center;
  int notUnit = 0, outward = 0, offGrid = 0;
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    double n[3], x[3];
    normals->GetTuple(p, n);
    surface->GetPoint(p, x);
    notUnit += std::abs(vtkMath::Norm(n) - 1.0) > 1e-5 ? 1 : 0;
    const std::array<double, 3> index = ToIndex(image, x);
    const double radial[3] = { index[0] - center[0], index[1] - center[1], index[2] - center[2] };
    outward += vtkMath::Dot(n, radial) >= 0.0 ? 1 : 0;
    // In index coordinates a vertex on a grid edge has two integer
    // coordinates; DiscMC puts it at the edge midpoint.
    int integers = 0, halves = 0;
    for (int a = 0; a < 3; ++a)
    {
      integers += IsInteger(index[a]) ? 1 : 0;
      halves += IsHalfInteger(index[a]) ? 1 : 0;
    }
    offGrid += (integers < 2 || (!interpolated && halves != 1)) ? 1 : 0;
  }
  t.Check(notUnit == 0, name + ": " + std::to_string(notUnit) + " normals are not unit length");
  t.Check(
    outward == 0, name + ": " + std::to_string(outward) + " normals point away from lower values");
  t.Check(offGrid == 0,
    name + ": " + std::to_string(offGrid) +
      (interpolated ? " vertices are not on grid edges" : " vertices are not edge midpoints"));

  // Polygons: convex; each lies in the box of its terminal node, which is the
  // box on port 0 (the cut at tolerance 0) with the same "node" and level.
  vtkDataArray* node = surface->GetCellData()->GetArray("node");
  vtkDataArray* level = surface->GetCellData()->GetArray("level");
  if (!t.Check(vtkIntArray::SafeDownCast(node) && vtkIntArray::SafeDownCast(level) &&
          node->GetNumberOfTuples() == polygons && level->GetNumberOfTuples() == polygons,
        name + ": int cell arrays 'node' and 'level', one value per polygon"))
  {
    return;
  }
  const int rootSize = static_cast<int>(FieldValue(boxes, "root_size"));
  const int cells[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
  std::map<std::int64_t, std::pair<int, std::array<double, 6>>> terminal; // id -> level, bounds
  const vtkIdType boxCount = static_cast<vtkIdType>(FieldValue(boxes, "cut_count"));
  vtkDataArray* boxNode = boxes->GetCellData()->GetArray("node");
  vtkDataArray* boxLevel = boxes->GetCellData()->GetArray("level");
  int wrongId = 0;
  for (vtkIdType b = 0; b < boxCount; ++b)
  {
    double lo[3], hi[3];
    boxes->GetPoint(8 * b, lo);
    boxes->GetPoint(8 * b + 7, hi);
    const int l = static_cast<int>(boxLevel->GetTuple1(12 * b));
    const auto id = static_cast<std::int64_t>(boxNode->GetTuple1(12 * b));
    wrongId += id != NodeId(ToIndex(image, lo), l, rootSize, cells) ? 1 : 0;
    terminal[id] = { l, { lo[0], hi[0], lo[1], hi[1], lo[2], hi[2] } };
  }
  t.Check(wrongId == 0,
    name + ": " + std::to_string(wrongId) +
      " boxes on port 0 have another node id than the "
      "level-by-level numbering gives");
  t.Check(static_cast<vtkIdType>(terminal.size()) == boxCount, name + ": box ids are distinct");
  int unknownNode = 0, wrongLevel = 0, outside = 0, notConvex = 0, degenerate = 0;
  double fanTriangles = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    surface->GetCellPoints(c, ids);
    fanTriangles += static_cast<double>(ids->GetNumberOfIds() - 2);
    const PolygonShape shape = ShapeOf(surface, ids);
    notConvex += shape == PolygonShape::NotConvex ? 1 : 0;
    degenerate += shape == PolygonShape::Degenerate ? 1 : 0;
    auto box = terminal.find(static_cast<std::int64_t>(node->GetTuple1(c)));
    if (box == terminal.end())
    {
      ++unknownNode;
      continue;
    }
    wrongLevel += box->second.first != level->GetTuple1(c) ? 1 : 0;
    outside += IsInBox(surface, ids, box->second.second) ? 0 : 1;
  }
  t.Check(unknownNode == 0,
    name + ": " + std::to_string(unknownNode) + " polygons name a node that is not terminal");
  t.Check(wrongLevel == 0,
    name + ": " + std::to_string(wrongLevel) + " polygons have another level than their node");
  t.Check(outside == 0,
    name + ": " + std::to_string(outside) + " polygons stick out of their node's box");
  t.Check(notConvex == 0, name + ": " + std::to_string(notConvex) + " polygons are not convex");
  // Interpolated MC makes zero-area triangles where samples equal the
  // isovalue (as vtkFlyingEdges3D does); DiscMC vertices are edge midpoints,
  // so its polygons always have an area.
  std::cout << name << ": " << degenerate << " zero-area polygons\n";
  t.Check(interpolated || degenerate == 0,
    name + ": " + std::to_string(degenerate) + " DiscMC polygons have zero area");
  t.Check(fanTriangles == triangles, name + ": triangles = sum of (polygon size - 2)");

  // Faces: every triangle names its merged coplanar face; the triangles of a
  // face share its node and its plane, and there are "faces" of them.
  vtkDataArray* face = surface->GetCellData()->GetArray("face");
  if (!t.Check(face && face->GetNumberOfTuples() == polygons,
        name + ": cell array 'face', one value per polygon"))
  {
    return;
  }
  struct FaceOf
  {
    double Node;
    double Normal[3];
  };
  std::map<std::int64_t, FaceOf> faces;
  int split = 0, bent = 0;
  for (vtkIdType c = 0; c < polygons; ++c)
  {
    surface->GetCellPoints(c, ids);
    double p0[3], p1[3], p2[3], e0[3], e1[3], n[3];
    surface->GetPoint(ids->GetId(0), p0);
    surface->GetPoint(ids->GetId(1), p1);
    surface->GetPoint(ids->GetId(2), p2);
    vtkMath::Subtract(p1, p0, e0);
    vtkMath::Subtract(p2, p0, e1);
    vtkMath::Cross(e0, e1, n);
    if (vtkMath::Normalize(n) == 0.0)
    {
      continue; // zero-area interpolated triangle: no plane
    }
    const auto id = static_cast<std::int64_t>(face->GetTuple1(c));
    auto found = faces.find(id);
    if (found == faces.end())
    {
      faces[id] = { node->GetTuple1(c), { n[0], n[1], n[2] } };
      continue;
    }
    split += found->second.Node != node->GetTuple1(c) ? 1 : 0;
    bent += vtkMath::Dot(found->second.Normal, n) < 1.0 - 1e-9 ? 1 : 0;
  }
  const double faceCount = FieldValue(surface, "faces");
  t.Check(split == 0,
    name + ": " + std::to_string(split) + " triangles lie in another node than their face");
  t.Check(
    bent == 0, name + ": " + std::to_string(bent) + " triangles are not in their face's plane");
  t.Check(interpolated ? faceCount == triangles : faceCount < triangles,
    name + ": faces = triangles (interpolated) or fewer (merged DiscMC)");
  t.Check(
    static_cast<double>(faces.size()) <= faceCount, name + ": face ids within the face count");
}

int Mode(int mode)
{
  Checker t;
  const std::string name =
    mode == vtkHybridOctreeFilter::SURFACE_MODE_INTERPOLATED ? "interpolated" : "discretized";
  CheckSurface(t, MakeCubeSphere(), mode, name + " 33^3");
  CheckSurface(t, MakeOddSphere(), mode, name + " 37x30x26");
  return t.Result();
}

/// vtkFlyingEdges3D at the same isovalue: the interpolated surface has the
/// same vertices and about the same triangles; DiscMC has fewer triangles.
int FlyingEdges()
{
  Checker t;
  for (const Sphere& sphere : { MakeCubeSphere(), MakeOddSphere() })
  {
    vtkImageData* image = sphere.Image;
    vtkNew<vtkFlyingEdges3D> flyingEdges;
    flyingEdges->SetInputData(image);
    flyingEdges->SetValue(0, Isovalue);
    flyingEdges->ComputeNormalsOff();
    flyingEdges->ComputeScalarsOff();
    flyingEdges->Update();
    vtkPolyData* reference = flyingEdges->GetOutput();
    const double feTriangles = static_cast<double>(reference->GetNumberOfPolys());

    vtkNew<vtkHybridOctreeFilter> filter;
    filter->SetInputData(image);
    filter->SetLeafSize(4);
    filter->SetIsovalue(Isovalue);
    filter->SetSurfaceModeToInterpolated();
    filter->Update();
    vtkPolyData* interpolated = filter->GetOutput(1);
    const double mcTriangles = FieldValue(interpolated, "triangles");
    const double mcVertices = FieldValue(interpolated, "vertices");

    // Every interpolated vertex is a FlyingEdges vertex.
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(reference);
    locator->BuildLocator();
    double worst = 0.0;
    for (vtkIdType p = 0; p < interpolated->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3];
      interpolated->GetPoint(p, x);
      reference->GetPoint(locator->FindClosestPoint(x), y);
      worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(x, y)));
    }

    filter->SetSurfaceModeToDiscretized();
    filter->Update();
    const double discTriangles = FieldValue(filter->GetOutput(1), "triangles");
    const double discPolygons = FieldValue(filter->GetOutput(1), "polygons");

    const int* d = image->GetDimensions();
    std::ostringstream label;
    label << d[0] << "x" << d[1] << "x" << d[2];
    std::cout << label.str() << ": FlyingEdges " << feTriangles << " triangles, "
              << reference->GetNumberOfPoints() << " points; interpolated " << mcTriangles
              << " triangles, " << mcVertices << " vertices; discretized " << discPolygons
              << " polygons, " << discTriangles << " triangles; farthest interpolated vertex "
              << worst << " from a FlyingEdges point\n";
    t.Check(feTriangles > 0, label.str() + ": FlyingEdges has triangles");
    t.Check(std::abs(mcTriangles - feTriangles) <= 0.02 * feTriangles,
      label.str() + ": interpolated triangles within 2% of FlyingEdges");
    t.Check(mcVertices == reference->GetNumberOfPoints(),
      label.str() + ": as many vertices as FlyingEdges points");
    t.Check(worst <= 1e-5 * image->GetSpacing()[0],
      label.str() + ": interpolated vertices are FlyingEdges vertices (" + std::to_string(worst) +
        ")");
    t.Check(discTriangles < feTriangles, label.str() + ": DiscMC has fewer triangles");
  }
  return t.Result();
}

/// An isovalue outside the data range: an empty surface, no error, boxes as usual.
int OutsideRange()
{
  Checker t;
  const Sphere sphere = MakeCubeSphere();
  vtkImageData* image = sphere.Image;
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  for (const double isovalue : { range[1] + 1.0, range[0] - 1.0, 1e30, -1e30 })
  {
    for (const int mode : { 0, 1 })
    {
      filter->SetIsovalue(isovalue);
      filter->SetSurfaceMode(mode);
      filter->Update();
      const std::string name =
        "isovalue " + std::to_string(isovalue) + " mode " + std::to_string(mode);
      t.Check(errors->Errors.empty(), name + ": no error:\n" + errors->AllErrors());
      vtkPolyData* surface = filter->GetOutput(1);
      t.Check(surface->GetNumberOfPoints() == 0 && surface->GetNumberOfCells() == 0,
        name + ": empty surface");
      t.Check(FieldValue(surface, "polygons") == 0 && FieldValue(surface, "triangles") == 0 &&
          FieldValue(surface, "vertices") == 0 && FieldValue(surface, "boundary_edges") == 0,
        name + ": zero counts");
      t.Check(FieldValue(surface, "isovalue") == isovalue, name + ": field isovalue");
      t.Check(filter->GetOutput(0)->GetNumberOfLines() > 0, name + ": boxes as usual");
    }
  }
  return t.Result();
}

/// The surface is extracted again only when the octree or a surface setting
/// changed.
int Cache()
{
  Checker t;
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(MakeCubeSphere().Image);
  filter->SetLeafSize(8);
  filter->SetErrorTolerance(0.0);
  filter->SetIsovalue(Isovalue);
  filter->Update();
  vtkPolyData* surface = filter->GetOutput(1);
  t.Check(filter->GetSurfaceExtractCount() == 1, "first request extracts");
  const double extractMs = FieldValue(surface, "extract_ms");
  const double polygons = FieldValue(surface, "polygons");
  const double fineCut = FieldValue(filter->GetOutput(0), "cut_count");

  filter->SetErrorTolerance(0.5);
  filter->Update();
  t.Check(FieldValue(filter->GetOutput(0), "cut_count") < fineCut, "the boxes were re-cut");
  t.Check(filter->GetSurfaceExtractCount() == 1, "a tolerance change does not extract");
  t.Check(FieldValue(surface, "extract_ms") == extractMs, "extract_ms unchanged: same surface");
  t.Check(surface->GetNumberOfPolys() == polygons, "the cached surface is on port 1");

  filter->SetIsovalue(12.0);
  filter->Update();
  t.Check(filter->GetSurfaceExtractCount() == 2, "an isovalue change extracts");
  t.Check(FieldValue(surface, "polygons") > polygons, "a larger sphere has more polygons");
  t.Check(filter->GetOctreeBuildCount() == 1, "an isovalue change does not rebuild the octree");

  filter->SetSurfaceModeToInterpolated();
  filter->Update();
  t.Check(filter->GetSurfaceExtractCount() == 3, "a mode change extracts");
  t.Check(SurfaceModeName(surface) == "interpolated", "interpolated surface on port 1");

  filter->MeasureSurfaceDistanceOff();
  filter->Update();
  t.Check(filter->GetSurfaceExtractCount() == 4, "turning the distance off extracts");
  t.Check(FieldValue(surface, "distance_mean") == -1 && FieldValue(surface, "distance_max") == -1,
    "distance not measured: -1");

  filter->SetErrorTolerance(0.0);
  filter->Update();
  t.Check(filter->GetSurfaceExtractCount() == 4, "tolerance back: still no extraction");

  filter->SetLeafSize(4);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 2, "a leaf size change rebuilds");
  t.Check(filter->GetSurfaceExtractCount() == 5, "a rebuilt octree extracts");

  filter->SetInputData(MakeOddSphere().Image);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 3, "new input rebuilds");
  t.Check(filter->GetSurfaceExtractCount() == 6, "new input extracts");

  std::ostringstream printed;
  filter->Print(printed);
  for (const char* line : { "Isovalue: 12\n", "SurfaceMode: 1 (interpolated)\n",
         "MeasureSurfaceDistance: off\n", "SurfaceExtractCount: 6\n", "Cached surface: yes\n" })
  {
    t.Check(printed.str().find(line) != std::string::npos,
      std::string("PrintSelf prints ") + line + printed.str());
  }

  filter->SetSurfaceMode(7);
  t.Check(filter->GetSurfaceMode() == 1, "SurfaceMode is clamped to 1");
  filter->SetSurfaceMode(-3);
  t.Check(filter->GetSurfaceMode() == 0, "SurfaceMode is clamped to 0");
  t.Check(std::string(filter->GetSurfaceModeAsString()) == "discretized", "mode name");
  return t.Result();
}
} // namespace

int TestHybridOctreeSurface(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  if (scenario == "discretized")
  {
    return Mode(vtkHybridOctreeFilter::SURFACE_MODE_DISCRETIZED);
  }
  if (scenario == "interpolated")
  {
    return Mode(vtkHybridOctreeFilter::SURFACE_MODE_INTERPOLATED);
  }
  if (scenario == "flying_edges")
  {
    return FlyingEdges();
  }
  if (scenario == "outside_range")
  {
    return OutsideRange();
  }
  if (scenario == "cache")
  {
    return Cache();
  }
  std::cerr << "unknown scenario '" << scenario
            << "': use discretized, interpolated, flying_edges, outside_range or cache\n";
  return EXIT_FAILURE;
}
