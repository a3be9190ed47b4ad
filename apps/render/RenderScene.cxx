#include "RenderScene.h"

#include "RenderErrors.h"
#include "RenderMeshChecks.h"
#include "RenderOptions.h"
#include "vtkrtDemoGlyphs.h"

#include "vtkCellArray.h"
#include "vtkDataSet.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkGeometryFilter.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkSTLReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#ifdef VTKRT_HAVE_RAYTRACE_PASS
#include "vtkRayTracePass.h"
#endif

#include <cstdlib>
#include <fstream>
#include <vector>

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

// The data of `path` read by the reader of its extension `ext`; false for an
// extension no reader here takes.
bool ReadByExtension(const std::string& path, const std::string& ext,
  vtkSmartPointer<vtkDataObject>& data)
{
  if (ext == ".vtp")
  {
    data = ReadWith<vtkXMLPolyDataReader>(path);
  }
  else if (ext == ".vtk")
  {
    data = ReadWith<vtkGenericDataObjectReader>(path);
  }
  else if (ext == ".ply")
  {
    data = ReadWith<vtkPLYReader>(path);
  }
  else if (ext == ".obj")
  {
    data = ReadWith<vtkOBJReader>(path);
  }
  else if (ext == ".stl")
  {
    data = ReadWith<vtkSTLReader>(path);
  }
  else
  {
    return false;
  }
  return true;
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

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, CapturingOutputWindow* output)
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
  if (ext == ".ply")
  {
    // vtkPLYReader loops or aborts on data shorter than its header declares.
    CheckPlyFile(path);
  }
  output->StartCapture();
  vtkSmartPointer<vtkDataObject> data;
  if (!ReadByExtension(path, ext, data))
  {
    output->StopCapture();
    throw Failure{ "cannot read mesh '" + path + "': unknown extension '" + ext +
        "' (expected .vtp .vtk .ply .obj .stl)",
      ExitRuntimeError };
  }
  output->StopCapture();
  ThrowIfCaptured(output, path);
  // Readers pass a face's out-of-range index through; normals and links
  // would then index past the points.
  CheckPointIds(data, path);

  vtkSmartPointer<vtkPolyData> mesh = vtkPolyData::SafeDownCast(data);
  if (!mesh && vtkDataSet::SafeDownCast(data))
  {
    // A legacy .vtk grid: render its outer surface.
    output->StartCapture();
    vtkNew<vtkGeometryFilter> surface;
    surface->SetInputData(data);
    surface->Update();
    mesh = surface->GetOutput();
    output->StopCapture();
    ThrowIfCaptured(output, path);
  }
  if (!mesh || mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    throw Failure{ "cannot read mesh '" + path + "': it has no polygons to render",
      ExitRuntimeError };
  }
  return mesh;
}

vtkIdType CountTriangles(vtkPolyData* mesh)
{
  // A polygon or strip of n points is n - 2 triangles.
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    for (vtkIdType i = 0; i < cells->GetNumberOfCells(); ++i)
    {
      const vtkIdType n = cells->GetCellSize(i);
      triangles += n >= 3 ? n - 2 : 0;
    }
  }
  return triangles;
}

std::string DemoDataDirectory()
{
  // An explicit override, the source tree this was built from, then an
  // installed layout next to the executable.
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("VTKRT_DATA_DIR"))
  {
    candidates.emplace_back(env);
  }
#ifdef VTKRT_SOURCE_DATA_DIR
  candidates.emplace_back(VTKRT_SOURCE_DATA_DIR);
#endif
  const std::string exeDir =
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::GetRealPath("/proc/self/exe"));
  candidates.emplace_back(exeDir + "/../share/vtkrt");
  for (const std::string& dir : candidates)
  {
    if (vtksys::SystemTools::FileExists(dir + "/bunny.vtp", true) &&
      vtksys::SystemTools::FileExists(dir + "/demo-spheres.vtp", true))
    {
      return dir;
    }
  }
  throw Failure{ "the demo scene's data (bunny.vtp, demo-spheres.vtp) was not found; set "
                 "VTKRT_DATA_DIR to the folder holding them",
    ExitRuntimeError };
}

void AddMesh(Scene& scene, vtkPolyData* mesh, const double color[3])
{
  vtkSmartPointer<vtkPolyData> shaded = mesh;
  if (!mesh->GetPointData()->GetNormals())
  {
    // Shading normals for files without them: smooth, but split at sharp
    // edges (30 degrees) so boxes stay boxes. Cells keep their ids.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(mesh);
    normals->SplittingOn();
    normals->SetFeatureAngle(30.0);
    normals->ComputeCellNormalsOff();
    normals->Update();
    shaded = normals->GetOutput();
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(shaded);
  mapper->ScalarVisibilityOff();
  scene.MeshActor = vtkSmartPointer<vtkActor>::New();
  scene.MeshActor->SetMapper(mapper);
  scene.MeshActor->GetProperty()->SetColor(color[0], color[1], color[2]);
  scene.MeshActor->GetProperty()->SetSpecular(0.3);
  scene.MeshActor->GetProperty()->SetSpecularPower(30);
  scene.Renderer->AddActor(scene.MeshActor);
  scene.Mesh = shaded;
  scene.Triangles += CountTriangles(mesh);
}

void BuildDemo(Scene& scene, CapturingOutputWindow* output)
{
  const std::string dir = DemoDataDirectory();
  vtkSmartPointer<vtkPolyData> bunny = ReadMesh(dir + "/bunny.vtp", output);
  const double bunnyColor[3] = { 0.86, 0.82, 0.74 };
  AddMesh(scene, bunny, bunnyColor);

  // Sphere glyphs of the "radius" array, coloured by "scalar" (vtkrtDemoGlyphs.h).
  vtkNew<vtkXMLPolyDataReader> centresReader;
  centresReader->SetFileName((dir + "/demo-spheres.vtp").c_str());
  centresReader->Update();
  vtkPolyData* centres = centresReader->GetOutput();
  if (!centres || centres->GetNumberOfPoints() == 0 ||
    !centres->GetPointData()->GetArray("radius") || !centres->GetPointData()->GetArray("scalar"))
  {
    throw Failure{ "demo-spheres.vtp in '" + dir + "' lacks points or its radius/scalar arrays",
      ExitRuntimeError };
  }
  vtkSmartPointer<vtkActor> glyphActor = vtkrtDemo::NewGlyphActor(centres);
  scene.Renderer->AddActor(glyphActor);
  scene.Spheres = centres->GetNumberOfPoints();
  scene.SphereCentres = centres;
  scene.Description = "demo (" + dir + "/bunny.vtp + demo-spheres.vtp)";
}
} // namespace

void BuildScene(Scene& scene, const Options& opt, CapturingOutputWindow* output)
{
  if (opt.Demo)
  {
    BuildDemo(scene, output);
  }
  else
  {
    const double color[3] = { 0.80, 0.82, 0.88 };
    AddMesh(scene, ReadMesh(opt.MeshFile, output), color);
    scene.Description = opt.MeshFile;
  }
  scene.Renderer->SetBackground(0.32, 0.34, 0.43);
  if (opt.Mode == "raytrace")
  {
    UseRayTracing(scene.Renderer);
  }
}

bool UseRayTracing(vtkRenderer* renderer)
{
#ifdef VTKRT_HAVE_RAYTRACE_PASS
  vtkNew<vtkRayTracePass> pass;
  renderer->SetPass(pass);
  return true;
#else
  (void)renderer;
  return false;
#endif
}
} // namespace vtkrtRender
