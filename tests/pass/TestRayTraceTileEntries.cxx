// The pass's tile entry lists from the inside (pass/vtkRayTraceFootprint's
// MakeTileEntryLists), walked by the shader's C++ twins: for a turned mesh
// under perspective and parallel cameras, from inside it, in a renderer's
// viewport that is a part of the window, every pixel's camera ray (at its
// center and its four corners, where sub-pixel samples may be) finds from
// its tile's list the hit the walk from the root finds, within the stack
// the shader declares.
// TestRayTraceTileEntries <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkRayTraceFootprint.h"
#include "vtkRayTraceGeometry.h"
#include "vtkRayTracePacker.h"
#include "vtkRayTraceRecords.h"
#include "vtkRayTraceScene.h"

#include "vtkrt/core/GpuTraversal.h"

#include "vtkCamera.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPolyData.h"
#include "vtkTransform.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace vtkrtPassTest;

namespace
{
using vtkrt::core::gpu::vec2;
using vtkrt::core::gpu::vec3;

/// Every pixel's rays walked from the root and from its tile's list.
void CheckView(vtkRenderer* ren, const vtkrt::pass::Geometry& geometry, const vtkrt::pass::Instance& instance,
  const std::string& what)
{
  using namespace vtkrt;
  pass::ScenePlacements places;
  places.Geometry.Placements[&geometry] = pass::GeometryPlacement{ geometry.Serial, 0, 0, 0, 0 };
  pass::CameraFrame camera;
  auto* cam = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  // No props in the renderer: the clipping range holds the mesh wherever the eye is.
  cam->SetClippingRange(0.01, 30.0);
  camera.Set(vtkOpenGLRenderer::SafeDownCast(ren), cam, false, pass::ViewScale(cam));
  pass::FrameRecords frame;
  const std::vector<pass::Instance> instances{ instance };
  if (!pass::MakeFrameRecords(instances, places, camera, ren, frame) || !camera.AffineRays)
  {
    Check(false, what + ": frame records and affine rays");
    return;
  }
  const std::uint32_t stackSize = core::gpu::stackSizeForDepth(geometry.MaxDepth);
  const pass::TileEntryLists lists = pass::MakeTileEntryLists(camera, frame, ren, 32, 8, stackSize);
  core::gpu::ShaderInputs u;
  std::vector<std::uint32_t> nodes(geometry.Nodes.size() * 8), triangles(geometry.Triangles.size() * 12);
  std::memcpy(nodes.data(), geometry.Nodes.data(), nodes.size() * 4);
  std::memcpy(triangles.data(), geometry.Triangles.data(), triangles.size() * 4);
  u.uNodes = core::gpu::TexelBuffer(nodes);
  u.uTriangles = core::gpu::TexelBuffer(triangles);
  u.uTileEntries = core::gpu::TexelBuffer(lists.Words);
  u.uTileGrid = core::gpu::vec4(lists.Grid[0], lists.Grid[1], lists.Grid[2], lists.Grid[3]);
  const core::gpu::InstanceRecord& rec = frame.Records[0];
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  ren->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  long rays = 0, hits = 0, missed = 0, deeper = 0;
  for (int py = 0; py < size[1]; ++py)
  {
    for (int px = 0; px < size[0]; ++px)
    {
      for (int corner = 0; corner < 5; ++corner)
      {
        const double sx = corner == 0 ? 0.5 : (corner & 1), sy = corner == 0 ? 0.5 : ((corner >> 1) & 1);
        const double x = 2.0 * (px + sx) / size[0] - 1.0, y = 2.0 * (py + sy) / size[1] - 1.0;
        double o[3], d[3];
        camera.AffineRay(x, y, o, d);
        const vec3 org(static_cast<float>(o[0]), static_cast<float>(o[1]), static_cast<float>(o[2]));
        const vec3 dir(static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]));
        const vec3 localOrg = core::gpu::rowsPoint(rec.cameraToLocal[0], rec.cameraToLocal[1], rec.cameraToLocal[2], org);
        const vec3 localDir = core::gpu::rowsDir(rec.cameraToLocal[0], rec.cameraToLocal[1], rec.cameraToLocal[2], dir);
        float tRoot = 1.0f, tList = 1.0f;
        int triRoot, triList;
        vec2 uv;
        core::gpu::traverseTriangles(u, 0, localOrg, localDir, 0.0f, tRoot, triRoot, uv, false);
        u.deepestStackEntry = -1;
        const int list = core::gpu::tileListOf(u, vec2(static_cast<float>(x), static_cast<float>(y)));
        core::gpu::traverseTriangles(u, 0, localOrg, localDir, 0.0f, tList, triList, uv, false, list);
        ++rays;
        hits += triRoot >= 0 ? 1 : 0;
        missed += tList != tRoot ? 1 : 0;
        deeper += u.deepestStackEntry >= static_cast<int>(stackSize) ? 1 : 0;
      }
    }
  }
  Check(hits > rays / 10 && lists.Entries > 0,
    what + ": " + std::to_string(hits) + " of " + std::to_string(rays) + " rays hit, lists of " +
      std::to_string(lists.Entries) + " nodes");
  Check(missed == 0 && deeper == 0,
    what + ": " + std::to_string(missed) + " rays found another hit from their tile's list, " +
      std::to_string(deeper) + " walks went past the stack of " + std::to_string(stackSize));
}

void TestRootHits()
{
  using namespace vtkrt;
  const std::unique_ptr<pass::Geometry> geometry =
    pass::BuildTriangles(SphereOverFloor(96, 12), pass::TriangleBuildOptions(1, 4));
  pass::Instance instance;
  instance.Geom = geometry.get();
  vtkNew<vtkTransform> turn;
  turn->RotateY(25.0);
  turn->RotateX(10.0);
  turn->Translate(0.3, -0.2, 0.1);
  std::copy_n(turn->GetMatrix()->GetData(), 16, instance.Matrix.begin()); // both row-major
  auto win = MakeWindow(200, 150);
  vtkNew<vtkRenderer> ren;
  ren->SetViewport(0.1, 0.05, 0.9, 1.0);
  win->AddRenderer(ren);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetPosition(1.0, 3.0, 5.0);
  camera->SetFocalPoint(0.0, 0.5, 0.0);
  ren->ResetCamera(-2.0, 2.0, -1.0, 2.0, -2.0, 2.0);
  camera->Zoom(1.5);
  CheckView(ren, *geometry, instance, "perspective");
  camera->Zoom(3.0);
  camera->Azimuth(40.0);
  CheckView(ren, *geometry, instance, "zoomed, cut by the viewport's edges");
  camera->SetPosition(0.3, 0.5, 0.2); // inside the sphere
  camera->SetFocalPoint(1.0, 0.2, -1.0);
  CheckView(ren, *geometry, instance, "the eye inside the sphere");
  camera->SetPosition(0.2, 0.1, 2.5); // low over the floor: boxes across the eye plane
  camera->SetFocalPoint(0.0, 0.6, 0.0);
  camera->SetViewAngle(70.0);
  CheckView(ren, *geometry, instance, "low over the floor");
  camera->ParallelProjectionOn();
  camera->SetPosition(3.0, 4.0, 5.0);
  camera->SetFocalPoint(0.0, 0.5, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(1.6);
  camera->Roll(30.0);
  CheckView(ren, *geometry, instance, "parallel projection, rolled");
  NoVTKOutput("tile entry lists");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "RootHits", TestRootHits },
  };
  return RunCase(argc, argv, cases);
}
