// Tests of vtkEGLHeadlessRenderWindow. One executable, one CTest entry per
// case: TestEGLHeadlessRenderWindow <Case>.
#include "vtkrtCheck.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkrtImageRegression.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

namespace
{
using vtkrtTest::Failures;
vtkrtTestOutputWindow* Output = nullptr;

using vtkrtTest::Check;

// A scene with a flat-coloured (ambient only) cube or sphere and a fixed camera.
struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkActor> Actor;

  Scene(bool sphere, std::array<double, 3> color, std::array<double, 3> background)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    if (sphere)
    {
      vtkNew<vtkSphereSource> source;
      source->SetRadius(0.6);
      source->SetThetaResolution(96);
      source->SetPhiResolution(96);
      mapper->SetInputConnection(source->GetOutputPort());
    }
    else
    {
      vtkNew<vtkCubeSource> source; // unit cube at the origin
      mapper->SetInputConnection(source->GetOutputPort());
    }
    this->Actor->SetMapper(mapper);
    this->Actor->GetProperty()->SetColor(color.data());
    this->Actor->GetProperty()->SetAmbient(1.0);
    this->Actor->GetProperty()->SetDiffuse(0.0);
    this->Actor->GetProperty()->SetSpecular(0.0);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetBackground(background.data());
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0, 0, 4);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(30);
    camera->SetClippingRange(1, 10);
  }
};

vtkSmartPointer<vtkEGLHeadlessRenderWindow> MakeWindow(int w, int h)
{
  auto window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  window->SetSize(w, h);
  window->SetMultiSamples(0);
  return window;
}

// Display position (pixels, origin bottom left) and depth in [0,1] of a world
// point, from the camera's composite projection (independent of VTK's
// coordinate helpers).
std::array<double, 3> Project(vtkRenderer* renderer, const double world[3])
{
  int* size = renderer->GetRenderWindow()->GetSize();
  const double aspect = static_cast<double>(size[0]) / size[1];
  vtkMatrix4x4* m =
    renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  const double in[4] = { world[0], world[1], world[2], 1.0 };
  double clip[4];
  m->MultiplyPoint(in, clip);
  return { (0.5 * clip[0] / clip[3] + 0.5) * size[0], (0.5 * clip[1] / clip[3] + 0.5) * size[1],
    0.5 * clip[2] / clip[3] + 0.5 };
}

// RGB pixels, bottom row first.
struct Pixels
{
  int W = 0, H = 0;
  vtkNew<vtkUnsignedCharArray> Data;
  const unsigned char* At(int x, int y) const { return this->Data->GetPointer(3 * (y * W + x)); }
};

void Read(vtkRenderWindow* window, Pixels& px)
{
  px.W = window->GetSize()[0];
  px.H = window->GetSize()[1];
  window->GetPixelData(0, 0, px.W - 1, px.H - 1, 1, px.Data.Get());
}

bool Near(const unsigned char* p, std::array<double, 3> c, int tol = 2)
{
  for (int i = 0; i < 3; ++i)
  {
    if (std::abs(static_cast<int>(p[i]) - static_cast<int>(std::lround(255 * c[i]))) > tol)
    {
      return false;
    }
  }
  return true;
}

// The unit cube seen face-on covers the projection of its front face: pixels
// 2 px inside must be the cube's colour, pixels 2 px outside the background.
void CheckCubeFootprint(vtkRenderer* renderer, const Pixels& px, std::array<double, 3> color,
  std::array<double, 3> background, const std::string& label)
{
  const double lo[3] = { -0.5, -0.5, 0.5 }, hi[3] = { 0.5, 0.5, 0.5 };
  const auto a = Project(renderer, lo);
  const auto b = Project(renderer, hi);
  int inside = 0, insideOk = 0, outside = 0, outsideOk = 0;
  for (int y = 0; y < px.H; ++y)
  {
    for (int x = 0; x < px.W; ++x)
    {
      const double cx = x + 0.5, cy = y + 0.5;
      const bool in = cx > a[0] + 2 && cx < b[0] - 2 && cy > a[1] + 2 && cy < b[1] - 2;
      const bool out = cx < a[0] - 2 || cx > b[0] + 2 || cy < a[1] - 2 || cy > b[1] + 2;
      if (in)
      {
        ++inside;
        insideOk += Near(px.At(x, y), color);
      }
      else if (out)
      {
        ++outside;
        outsideOk += Near(px.At(x, y), background);
      }
    }
  }
  std::ostringstream os;
  os << label << ": cube pixels " << insideOk << "/" << inside << ", background pixels "
     << outsideOk << "/" << outside;
  Check(inside > 100 && outside > 100 && insideOk == inside && outsideOk == outside, os.str());
}

bool NoVTKOutput(const std::string& label)
{
  const bool clean = Output->GetNumberOfErrors() == 0 && Output->GetNumberOfWarnings() == 0;
  Check(clean, label + ": no VTK error or warning");
  return clean;
}

//------------------------------------------------------------------------------
// Geometry and background where the projection says, depth readback equal to
// the projected depth (cube face, sphere surface), 1 on the background.
void TestPixelsAndDepth()
{
  const std::array<double, 3> red{ 1, 0, 0 }, bg{ 0.1, 0.2, 0.3 };
  auto window = MakeWindow(240, 180);
  Scene cube(false, red, bg);
  window->AddRenderer(cube.Renderer);
  window->Render();
  Check(window->IsContextReady(), "context ready after first Render");
  Check(window->GetGLRenderer()[0] != '\0', std::string("GL renderer: ") + window->GetGLRenderer());

  Pixels px;
  Read(window, px);
  Check(px.Data->GetNumberOfValues() == 240 * 180 * 3, "GetPixelData size");
  CheckCubeFootprint(cube.Renderer, px, red, bg, "cube");

  // Depth: the front face is perpendicular to the view direction, so its
  // depth is one value: the projection of its centre.
  vtkNew<vtkFloatArray> z;
  Check(window->GetZbufferData(0, 0, 239, 179, z.Get()) == VTK_OK, "GetZbufferData succeeds");
  const double centre[3] = { 0, 0, 0.5 };
  const double expected = Project(cube.Renderer, centre)[2];
  double maxFaceErr = 0;
  int face = 0, background = 0, backgroundOk = 0;
  for (int y = 0; y < 180; ++y)
  {
    for (int x = 0; x < 240; ++x)
    {
      const float d = z->GetValue(y * 240 + x);
      if (Near(px.At(x, y), red, 0))
      {
        ++face;
        maxFaceErr = std::max(maxFaceErr, std::abs(d - expected));
      }
      else if (Near(px.At(x, y), bg, 1))
      {
        ++background;
        backgroundOk += (d == 1.0f);
      }
    }
  }
  std::ostringstream os;
  os << "cube depth = projected " << expected << " (max error " << maxFaceErr << " over " << face
     << " px); background depth 1 on " << backgroundOk << "/" << background;
  Check(face > 1000 && maxFaceErr < 1e-5 && background > 1000 && backgroundOk == background,
    os.str());
  Check(expected > 0 && expected < 1, "projected depth inside (0,1)");

  // A sphere: every pixel's depth, unprojected, lands on the sphere.
  Scene sphere(true, { 0, 1, 0 }, bg);
  window->RemoveRenderer(cube.Renderer);
  window->AddRenderer(sphere.Renderer);
  window->Render();
  window->GetZbufferData(0, 0, 239, 179, z.Get());
  vtkNew<vtkMatrix4x4> inverse;
  inverse->DeepCopy(
    sphere.Renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(240.0 / 180, -1, 1));
  inverse->Invert();
  double maxRadiusErr = 0;
  int hits = 0;
  for (int y = 0; y < 180; ++y)
  {
    for (int x = 0; x < 240; ++x)
    {
      const float d = z->GetValue(y * 240 + x);
      if (d >= 1.0f)
      {
        continue;
      }
      ++hits;
      const double ndc[4] = { 2 * (x + 0.5) / 240 - 1, 2 * (y + 0.5) / 180 - 1, 2.0 * d - 1, 1 };
      double w[4];
      inverse->MultiplyPoint(ndc, w);
      const double r = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) / w[3];
      maxRadiusErr = std::max(maxRadiusErr, std::abs(r - 0.6));
    }
  }
  // Expected footprint: a disc of the sphere's apparent radius.
  // (tangent of its half angle from the eye: r / sqrt(d^2 - r^2)).
  const double pixelsPerTan = 90.0 / std::tan(15.0 * M_PI / 180);
  const double rPix = pixelsPerTan * 0.6 / std::sqrt(16 - 0.36);
  const double expectedHits = M_PI * rPix * rPix;
  os.str("");
  os << "sphere depth unprojects onto the sphere (max radius error " << maxRadiusErr << ", " << hits
     << " px, expected about " << expectedHits << ")";
  Check(maxRadiusErr < 0.006 && std::abs(hits - expectedHits) < 0.01 * expectedHits, os.str());
  NoVTKOutput("pixels and depth");
}

//------------------------------------------------------------------------------
// SetSize after the first render: readbacks follow, the image is re-projected.
void TestResize()
{
  const std::array<double, 3> red{ 1, 0, 0 }, bg{ 0.1, 0.2, 0.3 };
  auto window = MakeWindow(200, 150);
  Scene cube(false, red, bg);
  window->AddRenderer(cube.Renderer);
  window->Render();
  const int sizes[3][2] = { { 320, 240 }, { 100, 80 }, { 257, 131 } };
  for (const auto& s : sizes)
  {
    window->SetSize(s[0], s[1]);
    window->Render();
    std::ostringstream label;
    label << s[0] << "x" << s[1];
    Pixels px;
    Read(window, px);
    Check(px.W == s[0] && px.H == s[1] &&
        px.Data->GetNumberOfValues() == static_cast<vtkIdType>(s[0]) * s[1] * 3,
      label.str() + ": GetPixelData size");
    CheckCubeFootprint(cube.Renderer, px, red, bg, label.str());

    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->SetInputBufferTypeToRGBA();
    grab->Update();
    int dims[3];
    grab->GetOutput()->GetDimensions(dims);
    Check(dims[0] == s[0] && dims[1] == s[1] &&
        grab->GetOutput()->GetNumberOfScalarComponents() == 4,
      label.str() + ": vtkWindowToImageFilter RGBA size");

    vtkNew<vtkUnsignedCharArray> rgba;
    window->GetRGBACharPixelData(0, 0, s[0] - 1, s[1] - 1, 1, rgba.Get(), 0);
    const unsigned char* centre = rgba->GetPointer(4 * ((s[1] / 2) * s[0] + s[0] / 2));
    Check(rgba->GetNumberOfValues() == static_cast<vtkIdType>(s[0]) * s[1] * 4 &&
        centre[0] == 255 && centre[1] == 0 && centre[2] == 0,
      label.str() + ": GetRGBACharPixelData centre is the cube's red");
  }
  NoVTKOutput("resize");
}

//------------------------------------------------------------------------------
// Two windows, two contexts, two scenes; rendering one leaves the other's
// image alone; MakeCurrent switches.
void TestTwoWindows()
{
  const std::array<double, 3> red{ 1, 0, 0 }, blue{ 0, 0, 1 }, green{ 0, 1, 0 }, black{ 0, 0, 0 };
  auto a = MakeWindow(160, 120);
  auto b = MakeWindow(200, 100);
  Scene cube(false, red, blue);
  Scene sphere(true, green, black);
  a->AddRenderer(cube.Renderer);
  b->AddRenderer(sphere.Renderer);
  a->Render();
  b->Render();
  Check(a->GetGenericContext() && b->GetGenericContext() &&
      a->GetGenericContext() != b->GetGenericContext(),
    "each window has its own EGL context");
  Check(b->IsCurrent() && !a->IsCurrent(), "the last rendered window is current");
  a->MakeCurrent();
  Check(a->IsCurrent() && !b->IsCurrent(), "MakeCurrent switches to window A");
  b->MakeCurrent();
  Check(b->IsCurrent() && !a->IsCurrent(), "MakeCurrent switches to window B");

  Pixels pa, pb;
  Read(a, pa);
  Read(b, pb);
  Check(Near(pa.At(80, 60), red) && Near(pa.At(2, 2), blue), "window A: red cube on blue");
  Check(Near(pb.At(100, 50), green) && Near(pb.At(2, 2), black), "window B: green sphere on black");
  CheckCubeFootprint(cube.Renderer, pa, red, blue, "window A");

  // Re-render A with another background; B's image must not change.
  cube.Renderer->SetBackground(1, 1, 1);
  a->Render();
  Pixels pa2, pb2;
  Read(a, pa2);
  Read(b, pb2);
  Check(Near(pa2.At(2, 2), { 1, 1, 1 }) && Near(pa2.At(80, 60), red), "window A re-rendered on white");
  Check(std::equal(pb.Data->GetPointer(0), pb.Data->GetPointer(0) + pb.Data->GetNumberOfValues(),
          pb2.Data->GetPointer(0)),
    "window B's image unchanged by rendering A");

  // Finalizing one window leaves the other usable.
  a->Finalize();
  b->Render();
  Pixels pb3;
  Read(b, pb3);
  Check(Near(pb3.At(100, 50), green), "window B renders after A is finalized");
  a->Render();
  Pixels pa3;
  Read(a, pa3);
  Check(Near(pa3.At(80, 60), red), "window A renders again after Finalize");
  NoVTKOutput("two windows");
}

//------------------------------------------------------------------------------
// vtkHardwareSelector needs the colour/depth buffer sizes that a surfaceless
// context has no default framebuffer for.
void TestSelector()
{
  auto window = MakeWindow(200, 160);
  Scene cube(false, { 1, 0, 0 }, { 0, 0, 0 });
  window->AddRenderer(cube.Renderer);
  window->Render();
  int rgba[4];
  const int colorBits = window->GetColorBufferSizes(rgba);
  Check(rgba[0] >= 8 && rgba[1] >= 8 && rgba[2] >= 8 && colorBits >= 24,
    "GetColorBufferSizes reports >= 8 bits per channel (" + std::to_string(colorBits) + ")");
  Check(window->GetDepthBufferSize() >= 16,
    "GetDepthBufferSize reports a depth buffer (" + std::to_string(window->GetDepthBufferSize()) +
      " bits)");

  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(cube.Renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(95, 75, 105, 85);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  vtkActor* picked = nullptr;
  if (selection && selection->GetNumberOfNodes() == 1)
  {
    picked = vtkActor::SafeDownCast(
      selection->GetNode(0)->GetProperties()->Get(vtkSelectionNode::PROP()));
  }
  Check(picked == cube.Actor.Get(), "vtkHardwareSelector selects the cube at the centre");
  // The front face (+z) of vtkCubeSource is cell 5.
  vtkIdType cellId = -1;
  if (picked && selection->GetNode(0)->GetSelectionList()->GetNumberOfTuples() > 0)
  {
    vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(selection->GetNode(0)->GetSelectionList());
    cellId = ids ? ids->GetValue(0) : -1;
  }
  Check(cellId == 5, "selected cell is the cube's front face (" + std::to_string(cellId) + ")");
  NoVTKOutput("selector");
}

//------------------------------------------------------------------------------
// A lit scene against its checked-in baseline (through the shared harness).
void TestBaseline()
{
  auto window = MakeWindow(200, 150);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetCenter(-0.5, 0, 0);
  sphereSource->SetRadius(0.5);
  sphereSource->SetThetaResolution(48);
  sphereSource->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphereSource->GetOutputPort());
  vtkNew<vtkActor> sphere;
  sphere->SetMapper(sphereMapper);
  sphere->GetProperty()->SetColor(0.9, 0.4, 0.1);
  sphere->GetProperty()->SetSpecular(0.4);
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetCenter(0.6, 0, 0);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cubeSource->GetOutputPort());
  vtkNew<vtkActor> cube;
  cube->SetMapper(cubeMapper);
  cube->GetProperty()->SetColor(0.2, 0.5, 0.9);
  cube->RotateX(30);
  cube->RotateY(40);
  renderer->AddActor(sphere);
  renderer->AddActor(cube);
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->GetActiveCamera()->SetPosition(0, 1, 5);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  window->AddRenderer(renderer);
  window->Render();
  Check(vtkrtCompareWithBaseline(window, "window_LitScene") == 1, "lit scene matches its baseline");
  NoVTKOutput("baseline");
}

//------------------------------------------------------------------------------
// VTK's default MultiSamples (8; llvmpipe clamps to 4): the multisampled
// framebuffer is resolved for colour and depth readback.
void TestMultiSamples()
{
  const std::array<double, 3> red{ 1, 0, 0 }, bg{ 0.1, 0.2, 0.3 };
  auto window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  window->SetSize(160, 120);
  Scene cube(false, red, bg);
  window->AddRenderer(cube.Renderer);
  window->Render();
  Pixels px;
  Read(window, px);
  CheckCubeFootprint(cube.Renderer, px, red, bg, "MultiSamples " + std::to_string(window->GetMultiSamples()));
  vtkNew<vtkFloatArray> z;
  Check(window->GetZbufferData(0, 0, 159, 119, z.Get()) == VTK_OK, "GetZbufferData succeeds");
  const double centre[3] = { 0, 0, 0.5 };
  const double expected = Project(cube.Renderer, centre)[2];
  const float atCentre = z->GetValue(60 * 160 + 80);
  const float atCorner = z->GetValue(0);
  Check(std::abs(atCentre - expected) < 1e-5 && atCorner == 1.0f,
    "depth at the centre " + std::to_string(atCentre) + " (expected " + std::to_string(expected) +
      "), at the corner " + std::to_string(atCorner));
  NoVTKOutput("multisamples");
}

//------------------------------------------------------------------------------
// Two actors of one cube in one place: raster draws them at equal depths,
// and VTK's GL_LEQUAL depth test (VTK's X11 windows) shows the one drawn
// last; a context left at GL_LESS shows the first.
void TestCoincidentDrawnLast()
{
  const std::array<double, 3> red{ 1, 0, 0 }, bg{ 0.1, 0.2, 0.3 };
  std::array<double, 3> blue{ 0, 0, 1 };
  auto window = MakeWindow(160, 120);
  Scene first(false, red, bg);
  vtkNew<vtkActor> second;
  second->SetMapper(first.Actor->GetMapper());
  second->GetProperty()->DeepCopy(first.Actor->GetProperty());
  second->GetProperty()->SetColor(blue.data());
  first.Renderer->AddActor(second);
  window->AddRenderer(first.Renderer);
  for (int frame = 0; frame < 2; ++frame)
  {
    window->Render();
    Pixels px;
    Read(window, px);
    CheckCubeFootprint(first.Renderer, px, blue, bg, "frame " + std::to_string(frame) + ": the actor drawn last");
  }
  NoVTKOutput("coincident actors");
}

//------------------------------------------------------------------------------
// Teardown in every order: window before renderer, renderer before window,
// never-rendered windows, Finalize then delete, a new window after the last
// one (and its EGL display) went away.
void TestTeardown()
{
  const std::array<double, 3> red{ 1, 0, 0 }, bg{ 0, 0, 0 };
  for (int round = 0; round < 2; ++round)
  {
    {
      Scene cube(false, red, bg); // outlives the window
      auto window = MakeWindow(64, 48);
      window->AddRenderer(cube.Renderer);
      window->Render();
      window = nullptr;
      // The renderer, now without a window, can join a new one.
      auto second = MakeWindow(64, 48);
      second->AddRenderer(cube.Renderer);
      second->Render();
      Pixels px;
      Read(second, px);
      Check(Near(px.At(32, 24), red), "round " + std::to_string(round) +
          ": a renderer moves to a new window after the first is deleted");
    }
    {
      auto window = MakeWindow(64, 48);
      Scene cube(false, red, bg); // destroyed before the window
      window->AddRenderer(cube.Renderer);
      window->Render();
      window->Finalize();
      window->Finalize(); // twice is harmless
    }
    {
      auto never = MakeWindow(32, 32); // never rendered
      auto finalizedOnly = MakeWindow(32, 32);
      finalizedOnly->Finalize();
      auto empty = MakeWindow(32, 32); // no renderer at all
      empty->Render();
      Check(empty->IsContextReady(), "a window without renderers renders");
    }
    {
      // Reading before the first Render: a warning, VTK_ERROR, no crash.
      auto early = MakeWindow(16, 16);
      vtkNew<vtkUnsignedCharArray> rgb;
      vtkNew<vtkFloatArray> z;
      Output->SetEcho(false);
      const int a = early->GetPixelData(0, 0, 15, 15, 1, rgb.Get(), 0);
      const int b = early->GetZbufferData(0, 0, 15, 15, z.Get());
      Output->SetEcho(true);
      Check(a == VTK_ERROR && b == VTK_ERROR && Output->GetNumberOfWarnings() == 2 &&
          Output->GetNumberOfErrors() == 0,
        "readbacks before the first Render warn and return VTK_ERROR");
      Output->Clear();
    }
  }
  NoVTKOutput("teardown");
}

//------------------------------------------------------------------------------
// Description strings, PrintSelf, GL version.
void TestDescription()
{
  auto window = MakeWindow(64, 64);
  window->Initialize();
  Check(window->IsContextReady() && window->SupportsOpenGL() == 1, "Initialize makes a context");
  std::ostringstream os;
  window->Print(os);
  const std::string text = os.str();
  std::cout << "  EGL " << window->GetEGLVersion() << " (" << window->GetEGLVendor() << "), "
            << window->GetDeviceDescription() << ", " << window->GetGLRenderer() << ", GL "
            << window->GetGLVersion() << "\n";
  Check(text.find("EGL vendor: ") != std::string::npos && window->GetEGLVendor()[0] != '\0',
    "PrintSelf reports the EGL vendor");
  Check(text.find("GL renderer: ") != std::string::npos && window->GetGLRenderer()[0] != '\0',
    "PrintSelf reports the GL renderer");
  Check(text.find("Device: ") != std::string::npos && window->GetDeviceDescription()[0] != '\0',
    "PrintSelf reports the device");
  int major = 0, minor = 0;
  std::sscanf(window->GetGLVersion(), "%d.%d", &major, &minor);
  Check(major > 3 || (major == 3 && minor >= 2), "OpenGL 3.2 or later");
  Check(vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers(), "TuneMallocForLargeBuffers");
  NoVTKOutput("description");
}

//------------------------------------------------------------------------------
// An EGL device chosen by index (EGL_EXT_platform_device; Mesa lists its
// software device, a GPU driver its GPUs): the same pixel and depth checks.
// Returns false when EGL lists no device (the test is then skipped).
bool TestDeviceIndex()
{
  auto probe = MakeWindow(8, 8);
  if (probe->GetNumberOfDevices() == 0)
  {
    std::cout << "EGL lists no device: skipped\n";
    return false;
  }
  auto window = MakeWindow(8, 8);
  window->SetDeviceIndex(0);
  window->Initialize();
  Check(window->IsContextReady() &&
      std::string(window->GetDeviceDescription()).rfind("EGL device 0", 0) == 0,
    std::string("SetDeviceIndex(0) uses EGL device 0: ") + window->GetDeviceDescription());
  // The environment variable: the rest of the checks run on the device it names.
  setenv("VTKRT_EGL_DEVICE", "0", 1);
  TestPixelsAndDepth();
  auto fromEnv = MakeWindow(8, 8);
  fromEnv->Initialize();
  Check(std::string(fromEnv->GetDeviceDescription()).rfind("EGL device 0", 0) == 0,
    std::string("VTKRT_EGL_DEVICE=0 uses EGL device 0: ") + fromEnv->GetDeviceDescription());
  unsetenv("VTKRT_EGL_DEVICE");
  NoVTKOutput("device index");
  return true;
}

//------------------------------------------------------------------------------
// A device that does not exist: one clear error, no crash, Render a no-op;
// Finalize and a valid choice recover. `viaSetter` false: the environment
// (VTKRT_EGL_DEVICE, set by CTest) chose the device.
void TestFailure(bool viaSetter, const std::string& expectedFragment)
{
  auto window = MakeWindow(64, 64);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> actor;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkSphereSource> source;
  mapper->SetInputConnection(source->GetOutputPort());
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  if (viaSetter)
  {
    window->SetDeviceIndex(999);
  }
  Output->SetEcho(false);
  window->Render();
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  // Filled beforehand, so that what a readback leaves in them shows.
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(64 * 64);
  rgb->Fill(7);
  const int readRgb = window->GetPixelData(0, 0, 63, 63, 1, rgb.Get(), 0);
  vtkNew<vtkFloatArray> z;
  z->SetNumberOfTuples(64 * 64);
  z->Fill(0.5);
  const int readZ = window->GetZbufferData(0, 0, 63, 63, z.Get());
  Output->SetEcho(true);
  for (const auto& e : Output->GetErrors())
  {
    // The message only: VTK's "ERROR: In file, line" header stays out of a
    // passing test's output.
    const size_t at = e.find("): ");
    std::cout << "  expected message: " << (at == std::string::npos ? e : e.substr(at + 3));
  }
  Check(window->HasFailed() && !window->IsContextReady(), "window reports failure");
  Check(Output->GetNumberOfErrors() == 1, "exactly one VTK error (" +
      std::to_string(Output->GetNumberOfErrors()) + ")");
  Check(Output->GetNumberOfWarnings() == 0, "no VTK warning");
  Check(Output->HasErrorContaining("No usable EGL display") &&
      Output->HasErrorContaining(expectedFragment),
    "the error says why (mentions '" + expectedFragment + "')");
  Check(readRgb == VTK_ERROR && readZ == VTK_ERROR, "readbacks on a failed window return VTK_ERROR");
  // Callers that do not check (vtkWindowToImageFilter) get defined values:
  // black pixels, far depths.
  vtkImageData* grabbed = grab->GetOutput();
  const auto* grabbedPixels = static_cast<const unsigned char*>(grabbed->GetScalarPointer());
  const std::size_t grabbedBytes =
    static_cast<std::size_t>(grabbed->GetNumberOfPoints()) * grabbed->GetNumberOfScalarComponents();
  const bool black = grabbedPixels && grabbedBytes == 64 * 64 * 3 &&
    std::all_of(grabbedPixels, grabbedPixels + grabbedBytes, [](unsigned char c) { return c == 0; }) &&
    rgb->GetNumberOfValues() == 64 * 64 * 3 && rgb->GetValueRange()[1] == 0;
  const bool far = z->GetNumberOfValues() == 64 * 64 && z->GetValueRange()[0] == 1.0f &&
    z->GetValueRange()[1] == 1.0f;
  Check(black && far, "readbacks on a failed window: black pixels and far depths");
  Output->Clear();

  if (viaSetter)
  {
    window->SetDeviceIndex(-1);
    window->Finalize();
    window->Render();
    Check(window->IsContextReady(), "after Finalize, an automatic device choice renders");
    NoVTKOutput("recovery");
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "PixelsAndDepth", TestPixelsAndDepth },
    { "Resize", TestResize },
    { "TwoWindows", TestTwoWindows },
    { "Selector", TestSelector },
    { "Baseline", TestBaseline },
    { "Description", TestDescription },
    { "MultiSamples", TestMultiSamples },
    { "Teardown", TestTeardown },
    { "CoincidentDrawnLast", TestCoincidentDrawnLast },
    { "DeviceIndex", [] {} }, // run by main: may skip
    { "BadDeviceIndex", [] { TestFailure(true, "999"); } },
    { "BadDeviceFromEnv", [] { TestFailure(false, "VTKRT_EGL_DEVICE"); } },
    { "BadPlatformFromEnv", [] { TestFailure(false, "EGL_PLATFORM=x11"); } },
  };
  const std::string which = argc > 1 ? argv[1] : "";
  auto it = cases.find(which);
  if (it == cases.end())
  {
    std::cerr << "usage: " << argv[0] << " <case>; cases:";
    for (const auto& c : cases)
    {
      std::cerr << " " << c.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }
  if (which == "DeviceIndex")
  {
    if (!TestDeviceIndex())
    {
      return 77; // CTest SKIP_RETURN_CODE
    }
  }
  else
  {
    it->second();
  }
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
