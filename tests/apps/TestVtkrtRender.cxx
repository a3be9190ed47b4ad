// End-to-end tests of vtkrt-render: runs the program, checks its exit
// status, its report and the PNG it writes.
//   TestVtkrtRender <path to vtkrt-render> <case>
// The viewer's options (scalars, camera, formats, window) are tested by
// TestVtkrtRenderViewer.
#include "vtkrtImageRegression.h"
#include "vtkrtRenderAppTest.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkCellArray.h"
#include "vtkHexahedron.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkSphereSource.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"
#include "vtkUnstructuredGrid.h"
#include "vtkUnstructuredGridWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtksys/SystemTools.hxx"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
#include <regex>
#include <string>
#include <utility>

namespace
{
// The image exists, has the requested size and a share of pixels that are
// not the app's background colour.
void CheckImage(const std::string& path, int w, int h, double minCoverage)
{
  vtkSmartPointer<vtkImageData> image = ReadPNG(path);
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  Check(image && dims[0] == w && dims[1] == h,
    path + " exists and is " + std::to_string(w) + "x" + std::to_string(h) + " (got " +
      std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + ")");
  if (!image || dims[0] != w || dims[1] != h)
  {
    return;
  }
  const int nc = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int bg[3] = { 82, 87, 110 }; // 255 * (0.32, 0.34, 0.43)
  long covered = 0;
  for (long i = 0; i < static_cast<long>(w) * h; ++i)
  {
    const unsigned char* c = p + nc * i;
    covered += std::abs(c[0] - bg[0]) + std::abs(c[1] - bg[1]) + std::abs(c[2] - bg[2]) > 12;
  }
  const double coverage = static_cast<double>(covered) / (static_cast<double>(w) * h);
  Check(coverage >= minCoverage && coverage < 0.98,
    "non-background pixels: " + std::to_string(coverage * 100) + "% (>= " +
      std::to_string(minCoverage * 100) + "%)");
}

std::string WriteSphereSTL(double radius, vtkIdType& triangles)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(32);
  sphere->Update();
  triangles = sphere->GetOutput()->GetNumberOfPolys();
  const std::string path = Tmp + "/sphere.stl";
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputConnection(sphere->GetOutputPort());
  writer->SetFileTypeToBinary();
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}

// Distance from p to triangle `cell` of `mesh`.
double DistanceToCell(vtkPolyData* mesh, vtkIdType cell, const double p[3])
{
  if (cell < 0 || cell >= mesh->GetNumberOfCells())
  {
    return 1e300;
  }
  vtkIdType n;
  const vtkIdType* ids;
  mesh->GetCellPoints(cell, n, ids);
  if (n != 3)
  {
    return 1e300;
  }
  double a[3], b[3], c[3], closest[3], d2;
  mesh->GetPoint(ids[0], a);
  mesh->GetPoint(ids[1], b);
  mesh->GetPoint(ids[2], c);
  double pcoords[3], weights[3];
  int subId;
  vtkNew<vtkTriangle> tri;
  tri->GetPoints()->SetPoint(0, a);
  tri->GetPoints()->SetPoint(1, b);
  tri->GetPoints()->SetPoint(2, c);
  tri->GetPointIds()->SetId(0, 0);
  tri->GetPointIds()->SetId(1, 1);
  tri->GetPointIds()->SetId(2, 2);
  tri->EvaluatePosition(p, closest, subId, pcoords, d2, weights);
  return std::sqrt(d2);
}

// Parses "pick (X, Y): cell N at world (x, y, z)".
bool ParsePick(const std::string& text, long long& cell, double p[3])
{
  std::smatch m;
  const std::string num = "([-+0-9.eE]+)";
  if (!std::regex_search(text, m,
        std::regex("pick \\([0-9]+, [0-9]+\\): cell ([0-9]+) at world \\(" + num + ", " + num +
          ", " + num + "\\)")))
  {
    return false;
  }
  cell = std::stoll(m[1]);
  p[0] = std::stod(m[2]);
  p[1] = std::stod(m[3]);
  p[2] = std::stod(m[4]);
  return true;
}

//------------------------------------------------------------------------------
void TestDemo()
{
  const std::string out = Tmp + "/demo.png";
  vtksys::SystemTools::RemoveFile(out);
  const Result r = RunApp("--demo --mode raster --size 320x240 --frames 2 --output '" + out + "'");
  Check(r.Code == 0, "exit status 0");
  vtkNew<vtkXMLPolyDataReader> bunny;
  bunny->SetFileName(VTKRT_DATA_DIR "/bunny.vtp");
  bunny->Update();
  vtkNew<vtkXMLPolyDataReader> spheres;
  spheres->SetFileName(VTKRT_DATA_DIR "/demo-spheres.vtp");
  spheres->Update();
  Check(ReportNumber(r.Output, "triangles") == bunny->GetOutput()->GetNumberOfPolys(),
    "report: triangles = the bunny's triangle count");
  Check(ReportNumber(r.Output, "spheres") == spheres->GetOutput()->GetNumberOfPoints(),
    "report: spheres = the number of glyph centres");
  Check(Contains(r.Output, "first frame: +[0-9.]+ ms") &&
      Contains(r.Output, "steady frame: +[0-9.]+ ms \\(mean of 2 orbit steps\\)") &&
      Contains(r.Output, "scene build: +[0-9.]+ ms"),
    "report: build, first and steady frame times");
  CheckImage(out, 320, 240, 0.08);
  vtkSmartPointer<vtkImageData> image = ReadPNG(out);
  Check(image && vtkrtCompareWithBaseline(image, "apps_demo_raster") == 1,
    "demo image matches its baseline");
}

void TestFiles()
{
  // Binary STL.
  vtkIdType sphereTriangles = 0;
  const std::string stl = WriteSphereSTL(1.0, sphereTriangles);
  const std::string out1 = Tmp + "/sphere.png";
  vtksys::SystemTools::RemoveFile(out1);
  Result r = RunApp("'" + stl + "' --size 200x160 --frames 0 --output '" + out1 + "'");
  Check(r.Code == 0, ".stl: exit status 0");
  Check(ReportNumber(r.Output, "triangles") == sphereTriangles, ".stl: triangle count reported");
  Check(ReportNumber(r.Output, "spheres") == 0, ".stl: no spheres");
  CheckImage(out1, 200, 160, 0.10);

  // OBJ with quads: a unit cube is 6 quads = 12 triangles.
  const std::string obj = Tmp + "/cube.obj";
  {
    std::ofstream f(obj);
    f << "# unit cube\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }
  const std::string out2 = Tmp + "/cube.png";
  vtksys::SystemTools::RemoveFile(out2);
  r = RunApp("'" + obj + "' --size 150x150 --azimuth 40 --elevation 30 --frames 1 --output '" +
    out2 + "'");
  Check(r.Code == 0, ".obj: exit status 0");
  Check(ReportNumber(r.Output, "triangles") == 12, ".obj: 6 quads reported as 12 triangles");
  CheckImage(out2, 150, 150, 0.10);

  // Binary PLY (a coarse sphere) and the shipped bunny .vtp as a file argument.
  const std::string ply = Tmp + "/sphere.ply";
  vtkIdType plyTriangles = 0;
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(12);
    sphere->SetPhiResolution(9);
    sphere->Update();
    plyTriangles = sphere->GetOutput()->GetNumberOfPolys();
    vtkNew<vtkPLYWriter> writer;
    writer->SetInputConnection(sphere->GetOutputPort());
    writer->SetFileTypeToBinary();
    writer->SetFileName(ply.c_str());
    writer->Write();
  }
  const std::string out4 = Tmp + "/sphere-ply.png";
  vtksys::SystemTools::RemoveFile(out4);
  r = RunApp("'" + ply + "' --size 100x90 --frames 0 --output '" + out4 + "'");
  Check(r.Code == 0 && ReportNumber(r.Output, "triangles") == plyTriangles,
    ".ply: exit status 0 and its triangle count");
  CheckImage(out4, 100, 90, 0.10);
  const std::string out5 = Tmp + "/bunny-vtp.png";
  vtksys::SystemTools::RemoveFile(out5);
  r = RunApp("'" VTKRT_DATA_DIR "/bunny.vtp' --size 120x100 --frames 0 --output '" + out5 + "'");
  vtkNew<vtkXMLPolyDataReader> bunny;
  bunny->SetFileName(VTKRT_DATA_DIR "/bunny.vtp");
  bunny->Update();
  Check(r.Code == 0 && ReportNumber(r.Output, "triangles") == bunny->GetOutput()->GetNumberOfPolys(),
    ".vtp: exit status 0 and its triangle count");
  CheckImage(out5, 120, 100, 0.10);

  // Legacy .vtk unstructured grid: one hexahedron, rendered as its surface.
  const std::string vtk = Tmp + "/hex.vtk";
  {
    vtkNew<vtkPoints> points;
    const double c[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
      { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
    vtkNew<vtkHexahedron> hex;
    for (int i = 0; i < 8; ++i)
    {
      points->InsertNextPoint(c[i]);
      hex->GetPointIds()->SetId(i, i);
    }
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(points);
    grid->InsertNextCell(hex->GetCellType(), hex->GetPointIds());
    vtkNew<vtkUnstructuredGridWriter> writer;
    writer->SetInputData(grid);
    writer->SetFileName(vtk.c_str());
    writer->Write();
  }
  const std::string out3 = Tmp + "/hex.png";
  vtksys::SystemTools::RemoveFile(out3);
  r = RunApp("'" + vtk + "' --size 120x100 --frames 0 --output '" + out3 + "'");
  Check(r.Code == 0, ".vtk grid: exit status 0");
  Check(ReportNumber(r.Output, "triangles") == 12, ".vtk grid: surface of 6 quads = 12 triangles");
  CheckImage(out3, 120, 100, 0.10);
}

void TestPick()
{
  // The centre pixel of a sphere at the origin: a cell of the sphere, and a
  // world point on that cell, at the sphere's radius.
  vtkIdType triangles = 0;
  const std::string stl = WriteSphereSTL(2.0, triangles);
  Result r = RunApp("'" + stl + "' --size 200x200 --frames 0 --pick 100 100 --output '" + Tmp +
    "/pick-sphere.png'");
  long long cell = -1;
  double p[3] = { 0, 0, 0 };
  Check(r.Code == 0 && ParsePick(r.Output, cell, p), "sphere: pick reports a cell and a point");
  Check(Contains(r.Output, "on the mesh"), "sphere: the pick is on the mesh");
  const double radius = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  Check(cell >= 0 && cell < triangles && std::abs(radius - 2.0) < 0.02,
    "sphere: picked cell " + std::to_string(cell) + " at distance " + std::to_string(radius) +
      " from the centre (radius 2)");
  // A corner pixel is background.
  r = RunApp("'" + stl + "' --size 200x200 --frames 0 --pick 2 2 --output '" + Tmp +
    "/pick-sphere.png'");
  Check(r.Code == 0 && Contains(r.Output, "pick \\(2, 2\\): nothing"), "sphere: corner picks nothing");

  // The same sphere (double points) 1e8 from the origin: the point printed
  // keeps every digit, so it still lies at the radius from the centre.
  {
    vtkNew<vtkSphereSource> far;
    far->SetRadius(2.0);
    far->SetCenter(1e8, 1e8, 1e8);
    far->SetThetaResolution(32);
    far->SetPhiResolution(32);
    far->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputConnection(far->GetOutputPort());
    const std::string farPath = Tmp + "/far-sphere.vtp";
    writer->SetFileName(farPath.c_str());
    writer->Write();
    r = RunApp("'" + farPath + "' --size 200x200 --frames 0 --pick 100 100 --output '" + Tmp + "/pick-far.png'");
    Check(r.Code == 0 && ParsePick(r.Output, cell, p), "far sphere: pick reports a cell and a point");
    const double dx = p[0] - 1e8, dy = p[1] - 1e8, dz = p[2] - 1e8;
    const double farRadius = std::sqrt(dx * dx + dy * dy + dz * dz);
    Check(std::abs(farRadius - 2.0) < 0.02,
      "far sphere: the printed point lies " + std::to_string(farRadius) + " from the centre (radius 2)");
  }

  // Looking straight down the default view up: a note, another view up,
  // and the sphere drawn (VTK would draw nothing).
  r = RunApp("'" + stl + "' --size 200x200 --frames 0 --camera-position 0,10,0 --camera-focal-point 0,0,0 "
             "--output '" + Tmp + "/top-down.png'");
  Check(r.Code == 0 && Contains(r.Output, "note: the view up is along the view direction"),
    "top-down view: exit 0 and a note on the view up");
  CheckImage(Tmp + "/top-down.png", 200, 200, 0.3);
  // A view up given along the default view direction (no position given):
  // a usage error, not a blank image.
  r = RunApp("'" + stl + "' --size 200x200 --frames 0 --camera-focal-point 0,0,0 --camera-view-up 0,0,1 "
             "--output '" + Tmp + "/blank.png'");
  Check(r.Code == 2 && Contains(r.Output, "--camera-view-up is parallel to the view direction"),
    "a view up along the default view direction: exit 2");

  // Demo scene: the centre pixel lies on the bunny; the point lies on the
  // reported cell of bunny.vtp.
  r = RunApp("--demo --size 300x200 --frames 0 --pick 150 100 --output '" + Tmp + "/pick-demo.png'");
  Check(r.Code == 0 && ParsePick(r.Output, cell, p) && Contains(r.Output, "on the mesh"),
    "demo: the centre pixel picks a cell on the mesh");
  vtkNew<vtkXMLPolyDataReader> bunny;
  bunny->SetFileName(VTKRT_DATA_DIR "/bunny.vtp");
  bunny->Update();
  const double d = DistanceToCell(bunny->GetOutput(), cell, p);
  Check(d < 1e-6, "demo: the picked point lies on cell " + std::to_string(cell) +
      " (distance " + std::to_string(d) + ")");

  // A pixel well inside a glyph sphere (strongly coloured, as is its whole
  // 7x7 neighbourhood at 600x400; the bunny and background are greyish): the pick
  // reports that sphere and a point on its surface.
  r = RunApp("--demo --size 600x400 --frames 0 --output '" + Tmp + "/pick-spheres.png'");
  vtkSmartPointer<vtkImageData> image = ReadPNG(Tmp + "/pick-spheres.png");
  int px = -1, py = -1;
  if (image)
  {
    const int nc = image->GetNumberOfScalarComponents();
    const auto* data = static_cast<const unsigned char*>(image->GetScalarPointer());
    auto saturated = [&](int x, int y) {
      const unsigned char* c = data + nc * (y * 600 + x);
      const int hi = std::max({ c[0], c[1], c[2] }), lo = std::min({ c[0], c[1], c[2] });
      return hi > 80 && hi - lo > 0.5 * hi;
    };
    for (int y = 3; y < 397 && px < 0; ++y)
    {
      for (int x = 3; x < 597 && px < 0; ++x)
      {
        bool all = true;
        for (int dy = -3; dy <= 3 && all; ++dy)
        {
          for (int dx = -3; dx <= 3 && all; ++dx)
          {
            all = saturated(x + dx, y + dy);
          }
        }
        if (all)
        {
          px = x;
          py = 399 - y; // image rows for --pick run top down
        }
      }
    }
  }
  Check(px >= 0, "demo: found a pixel inside a sphere glyph");
  if (px >= 0)
  {
    r = RunApp("--demo --size 600x400 --frames 0 --pick " + std::to_string(px) + " " +
      std::to_string(py) + " --output '" + Tmp + "/pick-spheres.png'");
    std::smatch m;
    const std::string num = "([-+0-9.eE]+)";
    const bool parsed = std::regex_search(r.Output, m,
      std::regex("sphere ([0-9]+) at world \\(" + num + ", " + num + ", " + num + "\\)"));
    Check(r.Code == 0 && parsed, "demo: the pick reports a sphere");
    if (parsed)
    {
      vtkNew<vtkXMLPolyDataReader> spheres;
      spheres->SetFileName(VTKRT_DATA_DIR "/demo-spheres.vtp");
      spheres->Update();
      const vtkIdType id = std::stoll(m[1]);
      vtkPolyData* centres = spheres->GetOutput();
      if (id < centres->GetNumberOfPoints())
      {
        double c[3];
        centres->GetPoint(id, c);
        const double radius = centres->GetPointData()->GetArray("radius")->GetTuple1(id);
        const double dx = std::stod(m[2]) - c[0], dy = std::stod(m[3]) - c[1],
                     dz = std::stod(m[4]) - c[2];
        const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
        Check(std::abs(dist - radius) < 1e-6 * (1 + radius),
          "demo: the point lies on sphere " + std::to_string(id) + " (|p - c| = " +
            std::to_string(dist) + ", radius " + std::to_string(radius) + ")");
      }
      else
      {
        Check(false, "demo: sphere id within the glyph count");
      }
    }
  }
}

void TestBadArguments()
{
  struct Case
  {
    std::string Args;
    int Code;
    std::string Message;
    std::string Environment = "";
  };
  const std::string garbage = Tmp + "/garbage.ply";
  {
    std::ofstream f(garbage);
    f << "this is not a PLY file\n";
  }
  const std::string noExt = Tmp + "/mesh.xyz";
  {
    std::ofstream f(noExt);
    f << "1 2 3\n";
  }
  const Case cases[] = {
    { "", 2, "nothing to render" },
    { "--demo --size 0x100", 2, "--size expects WxH" },
    { "--demo --size big", 2, "--size expects WxH" },
    { "--demo --size 64x64 --resolution 64,64", 2, "--size and --resolution both give the image size" },
    { "--demo --size", 2, "--size needs a value" },
    { "--demo --mode fancy", 2, "--mode expects raster or raytrace" },
    { "--demo --azimuth north", 2, "--azimuth expects a number" },
    { "--demo --samples -1", 2, "--samples expects an integer" },
    { "--demo --samples 0", 2, "--samples expects an integer in \\[1, 256\\]" },
    { "--demo --pick 5", 2, "--pick needs a value" },
    { "--demo --size 100x100 --pick 100 5", 2, "--pick 100 5 is outside the 100x100 image" },
    { "--demo --frobnicate", 2, "unknown option '--frobnicate'" },
    { "--demo --camera-position 0,10,0 --camera-focal-point 0,0,0 --camera-view-up 0,-2,0", 2,
      "--camera-view-up is parallel to the view direction" },
    { "--demo '" + noExt + "'", 2, "either --demo or a mesh file, not both" },
    { "'" + Tmp + "/does-not-exist.stl'", 1, "cannot read mesh .*does-not-exist.stl.*no such file" },
    { "'" + garbage + "'", 1, "cannot read mesh .*garbage.ply" },
    { "'" + noExt + "'", 1, "unknown extension '.xyz'" },
    { "--demo --frames 0 --size 64x64 --output /nonexistent-dir/x.png", 1,
      "cannot write '/nonexistent-dir/x.png'" },
    { "--demo --frames 0 --size 64x64 --output '" + Tmp + "/no-egl.png'", 1,
      "No usable EGL display.*EGL device 99", "VTKRT_EGL_DEVICE=99" },
  };
  for (const Case& c : cases)
  {
    const Result r = RunApp(c.Args, c.Environment);
    Check(r.Code == c.Code && Contains(r.Output, "vtkrt-render: .*" + c.Message),
      "'" + c.Args + "': exit " + std::to_string(c.Code) + " and says '" + c.Message + "'");
    // One clear message of ours, not VTK's error dump.
    Check(!Contains(r.Output, "ERROR: In ") && !Contains(r.Output, "Warning: In ") &&
        !Contains(r.Output, "ERR\\|") && !Contains(r.Output, "WARN\\|"),
      "'" + c.Args + "': no raw VTK error text");
  }
  // Raytrace knobs under --mode raster: rendered, with one note naming them.
  const Result raster = RunApp("--demo --mode raster --shadows --ao 4 --size 64x64 --frames 0 --output '" + Tmp +
    "/raster-note.png'");
  Check(raster.Code == 0 &&
      Contains(raster.Output, "vtkrt-render: note: --shadows, --ao apply to raytrace mode; ignored with --mode raster"),
    "--mode raster --shadows --ao: exit 0 and a note that they are ignored");
  const Result help = RunApp("--help");
  Check(help.Code == 0 && Contains(help.Output, "usage: vtkrt-render") &&
      Contains(help.Output, "--pick X Y") &&
      Contains(help.Output, "This build: raytrace mode (not )?available"),
    "--help prints the usage and exits 0");
}

// A file that VTK 9.1's readers would loop, abort or crash on: exit 1 with
// one line naming the file and what is wrong.
void CheckBadFile(const std::string& path, const std::string& message)
{
  const Result r = RunApp("'" + path + "' --size 64x64 --frames 0 --output '" + Tmp + "/bad.png'");
  const std::string name = vtksys::SystemTools::GetFilenameName(path);
  Check(r.Code == 1 && Contains(r.Output, "^vtkrt-render: cannot read mesh '[^']*" + name + "': " +
                         message + "\n$"),
    name + ": exit 1 and one line saying '" + message + "'");
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream f(path, std::ios::binary);
  f << text;
}

void TestBadFiles()
{
  const std::string plyHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 1\n"
                                "property list uchar int vertex_indices\nend_header\n";
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";

  // A header claiming 10^9 vertices: vtkPLYReader would loop on end-of-file.
  std::string header = plyHeader;
  header.replace(header.find("vertex 3"), 8, "vertex 1000000000");
  WriteText(Tmp + "/billion.ply", header + triangle + "3 0 1 2\n");
  CheckBadFile(Tmp + "/billion.ply",
    "header declares 1000000000 vertices, 1 face \\(at least [0-9]+ bytes of ascii data\\) but "
    "only 26 bytes follow the header");

  // A binary PLY cut inside its vertices, and one missing only its last
  // bytes (the last face's list is cut short).
  const std::string good = Tmp + "/sphere.ply";
  vtkIdType sphereTriangles = 0;
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->Update();
    sphereTriangles = sphere->GetOutput()->GetNumberOfPolys();
    vtkNew<vtkPLYWriter> writer;
    writer->SetInputConnection(sphere->GetOutputPort());
    writer->SetFileTypeToBinary();
    writer->SetFileName(good.c_str());
    writer->Write();
  }
  std::string bytes;
  {
    std::ifstream f(good, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  WriteText(Tmp + "/cut.ply", bytes.substr(0, bytes.find("end_header\n") + 11 + 20));
  CheckBadFile(Tmp + "/cut.ply",
    "header declares [0-9]+ vertices, [0-9]+ faces \\(at least [0-9]+ bytes of "
    "binary_(little|big)_endian data\\) but only [0-9]+ bytes follow the header");
  WriteText(Tmp + "/short.ply", bytes.substr(0, bytes.size() - 5));
  CheckBadFile(Tmp + "/short.ply", "face ([0-9]+) of \\1 is cut short by the end of the file");

  // A binary STL cut inside its triangles (vtkSTLReader reads the first
  // ones without a word), and an empty STL.
  {
    vtkNew<vtkSphereSource> sphere;
    vtkNew<vtkSTLWriter> writer;
    writer->SetInputConnection(sphere->GetOutputPort());
    writer->SetFileTypeToBinary();
    writer->SetFileName((Tmp + "/sphere.stl").c_str());
    writer->Write();
    std::ifstream f(Tmp + "/sphere.stl", std::ios::binary);
    const std::string stl((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    WriteText(Tmp + "/cut.stl", stl.substr(0, 84 + 50 * 10 + 7));
    CheckBadFile(Tmp + "/cut.stl", "binary STL header declares [0-9]+ triangles \\([0-9]+ bytes\\) but the "
                                   "file has 591 bytes \\(10 whole triangles\\)");
    // A binary header may start with "solid" as an ascii file does.
    std::string solid = stl.substr(0, 84 + 50 * 10 + 7);
    solid.replace(0, 5, "solid");
    WriteText(Tmp + "/cut-solid.stl", solid);
    CheckBadFile(Tmp + "/cut-solid.stl", "binary STL header declares [0-9]+ triangles \\([0-9]+ bytes\\) but "
                                         "the file has 591 bytes \\(10 whole triangles\\)");
    WriteText(Tmp + "/empty.stl", "");
    CheckBadFile(Tmp + "/empty.stl", "the file is empty");
    const Result r = RunApp("'" + Tmp + "/sphere.stl' --size 64x64 --frames 0 --output '" + Tmp + "/good.png'");
    Check(r.Code == 0 && ReportNumber(r.Output, "triangles") == sphere->GetOutput()->GetNumberOfPolys(),
      "sphere.stl whole: exit 0 and all its triangles");
  }

  // An ascii PLY line with fewer values than its list length says.
  WriteText(Tmp + "/short-line.ply", plyHeader + triangle + "3 0 1\n");
  CheckBadFile(Tmp + "/short-line.ply", "face 1 of 1 has 3 values on its line but needs 4");

  // Face indices past the points: VTK reads them, then normals crash.
  WriteText(Tmp + "/index.ply", plyHeader + triangle + "3 0 1 7\n");
  CheckBadFile(Tmp + "/index.ply",
    "polygon 1 of 1 refers to point id 7 but the mesh has 3 points \\(ids 0 to 2\\)");
  const std::string objTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  WriteText(Tmp + "/index.obj", objTriangle + "f 1 2 9\n");
  CheckBadFile(Tmp + "/index.obj",
    "polygon 1 of 1 refers to point id 8 but the mesh has 3 points \\(ids 0 to 2\\)");
  WriteText(Tmp + "/negative.obj", objTriangle + "f 1 2 -9\n");
  CheckBadFile(Tmp + "/negative.obj",
    "polygon 1 of 1 refers to point id -[0-9]+ but the mesh has 3 points \\(ids 0 to 2\\)");
  WriteText(Tmp + "/index.vtk", "# vtk DataFile Version 3.0\nbad\nASCII\n"
                                 "DATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n"
                                 "0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 9\nCELL_TYPES 1\n5\n");
  CheckBadFile(Tmp + "/index.vtk",
    "cell 1 of 1 refers to point id 9 but the mesh has 3 points \\(ids 0 to 2\\)");
  // A face of two points, an empty one, a legacy polygon of two: VTK's
  // polydata cannot build its cells past them and its normals crash.
  WriteText(Tmp + "/two-point-face.ply", plyHeader + triangle + "2 0 1\n");
  CheckBadFile(Tmp + "/two-point-face.ply", "polygon 1 of 1 has 2 point\\(s\\); a polygon needs at least 3");
  WriteText(Tmp + "/empty-face.ply", plyHeader + triangle + "0\n");
  CheckBadFile(Tmp + "/empty-face.ply", "polygon 1 of 1 has 0 point\\(s\\); a polygon needs at least 3");
  WriteText(Tmp + "/two-point.vtk", "# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\n"
                                     "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 7\n3 0 1 2\n2 1 2\n");
  CheckBadFile(Tmp + "/two-point.vtk", "polygon 2 of 2 has 2 point\\(s\\); a polygon needs at least 3");
  WriteText(Tmp + "/missing-face.ply", plyHeader.substr(0, plyHeader.find("face 1")) + "face 2" +
      plyHeader.substr(plyHeader.find("face 1") + 6) + triangle + "3 0 1 2\n");
  CheckBadFile(Tmp + "/missing-face.ply", "face 2 of 2 is missing: the file ends before it");

  // Good files around them still render: the same triangle as ascii PLY and
  // OBJ, and the binary sphere whole.
  const std::pair<std::string, vtkIdType> goodFiles[] = { { Tmp + "/triangle.ply", 1 },
    { Tmp + "/triangle.obj", 1 }, { good, sphereTriangles } };
  WriteText(goodFiles[0].first, plyHeader + triangle + "3 0 1 2\n");
  WriteText(goodFiles[1].first, objTriangle + "f 1 2 3\n");
  for (const auto& file : goodFiles)
  {
    const Result r =
      RunApp("'" + file.first + "' --size 64x64 --frames 0 --output '" + Tmp + "/good.png'");
    Check(r.Code == 0 && ReportNumber(r.Output, "triangles") == file.second,
      file.first + ": exit 0 and " + std::to_string(file.second) + " triangle(s) reported");
  }
}

void TestRaytraceMode()
{
  const std::string out = Tmp + "/raytrace.png";
  vtksys::SystemTools::RemoveFile(out);
  const Result r = RunApp("--demo --mode raytrace --size 160x120 --frames 1 --output '" + out + "'");
#ifdef VTKRT_HAVE_RAYTRACE_PASS
  Check(r.Code == 0, "raytrace: exit status 0");
  CheckImage(out, 160, 120, 0.05);
  Check(Contains(r.Output, "of which:   extraction ") && Contains(r.Output, ", BVH build ") &&
      Contains(r.Output, ", shader compile "),
    "raytrace: the first frame by phase is reported");
  // The traced scene covers the same pixels as the rasterized one (shading
  // may differ; silhouettes agree up to edge pixels).
  const std::string rasterOut = Tmp + "/raster.png";
  const Result raster =
    RunApp("--demo --mode raster --size 160x120 --frames 0 --output '" + rasterOut + "'");
  Check(raster.Code == 0 && !Contains(raster.Output, "of which:"), "raster: no pass phases reported");
  vtkSmartPointer<vtkImageData> a = ReadPNG(out);
  vtkSmartPointer<vtkImageData> b = ReadPNG(rasterOut);
  if (raster.Code == 0 && a && b)
  {
    const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
    const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
    const int na = a->GetNumberOfScalarComponents(), nb = b->GetNumberOfScalarComponents();
    const int bg[3] = { 82, 87, 110 };
    auto covered = [&](const unsigned char* c) {
      return std::abs(c[0] - bg[0]) + std::abs(c[1] - bg[1]) + std::abs(c[2] - bg[2]) > 12;
    };
    long both = 0, either = 0;
    for (long i = 0; i < 160L * 120; ++i)
    {
      const bool ca = covered(pa + na * i), cb = covered(pb + nb * i);
      both += ca && cb;
      either += ca || cb;
    }
    const double iou = either ? static_cast<double>(both) / either : 0.0;
    Check(iou > 0.97, "raytrace and raster cover the same pixels (IoU " + std::to_string(iou) + ")");
  }
  else
  {
    Check(false, "raster reference rendered");
  }
#else
  Check(r.Code == 3 && Contains(r.Output, "raytrace mode is not available in this build"),
    "raytrace: this build says it is not available and exits 3");
  Check(!vtksys::SystemTools::FileExists(out, true), "raytrace: no image written");
#endif
}
} // namespace

int main(int argc, char* argv[])
{
  return RunCase(argc, argv, "TestVtkrtRender", {
    { "Demo", TestDemo },
    { "Files", TestFiles },
    { "Pick", TestPick },
    { "BadArguments", TestBadArguments },
    { "BadFiles", TestBadFiles },
    { "RaytraceMode", TestRaytraceMode },
  });
}
