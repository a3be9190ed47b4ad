// Tests of vtkRayTracePass's speed/accuracy knobs (sub-pixel sampling and
// progressive accumulation, ...): each case asserts what the knob changes in
// the image, that its shader code is present only when the knob is used, and
// compares against a baseline under data/baselines/.
// TestRayTracePassKnobs <Case>.
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkExtractEdges.h"
#include "vtkGlyph3DMapper.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkLight.h"
#include "vtkPlaneSource.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <vector>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
/// Pixels whose red channel is strictly between lo and hi.
long CountIntermediatePixels(vtkImageData* image, int lo, int hi)
{
  int d[3];
  image->GetDimensions(d);
  const int comps = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  long count = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1]; ++i)
  {
    count += (p[i * comps] > lo && p[i * comps] < hi) ? 1 : 0;
  }
  return count;
}

bool HasDefine(vtkRayTracePass* pass, const std::string& define)
{
  return std::string(pass->GetLastFragmentShaderSource()).find("#define " + define) !=
    std::string::npos;
}

/// Sub-pixel sampling and progressive accumulation, on an unlit white sphere
/// over black (every pixel of a one-ray image is 0 or 255).
void TestSampling()
{
  const int size = 160;
  auto win = MakeWindow(size, size);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.0, 0.0, 0.0);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  ren->AddActor(actor);
  ren->ResetCamera();

  // One centered ray per pixel, straight to the framebuffer.
  vtkNew<vtkRayTracePass> direct;
  ren->SetPass(direct);
  win->Render();
  auto single = Grab(win);
  const float centerDepth = win->GetZbufferDataAtPoint(size / 2, size / 2);
  Check(direct->GetAccumulatedFrames() == 0, "direct: no accumulation");
  Check(!HasDefine(direct, "VTKRT_SAMPLES_PER_PIXEL"), "direct: no sampling code in the shader");
  const long hard = CountIntermediatePixels(single, 16, 240);
  Check(hard == 0, "direct: a one-ray silhouette is hard (" + std::to_string(hard) +
      " intermediate pixels)");

  // Progressive, 1 sample per frame: frame 1 is the pixel center again.
  vtkNew<vtkRayTracePass> progressive;
  progressive->ProgressiveAccumulationOn();
  ren->SetPass(progressive);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "progressive: first frame accumulates 1");
  Check(HasDefine(progressive, "VTKRT_SAMPLES_PER_PIXEL 1"), "progressive: sampling code compiled");
  auto first = Grab(win);
  const long firstDiff = CountDifferingPixels(first, single, 1);
  Check(firstDiff == 0,
    "progressive frame 1 equals the one-ray image (" + std::to_string(firstDiff) + " differ)");
  const int n = 8;
  for (int k = 1; k < n; ++k)
  {
    win->Render();
  }
  Check(progressive->GetAccumulatedFrames() == n,
    "progressive: " + std::to_string(progressive->GetAccumulatedFrames()) + " frames accumulated, " +
      std::to_string(n) + " expected");
  Check(progressive->GetLastShaderCompiles() == 0 && progressive->GetLastBVHBuilds() == 0,
    "progressive: unchanged frames compile and build nothing");
  auto accumulated = Grab(win);

  // One frame of n samples: the same sample sequence, so the same image
  // (up to float summation order: 1/255 per channel).
  vtkNew<vtkRayTracePass> sampled;
  sampled->SetSamplesPerPixel(n);
  ren->SetPass(sampled);
  win->Render();
  Check(sampled->GetAccumulatedFrames() == 1, "sampled: one frame, no progressive accumulation");
  auto multi = Grab(win);
  const float sampledDepth = win->GetZbufferDataAtPoint(size / 2, size / 2);
  Check(centerDepth < 1.0f && std::abs(sampledDepth - centerDepth) < 1e-3f,
    "sampled: the hit's depth is written (" + std::to_string(sampledDepth) + " vs one ray " +
      std::to_string(centerDepth) + ")");
  const long sameDiff = CountDifferingPixels(accumulated, multi, 1);
  Check(sameDiff == 0,
    std::to_string(n) + " frames of 1 sample equal 1 frame of " + std::to_string(n) +
      " samples within 1/255 (" + std::to_string(sameDiff) + " differ)");
  const long soft = CountIntermediatePixels(multi, 16, 240);
  // The silhouette circle (radius ~ 1/3 of the image) crosses ~2*pi*r pixels.
  const long perimeter = static_cast<long>(2.0 * 3.14159 * size / 3.5);
  Check(soft > perimeter / 2,
    "sampled: silhouette pixels take intermediate values (" + std::to_string(soft) + " > " +
      std::to_string(perimeter / 2) + ")");
  win->Render();
  Check(sampled->GetAccumulatedFrames() == 1, "sampled without progressive: every frame restarts");
  Check(vtkrtCompareWithBaseline(multi, "pass_Sampling") == 1, "sampled: matches its baseline");

  // Any change restarts the accumulation.
  ren->SetPass(progressive);
  win->Render();
  win->Render();
  Check(progressive->GetAccumulatedFrames() >= 2, "progressive: accumulating again");
  ren->GetActiveCamera()->Azimuth(5.0);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "camera moved: accumulation restarts");

  // A screenshot as applications take it (vtkWindowToImageFilter renders
  // again and leaves the camera's view angle rounded to float) continues
  // the accumulation (it restarted before); a camera moved by a hundredth
  // of a degree still restarts it.
  win->Render();
  vtkNew<vtkWindowToImageFilter> shot;
  shot->SetInput(win);
  shot->Update();
  Check(progressive->GetAccumulatedFrames() == 3,
    "a screenshot continues the accumulation (" + std::to_string(progressive->GetAccumulatedFrames()) +
      " frames, 3 expected)");
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 4,
    "and the frame after it (" + std::to_string(progressive->GetAccumulatedFrames()) + " frames, 4 expected)");
  // A screenshot at twice the size renders four tiles with cameras of their
  // own: each tile accumulates as many frames as the image on screen had,
  // so its silhouette is as soft (with one frame a tile it was hard).
  vtkNew<vtkWindowToImageFilter> scaledShot;
  scaledShot->SetInput(win);
  scaledShot->SetScale(2);
  scaledShot->Update();
  const long scaledSoft = CountIntermediatePixels(scaledShot->GetOutput(), 16, 240);
  const long scaledPerimeter = static_cast<long>(2.0 * 3.14159 * 2 * size / 3.5);
  Check(progressive->GetAccumulatedFrames() == 4 && scaledSoft > scaledPerimeter / 2,
    "a screenshot at scale 2: each tile accumulates the 4 frames on screen (" +
      std::to_string(progressive->GetAccumulatedFrames()) + " frames, " + std::to_string(scaledSoft) +
      " intermediate pixels > " + std::to_string(scaledPerimeter / 2) + ")");
  ren->GetActiveCamera()->Azimuth(0.01);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "camera moved by 0.01 degree: accumulation restarts");
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 2, "unchanged after the move: 2 frames");
  actor->GetProperty()->SetColor(1.0, 0.5, 0.5);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "property changed: accumulation restarts");
  win->Render();
  sphere->SetThetaResolution(40);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "data changed: accumulation restarts");
  win->Render();
  win->SetSize(size + 20, size);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "window resized: accumulation restarts");
  win->Render();
  progressive->SetSamplesPerPixel(2);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "samples per pixel changed: restarts");

  // Depth: a raster grid of lines through the sphere's center is hidden by
  // the sphere's front half with sampling as without (a wrong depth would
  // show the grid's lines across the sphere).
  vtkNew<vtkPlaneSource> grid;
  grid->SetOrigin(-1.0, -1.0, 0.0);
  grid->SetPoint1(1.0, -1.0, 0.0);
  grid->SetPoint2(-1.0, 1.0, 0.0);
  grid->SetResolution(8, 8);
  vtkNew<vtkExtractEdges> gridLines; // lines: raster draws them
  gridLines->SetInputConnection(grid->GetOutputPort());
  vtkNew<vtkPolyDataMapper> gridMapper;
  gridMapper->SetInputConnection(gridLines->GetOutputPort());
  vtkNew<vtkActor> wire;
  wire->SetMapper(gridMapper);
  wire->GetProperty()->LightingOff();
  wire->GetProperty()->SetColor(0.0, 1.0, 0.0);
  ren->AddActor(wire);
  ren->SetPass(direct);
  win->Render();
  auto gridDirect = Grab(win);
  ren->SetPass(sampled);
  win->Render();
  auto gridSampled = Grab(win);
  const long gridDiff = CountDifferingPixels(gridDirect, gridSampled, 64);
  Check(gridDiff >= 0 && gridDiff < perimeter,
    "sampled depth composites raster like one ray (" + std::to_string(gridDiff) + " pixels differ, < " +
      std::to_string(perimeter) + ")");

  // A renderer on the right half of its window: the accumulation buffer
  // covers the renderer's viewport and resolves onto it.
  ren->RemoveActor(wire);
  auto halfWin = MakeWindow(2 * size, size);
  vtkNew<vtkRenderer> half;
  half->SetViewport(0.5, 0.0, 1.0, 1.0);
  half->SetBackground(0.0, 0.0, 0.3);
  half->AddActor(actor);
  half->ResetCamera();
  halfWin->AddRenderer(half);
  vtkNew<vtkRayTracePass> halfDirect;
  half->SetPass(halfDirect);
  halfWin->Render();
  auto halfOne = Grab(halfWin);
  vtkNew<vtkRayTracePass> halfSampled;
  halfSampled->SetSamplesPerPixel(4);
  half->SetPass(halfSampled);
  halfWin->Render();
  auto halfFour = Grab(halfWin);
  const long halfDiff = CountDifferingPixels(halfOne, halfFour, 64);
  Check(halfDiff >= 0 && halfDiff < perimeter,
    "sub-viewport: sampled image lines up with one ray (" + std::to_string(halfDiff) +
      " pixels differ)");
  half->SetPass(nullptr);
  NoVTKOutput("Sampling");
  ren->SetPass(nullptr);
}
/// The red channel at the pixel showing world point (x, y, z).
int RedAt(vtkRenderer* ren, vtkImageData* image, double x, double y, double z)
{
  ren->SetWorldPoint(x, y, z, 1.0);
  ren->WorldToDisplay();
  double d[3];
  ren->GetDisplayPoint(d);
  int dims[3];
  image->GetDimensions(dims);
  const int i = std::min(std::max(static_cast<int>(d[0]), 0), dims[0] - 1);
  const int j = std::min(std::max(static_cast<int>(d[1]), 0), dims[1] - 1);
  return static_cast<const unsigned char*>(image->GetScalarPointer(i, j, 0))[0];
}

/// Mean red channel over the (2r+1)^2 pixels around world point (x, y, z).
double MeanRedAround(vtkRenderer* ren, vtkImageData* image, double x, double y, double z, int r)
{
  ren->SetWorldPoint(x, y, z, 1.0);
  ren->WorldToDisplay();
  double d[3];
  ren->GetDisplayPoint(d);
  int dims[3];
  image->GetDimensions(dims);
  double sum = 0.0;
  int count = 0;
  for (int j = static_cast<int>(d[1]) - r; j <= static_cast<int>(d[1]) + r; ++j)
  {
    for (int i = static_cast<int>(d[0]) - r; i <= static_cast<int>(d[0]) + r; ++i)
    {
      if (i >= 0 && j >= 0 && i < dims[0] && j < dims[1])
      {
        sum += static_cast<const unsigned char*>(image->GetScalarPointer(i, j, 0))[0];
        ++count;
      }
    }
  }
  return count ? sum / count : -1.0;
}

/// Hard shadows: a sphere over a floor, lit by one directional scene light
/// from above and behind; the shadow falls in front of the sphere.
void TestShadows()
{
  auto win = MakeWindow(200, 160);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.2, 0.3, 0.4);
  ren->AddActor(FloorActor(3.0));
  auto ball = SphereActor(0.0, 1.0, 0.0, 0.5);
  ball->GetProperty()->SetColor(1.0, 0.6, 0.3);
  ren->AddActor(ball);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(0.5, 2.0, -1.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  ren->AddLight(light);
  ren->GetActiveCamera()->SetPosition(0.0, 3.0, 6.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.3, 0.0);
  ren->ResetCameraClippingRange();

  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(!HasDefine(pass, "VTKRT_SHADOWS"), "shadows off: no shadow code in the shader");
  auto unshadowed = Grab(win);
  pass->ShadowsOn();
  win->Render();
  Check(HasDefine(pass, "VTKRT_SHADOWS"), "shadows on: shadow code compiled");
  auto shadowed = Grab(win);
  // The renderer's UseShadows (raster's shadow maps) asks for them too.
  pass->ShadowsOff();
  ren->UseShadowsOn();
  win->Render();
  Check(CountDifferingPixels(Grab(win), shadowed, 0) == 0,
    "the renderer's UseShadows: the same shadows");
  ren->UseShadowsOff();
  pass->ShadowsOn();

  // The shadow's center: the sphere's center projected along the light.
  const int lit = RedAt(ren, shadowed, 1.5, 0.0, 1.0);
  const int dark = RedAt(ren, shadowed, -0.25, 0.0, 0.5);
  const int darkBefore = RedAt(ren, unshadowed, -0.25, 0.0, 0.5);
  Check(lit - dark > 100, "shadow: shadowed floor " + std::to_string(dark) +
      " much darker than lit floor " + std::to_string(lit));
  Check(std::abs(darkBefore - lit) <= 2,
    "without shadows the same floor point is lit (" + std::to_string(darkBefore) + ")");
  // No acne: lit floor points all over the image keep the unshadowed color.
  int worst = 0;
  for (double x : { -2.5, -2.0, -1.5, 1.5, 2.0, 2.5 })
  {
    for (double z : { -2.0, -1.0, 0.0, 1.0, 2.0 })
    {
      worst = std::max(worst, std::abs(RedAt(ren, shadowed, x, 0.0, z) - lit));
      worst = std::max(
        worst, std::abs(RedAt(ren, shadowed, x, 0.0, z) - RedAt(ren, unshadowed, x, 0.0, z)));
    }
  }
  Check(worst <= 2, "no shadow acne: lit floor uniform within 2/255 (worst " +
      std::to_string(worst) + ")");
  // The sphere does not shadow its own lit top.
  const int top = RedAt(ren, shadowed, 0.0, 1.5, 0.0);
  const int topBefore = RedAt(ren, unshadowed, 0.0, 1.5, 0.0);
  Check(std::abs(top - topBefore) <= 2 && top > 100,
    "no self-shadowing on the lit sphere (" + std::to_string(top) + " vs " +
      std::to_string(topBefore) + ")");
  // Only darker: shadows never brighten a pixel.
  Check(CountDifferingPixels(shadowed, unshadowed, 2) > 0, "shadows change the image");
  Check(vtkrtCompareWithBaseline(shadowed, "pass_Shadows") == 1, "shadows: matches its baseline");

  // Many instances (a top-level BVH): the same shadows. Extra spheres below
  // the floor, out of view and out of the light's way.
  std::vector<vtkSmartPointer<vtkActor>> extras;
  for (int k = 0; k < 9; ++k)
  {
    auto extra = vtkSmartPointer<vtkActor>::New();
    extra->SetMapper(ball->GetMapper());
    extra->SetPosition(k - 4.0, -20.0, 0.0);
    ren->AddActor(extra);
    extras.push_back(extra);
  }
  win->Render();
  Check(pass->GetLastTracedInstances() == 11 && pass->GetLastTopLevelBuilds() == 1,
    "top level: 11 instances traced (" + std::to_string(pass->GetLastTracedInstances()) + ")");
  auto manyShadowed = Grab(win);
  const long manyDiff = CountDifferingPixels(manyShadowed, shadowed, 2);
  Check(manyDiff == 0,
    "top level: the same shadowed image (" + std::to_string(manyDiff) + " pixels differ)");
  for (const auto& extra : extras)
  {
    ren->RemoveActor(extra);
  }

  // A scene a thousand times larger: offsets scale with the coordinates.
  for (vtkActor* a : { ball.GetPointer() })
  {
    a->SetScale(1000.0);
  }
  vtkActor* floorActor = nullptr;
  {
    vtkActorCollection* actors = ren->GetActors();
    actors->InitTraversal();
    while (vtkActor* a = actors->GetNextActor())
    {
      if (a != ball.GetPointer())
      {
        floorActor = a;
      }
    }
  }
  floorActor->SetScale(1000.0);
  ren->GetActiveCamera()->SetPosition(0.0, 3000.0, 6000.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 300.0, 0.0);
  ren->ResetCameraClippingRange();
  win->Render();
  auto large = Grab(win);
  const int largeLit = RedAt(ren, large, 1500.0, 0.0, 1000.0);
  const int largeDark = RedAt(ren, large, -250.0, 0.0, 500.0);
  int largeWorst = 0;
  for (double x : { -2500.0, -2000.0, -1500.0, 1500.0, 2000.0, 2500.0 })
  {
    for (double z : { -2000.0, -1000.0, 0.0, 1000.0, 2000.0 })
    {
      largeWorst = std::max(largeWorst, std::abs(RedAt(ren, large, x, 0.0, z) - largeLit));
    }
  }
  Check(largeLit - largeDark > 100 && largeWorst <= 2,
    "1000x scene: shadow " + std::to_string(largeDark) + " vs lit " + std::to_string(largeLit) +
      ", lit floor uniform (worst " + std::to_string(largeWorst) + ")");
  NoVTKOutput("Shadows");
  ren->SetPass(nullptr);

  // Analytic spheres (a sphere glyph) cast and receive shadows the same way.
  auto win2 = MakeWindow(200, 160);
  vtkNew<vtkRenderer> ren2;
  win2->AddRenderer(ren2);
  ren2->AddActor(FloorActor(3.0));
  vtkNew<vtkPoints> centers;
  centers->InsertNextPoint(0.0, 1.0, 0.0);
  vtkNew<vtkPolyData> centerData;
  centerData->SetPoints(centers);
  vtkNew<vtkSphereSource> glyphSource;
  glyphSource->SetRadius(0.5);
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centerData);
  glyphs->SetSourceConnection(glyphSource->GetOutputPort());
  glyphs->ScalingOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphs);
  ren2->AddActor(glyphActor);
  vtkNew<vtkLight> light2;
  light2->SetLightTypeToSceneLight();
  light2->SetPosition(0.5, 2.0, -1.0);
  light2->SetFocalPoint(0.0, 0.0, 0.0);
  ren2->AddLight(light2);
  ren2->GetActiveCamera()->SetPosition(0.0, 3.0, 6.0);
  ren2->GetActiveCamera()->SetFocalPoint(0.0, 0.3, 0.0);
  ren2->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass2;
  pass2->ShadowsOn();
  ren2->SetPass(pass2);
  win2->Render();
  auto glyphShadowed = Grab(win2);
  Check(std::string(pass2->GetLastFeatureKey()).find("S1") != std::string::npos,
    "glyph scene traces analytic spheres");
  const int glyphLit = RedAt(ren2, glyphShadowed, 1.5, 0.0, 1.0);
  const int glyphDark = RedAt(ren2, glyphShadowed, -0.25, 0.0, 0.5);
  const int glyphTop = RedAt(ren2, glyphShadowed, 0.0, 1.5, 0.0);
  Check(glyphLit - glyphDark > 100 && glyphTop > 100,
    "analytic sphere: shadow " + std::to_string(glyphDark) + " vs lit floor " +
      std::to_string(glyphLit) + ", lit top " + std::to_string(glyphTop));
  NoVTKOutput("Shadows (spheres)");
  ren2->SetPass(nullptr);
}

/// Ambient occlusion: a cube on a floor under the headlight; the floor at
/// the cube's foot (a crease) is darker than open floor.
void TestAmbientOcclusion()
{
  auto win = MakeWindow(200, 160);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(FloorActor(3.0));
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(0.0, 0.5, 0.0);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> box;
  box->SetMapper(cubeMapper);
  ren->AddActor(box);
  ren->GetActiveCamera()->SetPosition(1.0, 3.0, 5.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.3, 0.0);
  ren->ResetCameraClippingRange();

  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  auto plain = Grab(win);
  Check(HasDefine(pass, "VTKRT_AMBIENT_OCCLUSION_SAMPLES 0"), "occlusion off: no occlusion rays");
  pass->SetAmbientOcclusionSamples(16);
  pass->SetAmbientOcclusionRadius(0.5);
  pass->SetSamplesPerPixel(4);
  win->Render();
  Check(HasDefine(pass, "VTKRT_AMBIENT_OCCLUSION_SAMPLES 16"), "occlusion on: 16 rays compiled");
  auto occluded = Grab(win);
  // Floor just in front of the cube's front face (z = 0.5) vs open floor
  // (farther than the radius from the cube), 3x3 pixel means.
  const double crease = MeanRedAround(ren, occluded, 0.0, 0.0, 0.62, 1);
  const double open = MeanRedAround(ren, occluded, 1.2, 0.0, 1.5, 1);
  const double creasePlain = MeanRedAround(ren, plain, 0.0, 0.0, 0.62, 1);
  const double openPlain = MeanRedAround(ren, plain, 1.2, 0.0, 1.5, 1);
  Check(std::abs(creasePlain - openPlain) <= 3,
    "without occlusion crease and open floor match (" + std::to_string(creasePlain) + ", " +
      std::to_string(openPlain) + ")");
  Check(crease < 0.85 * open, "crease " + std::to_string(crease) + " darker than open floor " +
      std::to_string(open));
  Check(std::abs(open - openPlain) <= 0.05 * openPlain,
    "open floor barely occluded (" + std::to_string(open) + " vs " + std::to_string(openPlain) + ")");
  Check(vtkrtCompareWithBaseline(occluded, "pass_AmbientOcclusion", 20.0) == 1,
    "occlusion: matches its baseline");

  // A radius past the scene's diagonal (under 10 here) occludes as
  // the diagonal does, up to VTK_DOUBLE_MAX (an "unbounded" radius), which
  // is past float's range.
  std::vector<vtkSmartPointer<vtkImageData>> far;
  for (const double radius : { 10.0, 1e38, VTK_DOUBLE_MAX })
  {
    pass->SetAmbientOcclusionRadius(radius);
    win->Render();
    far.push_back(Grab(win));
  }
  Check(RootMeanSquareError(far[0], far[1]) == 0.0 && RootMeanSquareError(far[0], far[2]) == 0.0 &&
      RootMeanSquareError(far[0], occluded) > 0.5,
    "radii 10, 1e38 and VTK_DOUBLE_MAX occlude alike (RMSE " + std::to_string(RootMeanSquareError(far[0], far[1])) +
      ", " + std::to_string(RootMeanSquareError(far[0], far[2])) + "), unlike 0.5 (" +
      std::to_string(RootMeanSquareError(far[0], occluded)) + ")");
  pass->SetAmbientOcclusionRadius(0.5);

  // Progressive accumulation converges: the pixel-to-pixel noise of the
  // partly occluded floor in front of the cube falls with the frames.
  pass->SetSamplesPerPixel(1);
  pass->SetAmbientOcclusionSamples(4);
  pass->ProgressiveAccumulationOn();
  auto noise = [&](vtkImageData* image) {
    ren->SetWorldPoint(0.0, 0.0, 0.8, 1.0);
    ren->WorldToDisplay();
    double d[3];
    ren->GetDisplayPoint(d);
    double sum = 0.0;
    for (int j = static_cast<int>(d[1]) - 5; j <= static_cast<int>(d[1]) + 5; ++j)
    {
      for (int i = static_cast<int>(d[0]) - 8; i <= static_cast<int>(d[0]) + 8; ++i)
      {
        const auto* a = static_cast<const unsigned char*>(image->GetScalarPointer(i, j, 0));
        const auto* b = static_cast<const unsigned char*>(image->GetScalarPointer(i + 1, j, 0));
        sum += std::abs(int(a[0]) - int(b[0]));
      }
    }
    return sum;
  };
  win->Render();
  const double noisy = noise(Grab(win));
  for (int k = 1; k < 16; ++k)
  {
    win->Render();
  }
  const double converged = noise(Grab(win));
  Check(pass->GetAccumulatedFrames() == 16 && converged < 0.5 * noisy,
    "accumulated occlusion converges: neighbor noise " + std::to_string(noisy) + " -> " +
      std::to_string(converged) + " after " + std::to_string(pass->GetAccumulatedFrames()) +
      " frames");

  // The renderer's SSAO (raster's screen-space occlusion), with the pass's
  // own occlusion off, is traced: 4 occlusion rays within SSAORadius (it
  // was ignored).
  pass->ProgressiveAccumulationOff();
  pass->SetAmbientOcclusionSamples(0);
  pass->SetSamplesPerPixel(4);
  win->Render();
  auto none = Grab(win);
  ren->UseSSAOOn();
  ren->SetSSAORadius(0.5);
  win->Render();
  Check(HasDefine(pass, "VTKRT_AMBIENT_OCCLUSION_SAMPLES 4"), "the renderer's SSAO: 4 occlusion rays compiled");
  auto ssao = Grab(win);
  const double ssaoCrease = MeanRedAround(ren, ssao, 0.0, 0.0, 0.62, 1);
  const double ssaoOpen = MeanRedAround(ren, ssao, 1.2, 0.0, 1.5, 1);
  Check(ssaoCrease < 0.85 * ssaoOpen,
    "the renderer's SSAO: crease " + std::to_string(ssaoCrease) + " darker than open floor " +
      std::to_string(ssaoOpen));
  ren->SetSSAORadius(1e-6);
  win->Render();
  const double tiny = RootMeanSquareError(Grab(win), none);
  Check(tiny <= 0.5 && RootMeanSquareError(ssao, none) > 1.0,
    "its radius is SSAORadius: 1e-6 occludes nothing (RMSE " + std::to_string(tiny) + " from no occlusion)");
  ren->UseSSAOOff();
  NoVTKOutput("AmbientOcclusion");
  ren->SetPass(nullptr);
}

/// The traversal step cap: tiny caps miss, a cap above what any ray needs
/// changes nothing.
void TestTraversalSteps()
{
  auto win = MakeWindow(160, 160);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(96);
  sphere->SetPhiResolution(96);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(HasDefine(pass, "VTKRT_MAXIMUM_TRAVERSAL_STEPS 0"),
    "unlimited: no step counter compiled");
  auto full = Grab(win);
  const long fullCount = CountForegroundPixels(full, ren->GetBackground());
  pass->SetMaximumTraversalSteps(4);
  win->Render();
  auto capped = Grab(win);
  const long cappedCount = CountForegroundPixels(capped, ren->GetBackground());
  Check(cappedCount < fullCount / 2, "cap 4: visible misses (" + std::to_string(cappedCount) +
      " of " + std::to_string(fullCount) + " pixels hit)");
  pass->SetMaximumTraversalSteps(1000000);
  win->Render();
  auto generous = Grab(win);
  const long same = CountDifferingPixels(generous, full, 0);
  Check(same == 0, "a cap no ray reaches matches unlimited (" + std::to_string(same) + " differ)");
  pass->SetMaximumTraversalSteps(-5);
  Check(pass->GetMaximumTraversalSteps() == 0, "negative caps clamp to 0 (unlimited)");
  NoVTKOutput("TraversalSteps");
  ren->SetPass(nullptr);
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Sampling", TestSampling },
    { "Shadows", TestShadows },
    { "AmbientOcclusion", TestAmbientOcclusion },
    { "TraversalSteps", TestTraversalSteps },
  };
  return RunCase(argc, argv, cases);
}
