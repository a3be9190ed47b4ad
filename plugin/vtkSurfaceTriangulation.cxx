#include "vtkSurfaceTriangulation.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseKey.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include "vtkrt/core/SurfaceTriangulation.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <vector>

vtkStandardNewMacro(vtkSurfaceTriangulation);
vtkInformationKeyMacro(vtkSurfaceTriangulation, TRIANGULATION, ObjectBase);

namespace
{
std::atomic<bool> Caching{ true };
std::atomic<vtkIdType> Triangulations{ 0 };

/// Guards the polydata's information (not thread-safe) and makes one
/// thread triangulate while others asking for it wait.
std::mutex& CacheMutex()
{
  static std::mutex mutex;
  return mutex;
}

/// fn(begin, end) over [0, n) on VTK's SMP pool.
struct SMPFor
{
  template <class Body>
  void operator()(std::size_t n, Body&& body) const
  {
    vtkSMPTools::For(0, static_cast<vtkIdType>(n), [&body](vtkIdType b, vtkIdType e) {
      body(static_cast<std::size_t>(b), static_cast<std::size_t>(e));
    });
  }
};

/// fn(view) with the cell array's own storage.
template <class Fn>
auto WithCellArrayView(vtkCellArray* cells, Fn&& fn)
{
  if (cells->IsStorage64Bit())
  {
    return fn(vtkrt::core::CellArrayView<vtkTypeInt64>{ cells->GetOffsetsArray64()->GetPointer(0),
      cells->GetConnectivityArray64()->GetPointer(0), cells->GetNumberOfCells() });
  }
  return fn(vtkrt::core::CellArrayView<vtkTypeInt32>{ cells->GetOffsetsArray32()->GetPointer(0),
    cells->GetConnectivityArray32()->GetPointer(0), cells->GetNumberOfCells() });
}
} // namespace

//------------------------------------------------------------------------------
vtkSurfaceTriangulation::vtkSurfaceTriangulation()
  : Triangles(new vtkrt::core::SurfaceTriangles)
{
  vtkMath::UninitializeBounds(this->FinitePointBounds);
}

//------------------------------------------------------------------------------
vtkSurfaceTriangulation::~vtkSurfaceTriangulation() = default;

//------------------------------------------------------------------------------
vtkSmartPointer<vtkSurfaceTriangulation> vtkSurfaceTriangulation::Get(vtkPolyData* pd)
{
  std::lock_guard<std::mutex> lock(CacheMutex());
  const bool caching = Caching.load();
  if (caching)
  {
    auto* kept = vtkSurfaceTriangulation::SafeDownCast(pd->GetInformation()->Get(TRIANGULATION()));
    if (kept && kept->IsCurrent(pd))
    {
      return kept;
    }
  }
  auto made = vtkSmartPointer<vtkSurfaceTriangulation>::New();
  made->Triangulate(pd);
  ++Triangulations;
  if (caching)
  {
    pd->GetInformation()->Set(TRIANGULATION(), made);
  }
  return made;
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::Release(vtkPolyData* pd)
{
  std::lock_guard<std::mutex> lock(CacheMutex());
  pd->GetInformation()->Remove(TRIANGULATION());
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::SetCaching(bool caching)
{
  Caching.store(caching);
}

//------------------------------------------------------------------------------
bool vtkSurfaceTriangulation::GetCaching()
{
  return Caching.load();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceTriangulation::GetNumberOfTriangulations()
{
  return Triangulations.load();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkSurfaceTriangulation::GetGeometryMTime(vtkPolyData* pd)
{
  // What vtkPolyData::GetMTime covers, less the point, cell and field data.
  // GetVerts() and the others never allocate (an empty polydata answers a
  // shared empty array), so this is thread-safe.
  vtkMTimeType t = pd->vtkObject::GetMTime();
  if (vtkPoints* points = pd->GetPoints())
  {
    t = std::max(t, points->GetMTime());
  }
  for (vtkCellArray* cells : { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() })
  {
    t = std::max(t, cells->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
bool vtkSurfaceTriangulation::IsCurrent(vtkPolyData* pd) const
{
  const void* parts[5] = { pd->GetPoints(), pd->GetVerts(), pd->GetLines(), pd->GetPolys(),
    pd->GetStrips() };
  return std::equal(parts, parts + 5, this->SourceParts) &&
    vtkSurfaceTriangulation::GetGeometryMTime(pd) <= this->SourceMTime;
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::Triangulate(vtkPolyData* pd)
{
  this->SourceMTime = vtkSurfaceTriangulation::GetGeometryMTime(pd);
  const void* parts[5] = { pd->GetPoints(), pd->GetVerts(), pd->GetLines(), pd->GetPolys(),
    pd->GetStrips() };
  std::copy(parts, parts + 5, this->SourceParts);
  const vtkIdType firstPoly = pd->GetNumberOfVerts() + pd->GetNumberOfLines();
  const vtkIdType points = pd->GetNumberOfPoints();
  *this->Triangles = WithCellArrayView(pd->GetPolys(), [&](const auto& polys) {
    return WithCellArrayView(pd->GetStrips(), [&](const auto& strips) {
      return vtkrt::core::triangulateSurface(polys, firstPoly, strips, points, SMPFor());
    });
  });
  this->ComputeFinitePointBounds(pd);
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::ComputeFinitePointBounds(vtkPolyData* pd)
{
  vtkPoints* pts = pd->GetPoints();
  const vtkIdType n = pts ? pts->GetNumberOfPoints() : 0;
  vtkrt::core::AABB<double> box;
  std::size_t nonFinite = 0;
  if (n > 0)
  {
    vtkDataArray* data = pts->GetData();
    if (auto* f = vtkFloatArray::FastDownCast(data))
    {
      box = vtkrt::core::finitePointBounds(f->GetPointer(0), static_cast<std::size_t>(n), nonFinite, SMPFor());
    }
    else if (auto* d = vtkDoubleArray::FastDownCast(data))
    {
      box = vtkrt::core::finitePointBounds(d->GetPointer(0), static_cast<std::size_t>(n), nonFinite, SMPFor());
    }
    else
    {
      std::vector<double> xyz(3 * static_cast<std::size_t>(n));
      vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
        for (vtkIdType i = b; i < e; ++i)
        {
          pts->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
        }
      });
      box = vtkrt::core::finitePointBounds(xyz.data(), static_cast<std::size_t>(n), nonFinite, SMPFor());
    }
  }
  this->NonFinitePoints = static_cast<vtkIdType>(nonFinite);
  if (box.isEmpty())
  {
    vtkMath::UninitializeBounds(this->FinitePointBounds);
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->FinitePointBounds[2 * a] = box.min[a];
    this->FinitePointBounds[2 * a + 1] = box.max[a];
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceTriangulation::GetNumberOfTriangles() const
{
  return static_cast<vtkIdType>(this->Triangles->count);
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceTriangulation::GetNumberOfDegenerateCells() const
{
  return static_cast<vtkIdType>(this->Triangles->degenerateCells);
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceTriangulation::GetNumberOfInvalidPointIdCells() const
{
  return static_cast<vtkIdType>(this->Triangles->invalidPointIdCells);
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::GetFinitePointBounds(double bounds[6]) const
{
  std::copy(this->FinitePointBounds, this->FinitePointBounds + 6, bounds);
}

//------------------------------------------------------------------------------
size_t vtkSurfaceTriangulation::GetMemorySize() const
{
  return this->Triangles->memoryBytes();
}

//------------------------------------------------------------------------------
void vtkSurfaceTriangulation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkrt::core::SurfaceTriangles& t = *this->Triangles;
  os << indent << "Triangles: " << t.count << (t.uniform ? " (one a cell)" : "") << "\n";
  os << indent << "DegenerateCells: " << t.degenerateCells << "\n";
  os << indent << "InvalidPointIdCells: " << t.invalidPointIdCells << "\n";
  os << indent << "NonFinitePoints: " << this->NonFinitePoints << "\n";
  os << indent << "FinitePointBounds: (" << this->FinitePointBounds[0] << ", "
     << this->FinitePointBounds[1] << ", " << this->FinitePointBounds[2] << ", "
     << this->FinitePointBounds[3] << ", " << this->FinitePointBounds[4] << ", "
     << this->FinitePointBounds[5] << ")\n";
  os << indent << "SourceMTime: " << this->SourceMTime << "\n";
  os << indent << "MemorySize: " << this->GetMemorySize() << " bytes\n";
  os << indent << "Caching: " << (GetCaching() ? "On" : "Off") << "\n";
  os << indent << "NumberOfTriangulations (process): " << GetNumberOfTriangulations() << "\n";
}
