#include "vtkrtBenchEmbreeRays.h"
#include "vtkrtBenchTiming.h"

#include "vtkrtBenchEmbreeGeometry.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

namespace vtkrtBench
{
namespace
{
/// The mesh as an Embree scene (high quality, robust), at its own coordinates.
RTCScene MakeScene(RTCDevice device, vtkPolyData* mesh)
{
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  const double origin[3] = { 0.0, 0.0, 0.0 };
  AttachEmbreeTriangles(device, scene, mesh, origin);
  rtcCommitScene(scene);
  return scene;
}

/// A pinhole camera's rays: eye, and the directions to the image's corner
/// and along its rows and columns, per pixel.
struct Pinhole
{
  double Eye[3], Corner[3], Right[3], Up[3];
};

Pinhole PinholeOf(vtkCamera* camera, int width, int height)
{
  Pinhole c{};
  double dir[3], right[3], up[3];
  camera->GetPosition(c.Eye);
  camera->GetDirectionOfProjection(dir);
  vtkMath::Cross(dir, camera->GetViewUp(), right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, dir, up);
  // The view angle is vertical; a pixel is square.
  const double pixel =
    2.0 * std::tan(0.5 * vtkMath::RadiansFromDegrees(camera->GetViewAngle())) / height;
  for (int k = 0; k < 3; ++k)
  {
    c.Right[k] = right[k] * pixel;
    c.Up[k] = up[k] * pixel;
    c.Corner[k] = dir[k] - c.Right[k] * 0.5 * width - c.Up[k] * 0.5 * height;
  }
  return c;
}

/// One frame: rows of 2-pixel-high bands, 4x2 packets, over `threads`
/// threads; a hit pixel gets its facing ratio.
void TraceFrame(RTCScene scene, const Pinhole& cam, int width, int height, unsigned threads,
  std::vector<unsigned char>& image)
{
  auto work = [&](unsigned t) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (int y0 = 2 * int(t); y0 < height; y0 += 2 * int(threads))
    {
      for (int x0 = 0; x0 < width; x0 += 4)
      {
        alignas(32) RTCRayHit8 rh;
        alignas(32) int valid[8];
        for (int i = 0; i < 8; ++i)
        {
          const double px = x0 + (i % 4) + 0.5, py = y0 + (i / 4) + 0.5;
          valid[i] = (x0 + i % 4 < width && y0 + i / 4 < height) ? -1 : 0;
          rh.ray.org_x[i] = float(cam.Eye[0]);
          rh.ray.org_y[i] = float(cam.Eye[1]);
          rh.ray.org_z[i] = float(cam.Eye[2]);
          rh.ray.dir_x[i] = float(cam.Corner[0] + px * cam.Right[0] + py * cam.Up[0]);
          rh.ray.dir_y[i] = float(cam.Corner[1] + px * cam.Right[1] + py * cam.Up[1]);
          rh.ray.dir_z[i] = float(cam.Corner[2] + px * cam.Right[2] + py * cam.Up[2]);
          rh.ray.tnear[i] = 0.0f;
          rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
          rh.ray.mask[i] = 0xffffffffu;
          rh.ray.time[i] = 0.0f;
          rh.ray.flags[i] = 0;
          rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, scene, &ctx, &rh);
        for (int i = 0; i < 8; ++i)
        {
          if (!valid[i] || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID)
          {
            continue;
          }
          const float n[3] = { rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i] };
          const float d[3] = { rh.ray.dir_x[i], rh.ray.dir_y[i], rh.ray.dir_z[i] };
          const float nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
          const float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
          const float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
          const float facing = std::fabs(nd) / std::sqrt(nn * dd);
          image[std::size_t(y0 + i / 4) * width + x0 + i % 4] = static_cast<unsigned char>(255.0f * facing);
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t)
  {
    pool.emplace_back(work, t);
  }
  work(0);
  for (std::thread& th : pool)
  {
    th.join();
  }
}
}

EmbreeTiming EmbreePrimaryRays(vtkPolyData* mesh, vtkRenderer* ren, int width, int height,
  int frames, const std::function<void(vtkRenderer*, int)>& step)
{
  EmbreeTiming t;
  RTCDevice device = rtcNewDevice(nullptr);
  auto t0 = Clock::now();
  RTCScene scene = MakeScene(device, mesh);
  t.Build = 1e3 * Seconds(t0, Clock::now());
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<unsigned char> image(std::size_t(width) * height, 0);
  t0 = Clock::now();
  const double cpu0 = ProcessSeconds();
  for (int i = 0; i < frames; ++i)
  {
    step(ren, frames);
    TraceFrame(scene, PinholeOf(ren->GetActiveCamera(), width, height), width, height,
      threads, image);
  }
  t.Steady = 1e3 * Seconds(t0, Clock::now()) / std::max(1, frames);
  t.SteadyCpu = 1e3 * (ProcessSeconds() - cpu0) / std::max(1, frames);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return t;
}
}
