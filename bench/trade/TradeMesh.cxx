#include "TradeMesh.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace vtkrtTrade
{
namespace
{
template <class Reader>
vtkSmartPointer<vtkAlgorithm> NewReader(const std::string& path)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

/// A reader for `path` chosen by its extension; nullptr for another one.
vtkSmartPointer<vtkAlgorithm> ReaderFor(const std::string& path)
{
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  if (ext == ".ply")
  {
    return NewReader<vtkPLYReader>(path);
  }
  if (ext == ".obj")
  {
    return NewReader<vtkOBJReader>(path);
  }
  if (ext == ".stl")
  {
    return NewReader<vtkSTLReader>(path);
  }
  if (ext == ".vtp")
  {
    return NewReader<vtkXMLPolyDataReader>(path);
  }
  return nullptr;
}
}

vtkSmartPointer<vtkPolyData> DoubleTriangles(vtkPolyData* input)
{
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputData(input);
  tri->PassVertsOff();
  tri->PassLinesOff();
  tri->Update();
  vtkPolyData* t = tri->GetOutput();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(t->GetNumberOfPoints());
  for (vtkIdType i = 0; i < t->GetNumberOfPoints(); ++i)
  {
    pts->SetPoint(i, t->GetPoint(i));
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(pts);
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(t->GetPolys());
  out->SetPolys(polys);
  return out;
}

vtkSmartPointer<vtkPolyData> BumpySphere(int res)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  sphere->Update();
  auto pd = DoubleTriangles(sphere->GetOutput());
  vtkPoints* pts = pd->GetPoints();
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    const double theta = std::atan2(p[1], p[0]);
    const double phi = std::acos(std::max(-1.0, std::min(1.0, p[2])));
    const double r = 1.0 + 0.08 * std::sin(5 * theta) * std::sin(6 * phi) +
      0.02 * std::sin(23 * theta) * std::sin(19 * phi);
    pts->SetPoint(i, r * p[0], r * p[1], r * p[2]);
  }
  return pd;
}

vtkSmartPointer<vtkPolyData> Translated(vtkPolyData* mesh, const Point& offset)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    pts->SetPoint(i, p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
  }
  out->SetPoints(pts);
  out->SetPolys(mesh->GetPolys());
  return out;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  if (!vtksys::SystemTools::FileExists(path))
  {
    std::cerr << "vtkrtBenchTrade: no mesh " << path << "\n";
    return nullptr;
  }
  vtkSmartPointer<vtkAlgorithm> reader = ReaderFor(path);
  if (!reader)
  {
    std::cerr << "vtkrtBenchTrade: " << path << ": not .ply, .obj, .stl or .vtp\n";
    return nullptr;
  }
  reader->Update();
  auto* read = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!read)
  {
    std::cerr << "vtkrtBenchTrade: could not read " << path << "\n";
    return nullptr;
  }
  return DoubleTriangles(read);
}
}
