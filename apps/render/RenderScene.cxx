#include "RenderScene.h"

#include "RenderColoring.h"
#include "RenderErrors.h"
#include "RenderOptions.h"
#include "RenderProgress.h"
#include "RenderRead.h"
#include "vtkrtDemoGlyphs.h"

#include "vtkCellArray.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#ifdef VTKRT_HAVE_RAYTRACE_PASS
#include "vtkRayTracePass.h"
#endif

#include <cstdlib>
#include <vector>

namespace vtkrtRender
{
namespace
{
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

// A point cloud (no polygons): one vertex a point, drawn (and traced) as
// spheres of the point size.
vtkSmartPointer<vtkPolyData> AsPointCloud(vtkPolyData* mesh)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(mesh->GetPoints());
  cloud->GetPointData()->PassData(mesh->GetPointData());
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    vertices->InsertNextCell(1, &i);
  }
  cloud->SetVerts(vertices);
  return cloud;
}

// Shading normals for files without them: smooth, but split at sharp edges
// (30 degrees) so boxes stay boxes. Cells keep their ids.
vtkSmartPointer<vtkPolyData> WithNormals(vtkPolyData* mesh)
{
  if (mesh->GetPointData()->GetNormals())
  {
    return mesh;
  }
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(mesh);
  normals->SplittingOn();
  normals->SetFeatureAngle(30.0);
  normals->ComputeCellNormalsOff();
  normals->Update();
  return normals->GetOutput();
}

void AddMesh(Scene& scene, const std::string& file, vtkPolyData* mesh, const double color[3],
  const LookOptions& look)
{
  const bool cloud = mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0;
  vtkSmartPointer<vtkPolyData> shaded = cloud ? AsPointCloud(mesh) : WithNormals(mesh);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(shaded);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkProperty* property = actor->GetProperty();
  property->SetColor(color[0], color[1], color[2]);
  property->SetSpecular(0.3);
  property->SetSpecularPower(30);
  property->SetOpacity(look.Opacity);
  property->SetEdgeVisibility(look.Edges);
  property->SetPointSize(static_cast<float>(look.PointSize));
  property->SetRenderPointsAsSpheres(cloud);
  scene.Renderer->AddActor(actor);
  const bool computed = shaded->GetPointData()->GetNormals() && !mesh->GetPointData()->GetNormals();
  scene.Meshes.push_back(SceneMesh{ file, shaded, actor, computed });
  scene.Triangles += CountTriangles(mesh);
  scene.Points += cloud ? mesh->GetNumberOfPoints() : 0;
}

void BuildDemo(Scene& scene, CapturingOutputWindow* output, const LookOptions& look)
{
  const std::string dir = DemoDataDirectory();
  vtkSmartPointer<vtkPolyData> bunny = ReadMesh(dir + "/bunny.vtp", output);
  const double bunnyColor[3] = { 0.86, 0.82, 0.74 };
  AddMesh(scene, dir + "/bunny.vtp", bunny, look.ColorGiven ? look.Color.data() : bunnyColor, look);

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

void BuildFiles(Scene& scene, const Options& opt, CapturingOutputWindow* output)
{
  for (const std::string& file : opt.MeshFiles)
  {
    Progress::Begin("reading " + vtksys::SystemTools::GetFilenameName(file));
    vtkSmartPointer<vtkPolyData> mesh = ReadMesh(file, output);
    Progress::End();
    AddMesh(scene, file, mesh, opt.Look.Color.data(), opt.Look);
    scene.Description += (scene.Description.empty() ? "" : " + ") + file;
  }
}
} // namespace

void BuildScene(Scene& scene, const Options& opt, CapturingOutputWindow* output)
{
  if (opt.Demo)
  {
    BuildDemo(scene, output, opt.Look);
  }
  else
  {
    BuildFiles(scene, opt, output);
  }
  if (opt.Scalars.Enabled)
  {
    ColorByScalars(scene, opt.Scalars);
  }
  const Vector3& bg = opt.Look.Background;
  scene.Renderer->SetBackground(bg[0], bg[1], bg[2]);
  if (opt.Mode == "raytrace")
  {
    UseRayTracing(scene.Renderer, opt);
  }
}

bool UseRayTracing(vtkRenderer* renderer, const Options& opt)
{
#ifdef VTKRT_HAVE_RAYTRACE_PASS
  vtkNew<vtkRayTracePass> pass;
  // Only the knobs given on the command line: the rest keep the pass's own.
  const TraceOptions& trace = opt.Trace;
  if (!trace.Preset.empty())
  {
    pass->SetQualityPreset(trace.Preset == "interactive" ? vtkRayTracePass::INTERACTIVE
        : trace.Preset == "balanced"                     ? vtkRayTracePass::BALANCED
                                                         : vtkRayTracePass::EXACT);
  }
  if (opt.Samples > 0)
  {
    pass->SetSamplesPerPixel(opt.Samples);
  }
  if (trace.Shadows)
  {
    pass->SetShadows(true);
  }
  if (trace.AmbientOcclusion >= 0)
  {
    pass->SetAmbientOcclusionSamples(trace.AmbientOcclusion);
  }
  if (trace.Progressive > 0)
  {
    pass->SetProgressiveAccumulation(true);
  }
  if (!trace.Precision.empty())
  {
    pass->SetPrecisionMode(
      trace.Precision == "world" ? vtkRayTracePass::WORLD : vtkRayTracePass::CAMERA_RELATIVE);
  }
  renderer->SetPass(pass);
  return true;
#else
  (void)renderer;
  (void)opt;
  return false;
#endif
}
} // namespace vtkrtRender
