// End-to-end tests of vtkrt-render's viewer options (issue 23): scalars and
// colormaps, the up axis and explicit camera, input and output formats,
// several files and picks, the ray tracer's knobs, progress, bad input, and
// the interactive window (under xvfb, with a played event log).
//   TestVtkrtRenderViewer <path to vtkrt-render> <case>
#include "vtkrtRenderAppTest.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkAppendFilter.h"
#include "vtkBYUWriter.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkElevationFilter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSTLWriter.h"
#include "vtkSphereSource.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <vector>

namespace
{
const std::string Data = VTKRT_DATA_DIR;
const int Background[3] = { 82, 87, 110 }; // 255 * (0.32, 0.34, 0.43)

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream f(path, std::ios::binary);
  f << text;
}

std::string ReadBytes(const std::string& path, size_t n)
{
  std::ifstream f(path, std::ios::binary);
  std::string bytes(n, '\0');
  f.read(&bytes[0], static_cast<std::streamsize>(n));
  bytes.resize(static_cast<size_t>(f.gcount()));
  return bytes;
}

vtkSmartPointer<vtkPolyData> Sphere(double radius, const double centre[3], int resolution)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetCenter(centre[0], centre[1], centre[2]);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  sphere->Update();
  return sphere->GetOutput();
}

std::string WriteSTL(const std::string& name, vtkPolyData* mesh)
{
  const std::string path = Tmp + "/" + name;
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileTypeToBinary();
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}

// A unit sphere as an unstructured grid with a point array "Elevation" (0
// at the bottom, 1 at the top), a 3-component point array "Vec" and a cell
// array "Band" (the cell id modulo 7).
std::string WriteScalarSphere(vtkIdType& triangles)
{
  const double origin[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> sphere = Sphere(1.0, origin, 32);
  triangles = sphere->GetNumberOfPolys();
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputData(sphere);
  elevation->SetLowPoint(0, -1, 0);
  elevation->SetHighPoint(0, 1, 0);
  elevation->Update();
  auto* withElevation = vtkPolyData::SafeDownCast(elevation->GetOutput());
  vtkNew<vtkDoubleArray> vec;
  vec->SetName("Vec");
  vec->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < withElevation->GetNumberOfPoints(); ++i)
  {
    double p[3];
    withElevation->GetPoint(i, p);
    vec->InsertNextTuple3(p[0], p[1], p[2]);
  }
  withElevation->GetPointData()->AddArray(vec);
  vtkNew<vtkDoubleArray> band;
  band->SetName("Band");
  for (vtkIdType i = 0; i < withElevation->GetNumberOfCells(); ++i)
  {
    band->InsertNextValue(static_cast<double>(i % 7));
  }
  withElevation->GetCellData()->AddArray(band);
  vtkNew<vtkAppendFilter> grid;
  grid->SetInputData(withElevation);
  const std::string path = Tmp + "/scalars.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputConnection(grid->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}

const unsigned char* Pixel(vtkImageData* image, int x, int y)
{
  // Rows of the file run bottom up in vtkImageData; x, y here are image
  // coordinates with the origin at the bottom left.
  return static_cast<const unsigned char*>(image->GetScalarPointer(x, y, 0));
}

bool IsBackground(const unsigned char* c)
{
  return std::abs(c[0] - Background[0]) + std::abs(c[1] - Background[1]) +
    std::abs(c[2] - Background[2]) <=
    12;
}

// Pixels in columns [x0, x1) that are not background, and those of them
// that are strongly coloured (channel spread above 60).
void CountPixels(vtkImageData* image, int x0, int x1, long& covered, long& colourful)
{
  covered = colourful = 0;
  if (!image)
  {
    return;
  }
  int dims[3];
  image->GetDimensions(dims);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = std::max(0, x0); x < std::min(dims[0], x1); ++x)
    {
      const unsigned char* c = Pixel(image, x, y);
      covered += !IsBackground(c);
      colourful += std::max({ c[0], c[1], c[2] }) - std::min({ c[0], c[1], c[2] }) > 60;
    }
  }
}

// Root mean square difference of two same-size RGB images, the second read
// through `map` (image coordinates of the first to those of the second).
double Rms(vtkImageData* a, vtkImageData* b, const std::function<void(int&, int&)>& map)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] * da[1] != db[0] * db[1])
  {
    return 1e9;
  }
  double sum = 0.0;
  for (int y = 0; y < da[1]; ++y)
  {
    for (int x = 0; x < da[0]; ++x)
    {
      int u = x, v = y;
      map(u, v);
      const unsigned char* p = Pixel(a, x, y);
      const unsigned char* q = Pixel(b, u, v);
      for (int k = 0; k < 3; ++k)
      {
        sum += (p[k] - q[k]) * (p[k] - q[k]);
      }
    }
  }
  return std::sqrt(sum / (3.0 * da[0] * da[1]));
}

double Rms(vtkImageData* a, vtkImageData* b)
{
  return Rms(a, b, [](int&, int&) {});
}

double MeanBrightness(vtkImageData* image)
{
  int d[3];
  image->GetDimensions(d);
  double sum = 0.0;
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      const unsigned char* c = Pixel(image, x, y);
      sum += c[0] + c[1] + c[2];
    }
  }
  return sum / (3.0 * d[0] * d[1]);
}

// Renders `args` into Tmp/`name` and returns the image (null on failure).
vtkSmartPointer<vtkImageData> Render(
  const std::string& args, const std::string& name, Result* result = nullptr)
{
  const std::string out = Tmp + "/" + name;
  vtksys::SystemTools::RemoveFile(out);
  const Result r = RunApp(args + " --frames 0 --output '" + out + "'");
  if (result)
  {
    *result = r;
  }
  Check(r.Code == 0, name + ": exit status 0");
  return r.Code == 0 ? ReadPNG(out) : nullptr;
}

//------------------------------------------------------------------------------
void TestScalars()
{
  vtkIdType triangles = 0;
  const std::string vtu = "'" + WriteScalarSphere(triangles) + "'";
  long covered = 0, colourful = 0;
  Result r;
  for (const std::string mode : { "raytrace", "raster" })
  {
    const std::string base = vtu + " --mode " + mode + " --resolution 400,300";
    CountPixels(Render(base, "grey-" + mode + ".png", &r), 0, 400, covered, colourful);
    Check(ReportNumber(r.Output, "triangles") == triangles, mode + ": .vtu triangles reported");
    Check(covered > 20000 && colourful < covered / 100,
      mode + ": without --scalars the sphere is grey (" + std::to_string(colourful) + " of " +
        std::to_string(covered) + " pixels coloured)");
    CountPixels(
      Render(base + " --scalars", "elevation-" + mode + ".png", &r), 0, 400, covered, colourful);
    Check(colourful > covered / 2,
      mode + ": --scalars colours the sphere (" + std::to_string(colourful) + " of " +
        std::to_string(covered) + " pixels)");
    Check(Contains(r.Output, "coloured by: +point array 'Elevation' \\(magnitude\\), range \\[0"),
      mode + ": the report names the active array");
  }
  CountPixels(Render(vtu + " --scalars=Band --cells --colormap coolwarm --resolution 400,300",
                "band.png", &r),
    0, 400, covered, colourful);
  Check(colourful > covered / 4 && Contains(r.Output, "cell array 'Band'.*coolwarm"),
    "--scalars=Band --cells: coloured by the cell array through coolwarm");
  Render(vtu + " --scalars=Vec --comp 2 --range -0.5,0.5 --resolution 400,300", "vec.png", &r);
  Check(Contains(r.Output, "point array 'Vec' \\(component 2\\), range \\[-0.5, 0.5\\]"),
    "--comp 2 --range -0.5,0.5: reported as asked");

  // The scalar bar sits right of the framed sphere (which spans x 65..335).
  long barCovered = 0, barColourful = 0;
  CountPixels(Render(vtu + " --scalars --resolution 400,300", "nobar.png"), 345, 400, barCovered,
    barColourful);
  Check(barColourful == 0, "no --bar: nothing coloured right of the sphere");
  CountPixels(Render(vtu + " --scalars --bar --resolution 400,300", "bar.png"), 345, 400,
    barCovered, barColourful);
  Check(barColourful > 500,
    "--bar: a coloured bar right of the sphere (" + std::to_string(barColourful) + " pixels)");

  // Normals are the bunny's only array: coloured by them, a constant
  // magnitude gets one colour, the colormap's middle, not rounding noise.
  Render("'" + Data + "/bunny.vtp' --scalars --resolution 200,160", "normals.png", &r);
  Check(Contains(r.Output, "point array 'Normals' \\(magnitude\\), range \\[0.5, 1.5\\]"),
    "--scalars on unit normals alone: the constant magnitude's range is widened");
}

void TestUpAxis()
{
  // Azimuth and elevation 0: -Y up is +Y up turned half a turn (the view
  // from +Z with both axes flipped), +Z up looks from -Y.
  const std::string base =
    "'" + Data + "/teapot.obj' --azimuth 0 --elevation 0 --resolution 240,180";
  vtkSmartPointer<vtkImageData> byDefault = Render(base, "default.png");
  vtkSmartPointer<vtkImageData> plusY = Render(base + " --up +Y", "plus-y.png");
  vtkSmartPointer<vtkImageData> minusY = Render(base + " --up -Y", "minus-y.png");
  vtkSmartPointer<vtkImageData> plusZ = Render(base + " --up +Z", "plus-z.png");
  if (!byDefault || !plusY || !minusY || !plusZ)
  {
    Check(false, "up axis images rendered");
    return;
  }
  Check(Rms(byDefault, plusY) == 0.0, "the default up is +Y");
  const double turned = Rms(plusY, minusY,
    [](int& x, int& y)
    {
      x = 239 - x;
      y = 179 - y;
    });
  Check(turned < 3.0, "--up -Y is --up +Y turned half a turn (RMS " + std::to_string(turned) + ")");
  const double plain = Rms(plusY, minusY);
  const double side = Rms(plusY, plusZ);
  Check(plain > 15.0 && side > 15.0,
    "--up -Y and --up +Z change the image (RMS " + std::to_string(plain) + ", " +
      std::to_string(side) + ")");
}

// The share of a W x W image a unit sphere covers seen from distance `d`
// with vertical view angle `angle` (degrees).
double SphereShare(double d, double angle)
{
  const double pi = std::acos(-1.0);
  const double r = std::tan(std::asin(1.0 / d)) / std::tan(angle * pi / 360.0); // in half-heights
  return pi * r * r / 4.0;
}

void TestCamera()
{
  const double origin[3] = { 0, 0, 0 };
  const std::string stl = "'" + WriteSTL("sphere.stl", Sphere(1.0, origin, 96)) + "'";
  const std::string place = stl +
    " --resolution 300,300 --camera-position 0,0,5 "
    "--camera-focal-point 0,0,0 --camera-view-up 0,1,0";
  struct Case
  {
    std::string Args;
    double Share;
  };
  const Case cases[] = { { "", SphereShare(5, 30) },
    { " --camera-view-angle 60", SphereShare(5, 60) },
    { " --camera-zoom-factor 0.5", SphereShare(5, 60) } };
  int i = 0;
  for (const Case& c : cases)
  {
    long covered = 0, colourful = 0;
    CountPixels(
      Render(place + c.Args, "camera-" + std::to_string(i++) + ".png"), 0, 300, covered, colourful);
    const double share = covered / (300.0 * 300.0);
    Check(std::abs(share - c.Share) < 0.02 * c.Share + 0.002,
      "camera" + c.Args + ": the sphere covers " + std::to_string(share) + " of the image (" +
        std::to_string(c.Share) + " expected)");
  }
  // A view up of +X turns the image a quarter turn.
  const std::string teapot = "'" + Data +
    "/teapot.obj' --resolution 200,200 "
    "--camera-position 0,1,12 --camera-focal-point 0,1,0";
  vtkSmartPointer<vtkImageData> upY = Render(teapot + " --camera-view-up 0,1,0", "view-up-y.png");
  vtkSmartPointer<vtkImageData> upX = Render(teapot + " --camera-view-up 1,0,0", "view-up-x.png");
  if (upY && upX)
  {
    const double quarter = std::min(Rms(upX, upY,
                                      [](int& x, int& y)
                                      {
                                        const int t = x;
                                        x = y;
                                        y = 199 - t;
                                      }),
      Rms(upX, upY,
        [](int& x, int& y)
        {
          const int t = x;
          x = 199 - y;
          y = t;
        }));
    Check(quarter < 3.0 && Rms(upX, upY) > 10.0,
      "--camera-view-up 1,0,0 turns the image a quarter turn (RMS " + std::to_string(quarter) +
        ")");
  }
}

void TestFormats()
{
  const std::string bunny = "'" + Data + "/bunny.vtp' --resolution 120,90 --frames 0";
  const std::pair<std::string, std::string> outputs[] = { { "png", std::string("\x89PNG", 4) },
    { "jpg", std::string("\xFF\xD8\xFF", 3) }, { "jpeg", std::string("\xFF\xD8\xFF", 3) },
    { "tif", std::string("II*\0", 4) }, { "bmp", "BM" } };
  for (const auto& o : outputs)
  {
    const std::string out = Tmp + "/bunny." + o.first;
    vtksys::SystemTools::RemoveFile(out);
    const Result r = RunApp(bunny + " --output '" + out + "'");
    const std::string magic = ReadBytes(out, o.second.size());
    Check(r.Code == 0 && magic == o.second,
      "--output ." + o.first + " writes a ." + o.first + " file (its magic bytes)");
  }
  // Inputs: an image's surface, a glTF quad, a BYU sphere.
  vtkNew<vtkRTAnalyticSource> wave;
  wave->SetWholeExtent(0, 4, 0, 4, 0, 4);
  vtkNew<vtkXMLImageDataWriter> vti;
  vti->SetInputConnection(wave->GetOutputPort());
  vti->SetFileName((Tmp + "/wave.vti").c_str());
  vti->Write();
  WriteText(Tmp + "/quad.gltf",
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
    R"("buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAgD8AAAAAAAABAAIAAQADAAIA"}],)"
    R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},)"
    R"({"buffer":0,"byteOffset":48,"byteLength":12}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
    R"("min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":6,)"
    R"("type":"SCALAR"}]})");
  const double origin[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> sphere = Sphere(1.0, origin, 16);
  vtkNew<vtkBYUWriter> byu;
  byu->SetInputData(sphere);
  byu->SetGeometryFileName((Tmp + "/sphere.g").c_str());
  byu->Write();
  const std::pair<std::string, long long> inputs[] = { { "wave.vti", 6 * 16 * 2 },
    { "quad.gltf", 2 }, { "sphere.g", sphere->GetNumberOfPolys() } };
  for (const auto& input : inputs)
  {
    Result r;
    long covered = 0, colourful = 0;
    CountPixels(
      Render("'" + Tmp + "/" + input.first + "' --resolution 120,90", input.first + ".png", &r), 0,
      120, covered, colourful);
    Check(ReportNumber(r.Output, "triangles") == input.second && covered > 120 * 90 / 10,
      input.first + ": " + std::to_string(input.second) + " triangles reported, drawn");
  }
}

void TestPicksAndFiles()
{
  const double left[3] = { -3, 0, 0 }, right[3] = { 3, 0, 0 };
  vtkSmartPointer<vtkPolyData> a = Sphere(1.0, left, 24), b = Sphere(1.0, right, 24);
  const std::string fa = WriteSTL("left.stl", a), fb = WriteSTL("right.stl", b);
  Result r;
  vtkSmartPointer<vtkImageData> image = Render("'" + fa + "' '" + fb +
      "' --azimuth 0 --elevation 0 --resolution 400,200 --pick 65 100 --pick 335 100 --pick 200 5",
    "two-files.png", &r);
  Check(ReportNumber(r.Output, "triangles") == a->GetNumberOfPolys() + b->GetNumberOfPolys(),
    "two files: the triangles of both");
  long coveredLeft = 0, coveredRight = 0, colourful = 0;
  CountPixels(image, 0, 200, coveredLeft, colourful);
  CountPixels(image, 200, 400, coveredRight, colourful);
  Check(coveredLeft > 3000 && coveredRight > 3000,
    "two files: both spheres drawn (" + std::to_string(coveredLeft) + ", " +
      std::to_string(coveredRight) + " pixels)");
  Check(Contains(r.Output,
          "pick \\(65, 100\\): cell [0-9]+ at world \\(-[0-9.]+, .*on the mesh '[^']*left.stl'") &&
      Contains(r.Output,
        "pick \\(335, 100\\): cell [0-9]+ at world \\([0-9.]+, .*on the mesh '[^']*right.stl'") &&
      Contains(r.Output, "pick \\(200, 5\\): nothing"),
    "three --pick: three lines, each sphere picked in its file, the gap empty");
  const size_t first = r.Output.find("pick (65, 100)"), second = r.Output.find("pick (335, 100)");
  Check(first != std::string::npos && second != std::string::npos && first < second,
    "picks reported in the order given");
}

void TestStrips()
{
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n"
                             "property float y\nproperty float z\nelement tristrips 1\n"
                             "property list int int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n";
  WriteText(Tmp + "/strip.ply", header + vertices + "9 0 1 2 3 -1 2 3 4 5\n");
  // The same as binary little endian.
  std::string binary = header;
  binary.replace(binary.find("ascii"), 5, "binary_little_endian");
  const float xyz[18] = { 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0 };
  const int ids[10] = { 9, 0, 1, 2, 3, -1, 2, 3, 4, 5 };
  binary.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
  binary.append(reinterpret_cast<const char*>(ids), sizeof(ids));
  WriteText(Tmp + "/strip-binary.ply", binary);
  for (const std::string name : { "strip.ply", "strip-binary.ply" })
  {
    Result r;
    long covered = 0, colourful = 0;
    CountPixels(Render("'" + Tmp + "/" + name +
                    "' --azimuth 0 --elevation 0 --resolution 200,100 "
                    "--pick 100 50",
                  name + ".png", &r),
      0, 200, covered, colourful);
    Check(ReportNumber(r.Output, "triangles") == 4 && covered > 200 * 100 / 2 &&
        Contains(r.Output, "pick \\(100, 50\\): cell [0-9]+ at world"),
      name + ": two strips = 4 triangles, drawn and picked");
  }
}

void TestTraceKnobs()
{
  const std::string bunny = "'" + Data + "/bunny.vtp' --resolution 200,160";
  Result r;
  vtkSmartPointer<vtkImageData> plain = Render(bunny, "plain.png", &r);
  Check(Contains(r.Output, "^vtkrt-render: raytrace 200x160") &&
      Contains(r.Output, "tracing: +1 ray\\(s\\) per pixel, shadows off, ambient occlusion 0"),
    "ray traced by default, one ray a pixel");
  vtkSmartPointer<vtkImageData> occluded =
    Render(bunny + " --ao 8 --shadows --samples 2 --progressive 3 --precision world", "ao.png", &r);
  Check(Contains(r.Output,
          "tracing: +2 ray\\(s\\) per pixel, shadows on, ambient occlusion 8 "
          "ray\\(s\\), precision World") &&
      Contains(r.Output, "accumulated: +3 frames in"),
    "--samples --shadows --ao --progressive --precision reach the pass");
  if (plain && occluded)
  {
    const double before = MeanBrightness(plain), after = MeanBrightness(occluded);
    Check(after < before - 0.5,
      "ambient occlusion darkens the bunny (mean " + std::to_string(before) + " -> " +
        std::to_string(after) + ")");
  }
  Render(bunny + " --preset exact", "exact.png", &r);
  Check(Contains(r.Output,
          "tracing: +4 ray\\(s\\) per pixel, shadows on, ambient occlusion 4 ray\\(s\\), "
          "precision CameraRelative, preset Exact"),
    "--preset exact sets the pass's EXACT knobs");
  Check(Contains(r.Output, "accumulated: +16 frames in"),
    "--preset exact writes a still image accumulated over 16 frames");
  Render(bunny + " --preset exact --samples 1", "exact1.png", &r);
  Check(Contains(r.Output, "tracing: +1 ray\\(s\\) per pixel, shadows on, .*preset Custom"),
    "a knob given beside --preset overrides it");
  Render(bunny + " --mode raster --samples 4", "msaa.png", &r);
  Check(Contains(r.Output, "raster 200x160, MultiSamples 4") && !Contains(r.Output, "tracing:"),
    "--mode raster --samples 4: MSAA, no tracing");
}

// The mean colour of the pixels of `image` that are not background.
void MeanCovered(vtkImageData* image, double mean[3], long& covered)
{
  mean[0] = mean[1] = mean[2] = 0.0;
  covered = 0;
  int d[3];
  image->GetDimensions(d);
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      const unsigned char* c = Pixel(image, x, y);
      if (!IsBackground(c))
      {
        ++covered;
        for (int k = 0; k < 3; ++k)
        {
          mean[k] += c[k];
        }
      }
    }
  }
  for (int k = 0; k < 3 && covered > 0; ++k)
  {
    mean[k] /= covered;
  }
}

void TestLook()
{
  const double origin[3] = { 0, 0, 0 };
  const std::string stl =
    "'" + WriteSTL("sphere.stl", Sphere(1.0, origin, 48)) + "' --resolution 160,120";
  double grey[3], red[3];
  long covered = 0;
  vtkSmartPointer<vtkImageData> image = Render(stl, "grey.png");
  MeanCovered(image, grey, covered);
  image = Render(stl + " --color 1,0,0", "red.png");
  MeanCovered(image, red, covered);
  Check(red[0] > 2 * red[1] + 20 && red[0] > 2 * red[2] + 20 && grey[0] < grey[2],
    "--color 1,0,0: the sphere is red");
  image = Render(stl + " --bg-color 0,0,0", "black.png");
  Check(
    image && Pixel(image, 0, 0)[0] == 0 && Pixel(image, 0, 0)[1] == 0 && Pixel(image, 0, 0)[2] == 0,
    "--bg-color 0,0,0: a black corner");
  image = Render(stl + " --opacity 0.3 --bg-color 0,0,0", "faint.png");
  vtkSmartPointer<vtkImageData> opaque = Render(stl + " --bg-color 0,0,0", "opaque.png");
  const unsigned char* middle = image ? Pixel(image, 80, 60) : nullptr;
  const unsigned char* full = opaque ? Pixel(opaque, 80, 60) : nullptr;
  Check(middle && full && middle[0] > 10 && middle[0] < 0.6 * full[0],
    "--opacity 0.3: the sphere's middle blends with the black background");
  vtkSmartPointer<vtkImageData> plainImage = Render(stl + " --mode raster", "plain.png");
  vtkSmartPointer<vtkImageData> edgedImage = Render(stl + " --mode raster --edges", "edges.png");
  Check(plainImage && edgedImage && MeanBrightness(edgedImage) < MeanBrightness(plainImage) - 2,
    "--edges: the cell edges darken the sphere");

  // A point cloud (a PLY of vertices only) is drawn as spheres of --point-size pixels.
  std::ostringstream cloud;
  cloud << "ply\nformat ascii 1.0\nelement vertex 25\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n";
  for (int i = 0; i < 25; ++i)
  {
    cloud << (i % 5) << " " << (i / 5) << " 0\n";
  }
  WriteText(Tmp + "/cloud.ply", cloud.str());
  long small = 0, large = 0, colourful = 0;
  Result r;
  CountPixels(
    Render("'" + Tmp + "/cloud.ply' --resolution 200,200 --point-size 4", "cloud-4.png", &r), 0,
    200, small, colourful);
  Check(ReportNumber(r.Output, "points") == 25, "point cloud: 25 points reported");
  CountPixels(
    Render("'" + Tmp + "/cloud.ply' --resolution 200,200 --point-size 12", "cloud-12.png"), 0, 200,
    large, colourful);
  Check(small > 25 * 4 && large > 4 * small,
    "--point-size 4 and 12: " + std::to_string(small) + " and " + std::to_string(large) +
      " pixels of points");
}

void TestProgress()
{
  const std::string args = "'" + Data +
    "/bunny.vtp' --resolution 64,48 --frames 0 --progressive 2 --output '" + Tmp + "/progress.png'";
  Result r = RunApp(args);
  Check(r.Code == 0 && !Contains(r.Output, "done in"), "no progress when stderr is no terminal");
  r = RunApp(args + " --verbose");
  Check(r.Code == 0 &&
      Contains(r.Output, "vtkrt-render: reading bunny.vtp ... done in [0-9]+ ms") &&
      Contains(
        r.Output, "first frame \\(context, BVH build, upload, shaders\\) ... done in [0-9]+ ms") &&
      Contains(r.Output, "accumulating 2 frames ... done in [0-9]+ ms"),
    "--verbose: reading, first frame and accumulation with times");
}

void TestBadInput()
{
  vtkIdType triangles = 0;
  const std::string vtu = "'" + WriteScalarSphere(triangles) + "' --output '" + Tmp + "/bad.png'";
  const std::pair<std::string, std::string> cases[] = {
    { vtu + " --scalars=Nope",
      "--scalars: '[^']*scalars.vtu' has no point array 'Nope' \\(its "
      "point arrays: .*Elevation.*\\)" },
    { vtu + " --scalars=Band", "--scalars: '[^']*' has no point array 'Band'" },
    { vtu + " --scalars=Vec --comp 3",
      "--comp 3: the point array 'Vec' of '[^']*' has 3 component" },
    { vtu + " --colormap jet",
      "--colormap: no colormap 'jet' \\(known: viridis inferno coolwarm "
      "rainbow grayscale\\)" },
    { vtu + " --camera-position 1,2",
      "--camera-position expects three numbers X,Y,Z \\(got '1,2'\\)" },
    { vtu + " --camera-view-up 0,0,x", "--camera-view-up expects three numbers" },
    { vtu + " --bg-color 1,1,2", "--bg-color expects R,G,B in \\[0, 1\\]" },
    { vtu + " --range 5,1", "--range expects MIN,MAX with MIN < MAX" },
    { vtu + " --preset fastest",
      "--preset expects interactive, balanced or exact \\(got 'fastest'\\)" },
    { vtu + " --up W", "--up expects one of \\+X -X \\+Y -Y \\+Z -Z" },
    { vtu + " --resolution 100x100", "--resolution expects W,H" },
    { "'" + Data + "/bunny.vtp' --output x.gif", "--output 'x.gif': unknown image type" },
    // The teapot has no arrays; the normals the tool computes to shade it
    // are not data to colour by.
    { "'" + Data + "/teapot.obj' --scalars --output '" + Tmp + "/bad.png'",
      "--scalars: '[^']*teapot.obj' has no point array \\(its point arrays: none\\)" },
  };
  for (const auto& c : cases)
  {
    const Result r = RunApp(c.first);
    Check(r.Code == 2 &&
        Contains(r.Output,
          "^vtkrt-render: " + c.second +
            "[^\n]*\n\\(run vtkrt-render --help for the options\\)\n$"),
      "exit 2 and one message: " + c.second);
  }
  const Result help = RunApp("--help");
  for (const char* option :
    { "--resolution W,H", "--up ", "--scalars\\[=NAME\\]", "--cells", "--comp N", "--range MIN,MAX",
      "--bar", "--colormap", "--camera-position X,Y,Z", "--camera-focal-point", "--camera-view-up",
      "--camera-view-angle", "--samples N", "--point-size", "--edges", "--bg-color", "--color",
      "--opacity", "--shadows", "--ao N", "--progressive N", "--precision", "--preset" })
  {
    Check(
      Contains(help.Output, std::string("\n +") + option), std::string("--help lists ") + option);
  }
}

void TestWindow()
{
  if (!std::getenv("DISPLAY"))
  {
    std::cout << "SKIP: no DISPLAY (run under run-under-xvfb.sh)\n";
    std::exit(77);
  }
  // h shadows, q ambient occlusion, p picks at the centre (on the teapot)
  // and in a corner (nothing), then a left drag rotates the camera.
  const std::string keys = "# StreamVersion 1.1\n"
                           "MouseMoveEvent 150 100 0 0 0 0\n"
                           "CharEvent 150 100 0 104 1 h\n"
                           "CharEvent 150 100 0 113 1 q\n"
                           "CharEvent 150 100 0 112 1 p\n"
                           "MouseMoveEvent 2 2 0 0 0 0\n"
                           "CharEvent 2 2 0 112 1 p\n";
  const std::string drag = "LeftButtonPressEvent 150 100 0 0 0 0\n"
                           "MouseMoveEvent 190 120 0 0 0 0\n"
                           "LeftButtonReleaseEvent 190 120 0 0 0 0\n";
  WriteText(Tmp + "/keys.log", keys);
  WriteText(Tmp + "/drag.log", keys + drag);
  const std::string teapot =
    "'" + Data + "/teapot.obj' --resolution 300,200 --interaction-test-play '";
  const Result still = RunApp(teapot + Tmp + "/keys.log'");
  Check(still.Code == 0 && Contains(still.Output, "^vtkrt-render: raytrace window 300x200"),
    "no --output and a display: a traced window");
  Check(Contains(still.Output, "\nshadows on\n") &&
      Contains(still.Output, "\nambient occlusion 4 rays\n"),
    "keys h and q toggle shadows and ambient occlusion");
  Check(Contains(still.Output, "\npick \\(150, 99\\): cell [0-9]+ at world .* on the mesh") &&
      Contains(still.Output, "\npick \\(2, 197\\): nothing"),
    "key p picks the cell under the cursor (and nothing off the teapot)");
  const Result moved = RunApp(teapot + Tmp + "/drag.log'");
  std::smatch a, b;
  const std::regex camera("camera position \\(([^)]*)\\) after the events");
  const bool found =
    std::regex_search(still.Output, a, camera) && std::regex_search(moved.Output, b, camera);
  Check(found && a[1] != b[1],
    "a left drag rotates the camera (" + (found ? a[1].str() + " -> " + b[1].str() : "") + ")");
  const Result offscreen =
    RunApp("'" + Data + "/teapot.obj' --resolution 64,48 --frames 0 --output '" + Tmp + "/x.png'");
  Check(offscreen.Code == 0 && !Contains(offscreen.Output, "window") &&
      Contains(offscreen.Output, "MultiSamples 0\n") && Contains(offscreen.Output, "wrote "),
    "--output with a display still renders offscreen through EGL");
}
} // namespace

int main(int argc, char* argv[])
{
  return RunCase(argc, argv, "TestVtkrtRenderViewer", {
    { "Scalars", TestScalars },
    { "UpAxis", TestUpAxis },
    { "Camera", TestCamera },
    { "Formats", TestFormats },
    { "PicksAndFiles", TestPicksAndFiles },
    { "Strips", TestStrips },
    { "TraceKnobs", TestTraceKnobs },
    { "Look", TestLook },
    { "Progress", TestProgress },
    { "BadInput", TestBadInput },
    { "Window", TestWindow },
  });
}
