#include "RenderRead.h"

#include "RenderErrors.h"
#include "RenderMeshChecks.h"

#include "vtkBYUReader.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataGeometryFilter.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkGLTFReader.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkGeometryFilter.h"
#include "vtkOBJReader.h"
#include "vtkPLY.h"
#include "vtkPLYReader.h"
#include "vtkSTLReader.h"
#include "vtkXMLGenericDataObjectReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

namespace vtkrtRender
{
namespace
{
template <class Reader>
vtkSmartPointer<vtkDataObject> ReadWith(const std::string& path)
{
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutputDataObject(0);
}

using ReadFunction = vtkSmartPointer<vtkDataObject> (*)(const std::string&);

const std::map<std::string, ReadFunction>& Readers()
{
  static const std::map<std::string, ReadFunction> readers = {
    { ".vtp", ReadWith<vtkXMLPolyDataReader> },
    { ".vtu", ReadWith<vtkXMLGenericDataObjectReader> },
    { ".vti", ReadWith<vtkXMLGenericDataObjectReader> },
    { ".vts", ReadWith<vtkXMLGenericDataObjectReader> },
    { ".vtr", ReadWith<vtkXMLGenericDataObjectReader> },
    { ".vtm", ReadWith<vtkXMLGenericDataObjectReader> },
    { ".vtk", ReadWith<vtkGenericDataObjectReader> },
    { ".ply", ReadWith<vtkPLYReader> },
    { ".obj", ReadWith<vtkOBJReader> },
    { ".stl", ReadWith<vtkSTLReader> },
    { ".gltf", ReadWith<vtkGLTFReader> },
    { ".glb", ReadWith<vtkGLTFReader> },
    { ".g", ReadWith<vtkBYUReader> },
  };
  return readers;
}

// Turns the first VTK error or warning captured while reading `path` into
// our one message.
void ThrowIfCaptured(CapturingOutputWindow* output, const std::string& path)
{
  if (!output->Captured.empty())
  {
    throw Failure{ "cannot read mesh '" + path + "': " + MessageOf(output->Captured.front()),
      ExitRuntimeError };
  }
}

// A PLY strip: its point ids with -1 between strips, as the format's
// `tristrips` element stores them.
struct PlyStrip
{
  int Count;
  int* Ids;
};

// A PLY vertex as read here: only its position (vtkPLYReader has the rest).
struct PlyPosition
{
  float X[3];
};

// Reads the vertex element's positions (so the file advances past them).
void SkipPlyVertices(PlyFile* ply, char* name, int count)
{
  static const char* const axes[] = { "x", "y", "z" };
  for (int a = 0; a < 3; ++a)
  {
    PlyProperty axis = { axes[a], PLY_FLOAT, PLY_FLOAT,
      static_cast<int>(offsetof(PlyPosition, X) + a * sizeof(float)), 0, 0, 0, 0 };
    vtkPLY::ply_get_property(ply, name, &axis);
  }
  PlyPosition position;
  for (int i = 0; i < count; ++i)
  {
    vtkPLY::ply_get_element(ply, &position);
  }
}

// Appends the strips of the `tristrips` element (split at -1) to `strips`.
void ReadPlyStripElement(PlyFile* ply, char* name, int count, vtkCellArray* strips)
{
  PlyProperty indices = { "vertex_indices", PLY_INT, PLY_INT,
    static_cast<int>(offsetof(PlyStrip, Ids)), PLY_LIST, PLY_INT, PLY_INT,
    static_cast<int>(offsetof(PlyStrip, Count)) };
  vtkPLY::ply_get_property(ply, name, &indices);
  std::vector<vtkIdType> strip;
  for (int i = 0; i < count; ++i)
  {
    PlyStrip item = { 0, nullptr };
    vtkPLY::ply_get_element(ply, &item);
    for (int k = 0; k <= item.Count; ++k)
    {
      if (k == item.Count || item.Ids[k] < 0)
      {
        if (strip.size() >= 3)
        {
          strips->InsertNextCell(static_cast<vtkIdType>(strip.size()), strip.data());
        }
        strip.clear();
      }
      else
      {
        strip.push_back(item.Ids[k]);
      }
    }
    std::free(item.Ids); // allocated by vtkPLY's get_element
  }
}

// Appends each strip of the `tristrips` element of the PLY file at `path`
// (vtkPLYReader reads only `face`) to `strips`. Reads the vertex and strip
// elements in file order; stops at any other element before the strips.
void ReadPlyStrips(const std::string& path, vtkCellArray* strips)
{
  int elementCount = 0;
  char** names = nullptr;
  PlyFile* ply = vtkPLY::ply_open_for_reading(path.c_str(), &elementCount, &names);
  if (!ply)
  {
    return;
  }
  bool reading = true;
  for (int e = 0; e < elementCount; ++e)
  {
    int count = 0, properties = 0;
    vtkPLY::ply_get_element_description(ply, names[e], &count, &properties);
    if (reading && std::strcmp(names[e], "vertex") == 0)
    {
      SkipPlyVertices(ply, names[e], count);
    }
    else if (reading && std::strcmp(names[e], "tristrips") == 0)
    {
      ReadPlyStripElement(ply, names[e], count, strips);
      reading = false;
    }
    else
    {
      reading = false;
    }
    std::free(names[e]); // allocated by ply_open_for_reading
  }
  std::free(names);
  vtkPLY::ply_close(ply);
}

bool HasPlyStrips(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  std::string line;
  while (std::getline(file, line) && line.compare(0, 10, "end_header") != 0)
  {
    if (line.compare(0, 18, "element tristrips ") == 0)
    {
      return true;
    }
  }
  return false;
}

// The file's data, by the reader of its extension. Throws Failure.
vtkSmartPointer<vtkDataObject> ReadData(const std::string& path, CapturingOutputWindow* output)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    throw Failure{ "cannot read mesh '" + path + "': no such file", ExitRuntimeError };
  }
  if (!std::ifstream(path).good())
  {
    throw Failure{ "cannot read mesh '" + path + "': cannot open it", ExitRuntimeError };
  }
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  const auto reader = Readers().find(ext);
  if (reader == Readers().end())
  {
    throw Failure{ "cannot read mesh '" + path + "': unknown extension '" + ext + "' (expected " +
        MeshExtensions() + ")",
      ExitRuntimeError };
  }
  if (ext == ".ply")
  {
    // vtkPLYReader loops or aborts on data shorter than its header declares.
    CheckPlyFile(path);
  }
  else if (ext == ".stl")
  {
    CheckStlFile(path);
  }
  output->StartCapture();
  vtkSmartPointer<vtkDataObject> data = reader->second(path);
  output->StopCapture();
  ThrowIfCaptured(output, path);
  // Readers pass a face's out-of-range index through; normals and links
  // would then index past the points.
  CheckCells(data, path);
  return data;
}

// A grid's or a multiblock's outer surface as polygons.
vtkSmartPointer<vtkPolyData> SurfaceOf(
  vtkDataObject* data, const std::string& path, CapturingOutputWindow* output)
{
  vtkSmartPointer<vtkPolyData> mesh = vtkPolyData::SafeDownCast(data);
  if (mesh)
  {
    return mesh;
  }
  output->StartCapture();
  if (vtkDataSet::SafeDownCast(data))
  {
    vtkNew<vtkGeometryFilter> surface;
    surface->SetInputData(data);
    surface->Update();
    mesh = surface->GetOutput();
  }
  else if (vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkNew<vtkCompositeDataGeometryFilter> surface;
    surface->SetInputData(data);
    surface->Update();
    mesh = surface->GetOutput();
  }
  output->StopCapture();
  ThrowIfCaptured(output, path);
  return mesh;
}
} // namespace

std::string MeshExtensions()
{
  std::string list;
  for (const auto& reader : Readers())
  {
    list += (list.empty() ? "" : " ") + reader.first;
  }
  return list;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, CapturingOutputWindow* output)
{
  vtkSmartPointer<vtkPolyData> mesh = SurfaceOf(ReadData(path, output), path, output);
  if (mesh && mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0 &&
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path)) == ".ply" &&
    HasPlyStrips(path))
  {
    vtkNew<vtkCellArray> strips;
    ReadPlyStrips(path, strips);
    mesh->SetStrips(strips);
    CheckCells(mesh, path);
  }
  if (!mesh || mesh->GetNumberOfPoints() == 0)
  {
    throw Failure{ "cannot read mesh '" + path + "': it has no polygons or points to render",
      ExitRuntimeError };
  }
  return mesh;
}
} // namespace vtkrtRender
