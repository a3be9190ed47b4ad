// vtkHardwareSelector, vtkPropPicker, vtkRenderer::PickProp and
// vtkWorldPointPicker with the pass on answer as they do with raster: each
// case builds the same scene twice, one renderer rasterized, one traced, and
// compares what VTK's own selection classes return.
#include "vtkrtPassTestUtils.h"

#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCubeSource.h"
#include "vtkDataObject.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkOutlineSource.h"
#include "vtkPropPicker.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTypeInt32Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWorldPointPicker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
constexpr int W = 300;
constexpr int H = 200;

/// A scene in one window: a fine sphere mesh, a cube, sphere glyphs (each
/// its own actor), optionally behind a box outline (lines) that raster draws.
struct Scene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(W, H);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRayTracePass> Pass;
  std::vector<vtkSmartPointer<vtkActor>> Actors; ///< in a fixed order: mesh, cube, glyphs[, box]
  std::vector<vtkSmartPointer<vtkObject>> Keep;

  Scene(bool traced, bool rasterBox)
  {
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(32);
    this->Add(sphere->GetOutputPort());
    vtkNew<vtkCubeSource> cube;
    cube->SetCenter(2.5, 0.3, 0.0);
    this->Add(cube->GetOutputPort());
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(-3, -2, 0);
    plane->SetPoint1(-1, -2, 0);
    plane->SetPoint2(-3, 2, 0);
    plane->SetResolution(3, 4);
    vtkNew<vtkSphereSource> glyph;
    glyph->SetRadius(0.2);
    glyph->SetThetaResolution(24);
    glyph->SetPhiResolution(24);
    vtkNew<vtkGlyph3DMapper> glyphs;
    glyphs->SetInputConnection(plane->GetOutputPort());
    glyphs->SetSourceConnection(glyph->GetOutputPort());
    glyphs->ScalingOff();
    this->AddMapper(glyphs);
    this->Keep.insert(this->Keep.end(), { sphere.Get(), cube.Get(), plane.Get(), glyph.Get() });
    if (rasterBox)
    {
      // Lines: left to raster, composited with the traced ids by depth.
      vtkNew<vtkOutlineSource> box;
      box->SetBounds(-0.5, 0.5, -0.5, 0.5, 0.8, 1.6);
      this->Add(box->GetOutputPort());
      this->Actors.back()->GetProperty()->SetLineWidth(3);
      this->Keep.push_back(box.Get());
    }
    this->Renderer->ResetCamera();
    if (traced)
    {
      this->Renderer->SetPass(this->Pass);
    }
    this->Window->Render();
  }

  void Add(vtkAlgorithmOutput* port)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(port);
    this->AddMapper(mapper);
  }

  void AddMapper(vtkMapper* mapper)
  {
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    this->Renderer->AddActor(actor);
    this->Actors.push_back(actor);
  }

  int IndexOf(vtkObjectBase* prop) const
  {
    for (std::size_t i = 0; i < this->Actors.size(); ++i)
    {
      if (this->Actors[i] == prop)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  }

  /// Display coordinates of a world point.
  std::array<int, 2> Project(const double p[3])
  {
    this->Renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
    this->Renderer->WorldToDisplay();
    const double* d = this->Renderer->GetDisplayPoint();
    return { { static_cast<int>(std::floor(d[0])), static_cast<int>(std::floor(d[1])) } };
  }
};

/// One selection node as a test compares it.
struct Selected
{
  unsigned int Composite = 0;
  std::set<vtkIdType> Ids;
};

std::map<int, Selected> Select(Scene& scene, const unsigned int area[4], int association)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.Renderer);
  selector->SetArea(area[0], area[1], area[2], area[3]);
  selector->SetFieldAssociation(association);
  vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(selector->Select());
  std::map<int, Selected> out;
  for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = result->GetNode(n);
    Selected& s = out[scene.IndexOf(node->GetProperties()->Get(vtkSelectionNode::PROP()))];
    s.Composite = static_cast<unsigned int>(node->GetProperties()->Get(vtkSelectionNode::COMPOSITE_INDEX()));
    vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    for (vtkIdType k = 0; ids && k < ids->GetNumberOfTuples(); ++k)
    {
      s.Ids.insert(ids->GetValue(k));
    }
  }
  return out;
}

/// |a and b| / |a or b|.
double Overlap(const std::set<vtkIdType>& a, const std::set<vtkIdType>& b)
{
  std::vector<vtkIdType> both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
  const std::size_t either = a.size() + b.size() - both.size();
  return either ? static_cast<double>(both.size()) / static_cast<double>(either) : 1.0;
}

/// Raster's and the pass's selections agree: the same props and composite
/// indices; the same ids, up to silhouette pixels for the fine mesh (prop 0:
/// a pixel center on a shared edge may go to either neighbour).
void CompareSelections(const std::string& label, const std::map<int, Selected>& raster,
  const std::map<int, Selected>& traced)
{
  std::ostringstream props;
  for (const auto& r : raster)
  {
    props << r.first << " ";
  }
  Check(!raster.empty(), label + ": raster selects something (props " + props.str() + ")");
  Check(raster.size() == traced.size(), label + ": as many selected props as raster");
  for (const auto& r : raster)
  {
    const auto t = traced.find(r.first);
    const std::string what = label + ", prop " + std::to_string(r.first);
    Check(t != traced.end(), what + ": selected with the pass too");
    if (t == traced.end())
    {
      continue;
    }
    // VTK 9.1's glyph mapper gives a plain input no composite index (the
    // pixel keeps whatever the previous prop set): only the others compare.
    Check(r.first == 2 || r.second.Composite == t->second.Composite, what + ": same composite index");
    const double overlap = Overlap(r.second.Ids, t->second.Ids);
    const double needed = r.first == 0 ? 0.98 : 1.0;
    Check(overlap >= needed, what + ": ids overlap " + std::to_string(overlap) + " (" +
        std::to_string(r.second.Ids.size()) + " raster, " + std::to_string(t->second.Ids.size()) +
        " traced)");
  }
}

void CompareAreas(int association, bool rasterBox)
{
  Scene raster(false, rasterBox);
  Scene traced(true, rasterBox);
  Check(traced.Pass->GetNumberOfTracedProps() == 3, "mesh, cube and glyphs are traced");
  auto before = Grab(traced.Window);
  const unsigned int areas[][4] = { { 0, 0, W - 1, H - 1 }, { 100, 50, 200, 150 },
    { 20, 20, 90, 110 }, { 140, 90, 150, 100 } };
  for (const auto& area : areas)
  {
    std::ostringstream label;
    label << (association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "cells" : "points")
          << (rasterBox ? " with a raster box" : "") << ", area " << area[0] << "," << area[1]
          << "-" << area[2] << "," << area[3];
    CompareSelections(label.str(), Select(raster, area, association), Select(traced, area, association));
  }
  // Selecting changes nothing: each actor has its own mapper back and the
  // next frame is the same picture.
  Check(vtkGlyph3DMapper::SafeDownCast(traced.Actors[2]->GetMapper()) != nullptr,
    "the glyph actor has its own mapper back");
  traced.Window->Render();
  Check(CountDifferingPixels(before, Grab(traced.Window), 0) == 0, "the frame after selecting is unchanged");
  NoVTKOutput("selection");
}

void TestCells()
{
  CompareAreas(vtkDataObject::FIELD_ASSOCIATION_CELLS, false);
  CompareAreas(vtkDataObject::FIELD_ASSOCIATION_CELLS, true);
}

void TestPoints()
{
  CompareAreas(vtkDataObject::FIELD_ASSOCIATION_POINTS, false);
}

/// vtkCompositePolyDataMapper2: each block reports its flat index.
void TestComposite()
{
  auto build = [](bool traced, Scene*& out) {
    out = new Scene(traced, false);
    vtkNew<vtkMultiBlockDataSet> blocks;
    const double centers[3][3] = { { -1.0, 2.5, 0.0 }, { 0.5, 2.5, 0.0 }, { 2.0, 2.5, 0.0 } };
    for (int b = 0; b < 3; ++b)
    {
      vtkNew<vtkSphereSource> s;
      s->SetCenter(centers[b][0], centers[b][1], centers[b][2]);
      s->SetRadius(0.6);
      s->Update();
      // Block 1 stays empty: an empty child takes a flat index too.
      blocks->SetBlock(b == 1 ? 3 : b, s->GetOutput());
    }
    vtkNew<vtkCompositePolyDataMapper2> mapper;
    mapper->SetInputDataObject(blocks);
    out->AddMapper(mapper);
    out->Renderer->ResetCamera();
    out->Window->Render();
  };
  Scene* raster = nullptr;
  Scene* traced = nullptr;
  build(false, raster);
  build(true, traced);
  Check(traced->Pass->GetNumberOfTracedProps() == 4, "the composite actor is traced too");
  const unsigned int area[4] = { 0, 0, W - 1, H - 1 };
  const int cells = vtkDataObject::FIELD_ASSOCIATION_CELLS;
  auto r = Select(*raster, area, cells);
  auto t = Select(*traced, area, cells);
  std::set<unsigned int> rasterComposites, tracedComposites;
  Check(r.count(3) == 1 && t.count(3) == 1, "the composite actor is selected");
  // Nodes of one prop with several composite indices: compare them all.
  for (Scene* s : { raster, traced })
  {
    vtkNew<vtkHardwareSelector> sel;
    sel->SetRenderer(s->Renderer);
    sel->SetArea(0, 0, W - 1, H - 1);
    vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(sel->Select());
    std::set<unsigned int>& composites = s == raster ? rasterComposites : tracedComposites;
    for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
    {
      vtkInformation* p = result->GetNode(n)->GetProperties();
      if (s->IndexOf(p->Get(vtkSelectionNode::PROP())) == 3)
      {
        composites.insert(static_cast<unsigned int>(p->Get(vtkSelectionNode::COMPOSITE_INDEX())));
      }
    }
  }
  std::ostringstream seen;
  for (unsigned int c : rasterComposites)
  {
    seen << c << " ";
  }
  Check(rasterComposites.size() == 3 && rasterComposites == tracedComposites,
    "the blocks' composite indices are raster's (" + seen.str() + ")");
  delete raster;
  delete traced;
  NoVTKOutput("composite");
}

/// vtkPropPicker, vtkRenderer::PickProp and vtkWorldPointPicker.
void TestPropPicking()
{
  Scene raster(false, false);
  Scene traced(true, false);
  const double centers[][3] = { { 0, 0, 1 }, { 2.5, 0.3, 0.5 }, { -1.666, 0, 0.2 }, { 0, 1.9, 0 } };
  const char* names[] = { "the mesh", "the cube", "a glyph", "an empty pixel" };
  for (int c = 0; c < 4; ++c)
  {
    const std::array<int, 2> xy = raster.Project(centers[c]);
    vtkNew<vtkPropPicker> r, t;
    r->Pick(xy[0], xy[1], 0, raster.Renderer);
    t->Pick(xy[0], xy[1], 0, traced.Renderer);
    const int expected = c < 3 ? c : -1;
    Check(raster.IndexOf(r->GetActor()) == expected, std::string("raster's vtkPropPicker finds ") + names[c]);
    Check(traced.IndexOf(t->GetActor()) == expected, std::string("the pass's vtkPropPicker finds ") + names[c]);
    if (c < 3)
    {
      const double* pr = r->GetPickPosition();
      const double* pt = t->GetPickPosition();
      Check(std::hypot(pr[0] - pt[0], pr[1] - pt[1], pr[2] - pt[2]) < 0.02,
        std::string("vtkPropPicker's world point on ") + names[c] + " is raster's");
    }
    vtkAssemblyPath* ar = raster.Renderer->PickProp(xy[0], xy[1]);
    vtkAssemblyPath* at = traced.Renderer->PickProp(xy[0], xy[1]);
    const int ir = ar ? raster.IndexOf(ar->GetFirstNode()->GetViewProp()) : -1;
    const int it = at ? traced.IndexOf(at->GetFirstNode()->GetViewProp()) : -1;
    Check(ir == expected && it == ir, std::string("PickProp(x, y) at ") + names[c] + " is raster's");
  }
  // An area over everything: the same picked props.
  auto pickedIn = [](Scene& s) {
    std::set<int> picked;
    s.Renderer->PickProp(0, 0, W - 1, H - 1);
    vtkPropCollection* props = s.Renderer->GetPickResultProps();
    vtkCollectionSimpleIterator it;
    props->InitTraversal(it);
    while (vtkProp* p = props->GetNextProp(it))
    {
      picked.insert(s.IndexOf(p));
    }
    return picked;
  };
  Check(pickedIn(raster) == pickedIn(traced) && pickedIn(traced).size() == 3,
    "PickProp(x0, y0, x1, y1) over the window picks the three props, as raster");
  // The z-buffer picker reads the traced depth.
  const std::array<int, 2> xy = raster.Project(centers[0]);
  vtkNew<vtkWorldPointPicker> r, t;
  r->Pick(xy[0], xy[1], 0, raster.Renderer);
  t->Pick(xy[0], xy[1], 0, traced.Renderer);
  const double* pr = r->GetPickPosition();
  const double* pt = t->GetPickPosition();
  Check(std::hypot(pr[0] - pt[0], pr[1] - pt[1], pr[2] - pt[2]) < 0.02,
    "vtkWorldPointPicker's point is raster's");
  NoVTKOutput("prop picking");
}

/// Picking between progressive frames leaves the accumulated image alone:
/// the frame after continues the sum, as if no pick had happened.
void TestAccumulation()
{
  Scene picked(true, false);
  Scene untouched(true, false);
  for (Scene* s : { &picked, &untouched })
  {
    s->Pass->ProgressiveAccumulationOn();
    for (int frame = 0; frame < 3; ++frame)
    {
      s->Window->Render();
    }
  }
  Check(picked.Pass->GetAccumulatedFrames() == 3, "accumulation: three frames summed");
  const std::array<int, 2> xy = picked.Project(std::array<double, 3>{ { 0, 0, 1 } }.data());
  vtkNew<vtkPropPicker> picker;
  picker->Pick(xy[0], xy[1], 0, picked.Renderer);
  const unsigned int area[4] = { 0, 0, W - 1, H - 1 };
  Select(picked, area, vtkDataObject::FIELD_ASSOCIATION_CELLS);
  picked.Window->Render();
  untouched.Window->Render();
  Check(picked.Pass->GetAccumulatedFrames() == 4, "accumulation: the frame after the picks is the fourth");
  Check(Difference(Grab(picked.Window), Grab(untouched.Window)) == 0.0,
    "accumulation: the same image as four frames without picks");
  NoVTKOutput("accumulation");
}

/// Cell ids past 2^24 take the selector's high 24-bit passes: a quad whose
/// two triangles are cells 2^24 + 5 and + 6, after 2^24 + 5 one-point
/// polygons (cells that draw nothing, traced or rasterized).
void TestHighCellIds()
{
  const vtkIdType skipped = (vtkIdType(1) << 24) + 5;
  vtkNew<vtkPoints> points;
  const double corners[4][3] = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 } };
  for (const auto& c : corners)
  {
    points->InsertNextPoint(c);
  }
  vtkNew<vtkTypeInt32Array> offsets;
  vtkNew<vtkTypeInt32Array> connectivity;
  offsets->SetNumberOfValues(skipped + 3);
  connectivity->SetNumberOfValues(skipped + 6);
  for (vtkIdType c = 0; c <= skipped; ++c)
  {
    offsets->SetValue(c, static_cast<vtkTypeInt32>(c));
  }
  for (vtkIdType c = 0; c < skipped; ++c)
  {
    connectivity->SetValue(c, 0);
  }
  const vtkTypeInt32 quad[6] = { 0, 1, 2, 0, 2, 3 };
  for (int k = 0; k < 6; ++k)
  {
    connectivity->SetValue(skipped + k, quad[k]);
  }
  offsets->SetValue(skipped + 1, static_cast<vtkTypeInt32>(skipped + 3));
  offsets->SetValue(skipped + 2, static_cast<vtkTypeInt32>(skipped + 6));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polys);

  auto win = MakeWindow(64, 64);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(MeshActor(mesh));
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(pass->GetNumberOfTracedProps() == 1, "high ids: the quad is traced");
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(ren);
  selector->SetArea(0, 0, 63, 63);
  vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(selector->Select());
  Check(selector->HasHighCellIds(), "high ids: the selector takes its high 24-bit passes");
  std::set<vtkIdType> ids;
  for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
  {
    vtkIdTypeArray* list = vtkIdTypeArray::SafeDownCast(result->GetNode(n)->GetSelectionList());
    for (vtkIdType k = 0; list && k < list->GetNumberOfTuples(); ++k)
    {
      ids.insert(list->GetValue(k));
    }
  }
  Check(ids == std::set<vtkIdType>{ skipped, skipped + 1 },
    "high ids: the quad's cells " + std::to_string(skipped) + " and " + std::to_string(skipped + 1) +
      " (" + std::to_string(ids.size()) + " ids)");
  NoVTKOutput("high ids");
}

/// The cell ids a cell selection of the pixel at `d` returns.
std::set<vtkIdType> CellsAt(vtkRenderer* ren, const std::array<int, 2>& d)
{
  const unsigned int pixel[4] = { static_cast<unsigned int>(d[0]), static_cast<unsigned int>(d[1]),
    static_cast<unsigned int>(d[0]), static_cast<unsigned int>(d[1]) };
  return SelectedCells(ren, pixel);
}

/// Points drawn as spheres report the cell that holds them, as raster does
/// (the first in VTK's numbering: verts, lines, polygons): one-point verts
/// in reverse order, a poly-vertex, points shared with two triangles (points
/// representation, where a point of the triangles alone reports the first
/// of them), a point on a coordinate plane; cell scalars color each sphere by
/// that cell. A second actor (a shifted copy) puts its spheres' cell ids
/// past the first's in the sphere buffer.
void TestPointCells()
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 10; ++i)
  {
    // Point 0 at the origin: a zero coordinate once scaled the sphere away.
    points->InsertNextPoint(0.4 * i, i % 2 == 0 ? 0.0 : 0.3, 0.0);
  }
  points->InsertNextPoint(1.4, 0.9, 0.0); // in the two triangles alone
  points->InsertNextPoint(2.2, 1.0, 0.0); // in the second triangle alone
  vtkNew<vtkCellArray> verts;
  for (vtkIdType k = 0; k < 5; ++k)
  {
    const vtkIdType point = 4 - k;
    verts->InsertNextCell(1, &point);
  }
  const vtkIdType many[5] = { 9, 8, 7, 6, 5 };
  verts->InsertNextCell(5, many);
  vtkNew<vtkCellArray> polys;
  const vtkIdType first[3] = { 3, 4, 10 }, second[3] = { 4, 11, 10 };
  polys->InsertNextCell(3, first);
  polys->InsertNextCell(3, second);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(verts);
  poly->SetPolys(polys);
  vtkNew<vtkUnsignedCharArray> cellColors;
  cellColors->SetNumberOfComponents(3);
  for (int c = 0; c < 8; ++c)
  {
    const unsigned char rgb[3] = { static_cast<unsigned char>(30 * c), static_cast<unsigned char>(255 - 30 * c),
      static_cast<unsigned char>(c % 2 == 0 ? 200 : 60) };
    cellColors->InsertNextTypedTuple(rgb);
  }
  poly->GetCellData()->SetScalars(cellColors);
  const double shift[3] = { 0.0, 1.6, 0.0 };
  vtkSmartPointer<vtkPolyData> shifted = Shifted(poly, shift);
  for (const bool pointsRepresentation : { false, true })
  {
    const std::string label = pointsRepresentation ? "points representation" : "verts";
    auto win = MakeWindow(W, H);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    for (vtkPolyData* data : { poly.Get(), shifted.Get() })
    {
      vtkSmartPointer<vtkActor> actor = MeshActor(data);
      actor->GetMapper()->ScalarVisibilityOn();
      actor->GetMapper()->SetScalarModeToUseCellData();
      actor->GetProperty()->RenderPointsAsSpheresOn();
      actor->GetProperty()->SetPointSize(16);
      if (pointsRepresentation)
      {
        actor->GetProperty()->SetRepresentationToPoints();
      }
      ren->AddActor(actor);
    }
    ren->ResetCamera();
    // The spheres' centres: under verts, only the verts' points are
    // spheres (a triangle's corner pixel may go to either triangle).
    std::vector<std::array<int, 2>> pixels;
    auto project = [&]() {
      pixels.clear();
      for (vtkPolyData* data : { poly.Get(), shifted.Get() })
      {
        for (vtkIdType i = 0; i < (pointsRepresentation ? data->GetNumberOfPoints() : 10); ++i)
        {
          ren->SetWorldPoint(data->GetPoint(i)[0], data->GetPoint(i)[1], 0.0, 1.0);
          ren->WorldToDisplay();
          const double* d = ren->GetDisplayPoint();
          pixels.push_back({ { static_cast<int>(d[0]), static_cast<int>(d[1]) } });
        }
      }
    };
    win->Render();
    project();
    const auto rasterImage = Grab(win);
    std::vector<std::set<vtkIdType>> rasterCells;
    for (const auto& pixel : pixels)
    {
      rasterCells.push_back(CellsAt(ren, pixel));
    }
    vtkNew<vtkRayTracePass> pass;
    ren->SetPass(pass);
    win->Render();
    const auto tracedImage = Grab(win);
    Check(pass->GetNumberOfTracedProps() == 2, label + ": traced");
    int same = 0;
    std::ostringstream got;
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      const std::set<vtkIdType> cells = CellsAt(ren, pixels[i]);
      same += cells == rasterCells[i] && cells.size() == 1 ? 1 : 0;
      got << " " << (cells.empty() ? -1 : *cells.begin()) << "/"
          << (rasterCells[i].empty() ? -1 : *rasterCells[i].begin());
    }
    Check(same == static_cast<int>(pixels.size()),
      label + ": each point's sphere selects raster's cell (traced/raster:" + got.str() + ")");
    const double rmse = RootMeanSquareError(Blurred(rasterImage), Blurred(tracedImage));
    Check(rmse < 8.0, label + ": the spheres' cell colors as raster's (blurred RMSE " + std::to_string(rmse) + ")");
    if (rmse >= 8.0)
    {
      WriteFailedImages("SelectionPointCells", rasterImage, tracedImage);
    }
    NoVTKOutput(label);
  }

  // One point, on a coordinate plane: a zero coordinate once scaled its
  // sphere away, with a warning that it was too small to shade.
  vtkNew<vtkPoints> one;
  one->InsertNextPoint(0.3, 0.2, 0.0);
  vtkNew<vtkCellArray> vertex;
  const vtkIdType zero = 0;
  vertex->InsertNextCell(1, &zero);
  vtkNew<vtkPolyData> single;
  single->SetPoints(one);
  single->SetVerts(vertex);
  auto win = MakeWindow(W, H);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkSmartPointer<vtkActor> actor = MeshActor(single);
  actor->GetProperty()->RenderPointsAsSpheresOn();
  actor->GetProperty()->SetPointSize(20);
  ren->AddActor(actor);
  ren->ResetCamera();
  const RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  const double black[3] = { 0, 0, 0 };
  const long rasterPixels = CountForegroundPixels(frames.Raster, black);
  const long tracedPixels = CountForegroundPixels(frames.Traced, black);
  Check(rasterPixels > 200 && std::abs(tracedPixels - rasterPixels) <= rasterPixels / 10,
    "one point at z = 0: its sphere drawn (" + std::to_string(tracedPixels) + " pixels, raster " +
      std::to_string(rasterPixels) + ")");
  NoVTKOutput("one point at z = 0");
}

/// An area outside the window, an empty scene, a selector with no renderer.
void TestBadInput()
{
  Scene raster(false, false);
  Scene traced(true, false);
  // VTK's selector reads the pixels of the area as they come (outside the
  // window they are undefined, for raster too): it must not crash.
  const unsigned int outside[4] = { W - 20, H - 20, W + 50, H + 50 };
  const int cells = vtkDataObject::FIELD_ASSOCIATION_CELLS;
  auto before = Grab(traced.Window);
  Select(raster, outside, cells);
  Select(traced, outside, cells);
  traced.Window->Render();
  Check(CountDifferingPixels(before, Grab(traced.Window), 0) == 0,
    "an area partly outside the window: no crash, the next frame unchanged");
  Output->Clear();

  auto win = MakeWindow(64, 64);
  vtkNew<vtkRenderer> empty;
  vtkNew<vtkRayTracePass> pass;
  empty->SetPass(pass);
  win->AddRenderer(empty);
  win->Render();
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(empty);
  selector->SetArea(0, 0, 63, 63);
  vtkSmartPointer<vtkSelection> none = vtk::TakeSmartPointer(selector->Select());
  Check(none && none->GetNumberOfNodes() == 0, "an empty scene selects nothing");
  NoVTKOutput("empty scene");

  vtkNew<vtkHardwareSelector> orphan;
  vtkSelection* nothing = orphan->Select();
  Check(nothing == nullptr && Output->GetNumberOfErrors() == 1,
    "a selector with no renderer: VTK's error, no selection");
  Output->Clear();
}
/// A selection traces only the pixels it reads, once a capture: a pick's
/// first pass traces its one pixel and its later passes read that trace
/// again; an area's first pass traces the area's part inside the viewport,
/// and a later selection of the same pixels reads it again until the camera
/// or the scene changes (also when a frame in between rebuilt the scene).
/// (Every pass traced the whole viewport before: 7-12x raster's pick time
/// in a user trial.)
void TestTracedArea()
{
  Scene traced(true, false);
  std::vector<vtkTypeInt64> perPass;
  vtkNew<vtkCallbackCommand> record;
  struct Target
  {
    Scene* S;
    std::vector<vtkTypeInt64>* PerPass;
  } target{ &traced, &perPass };
  record->SetClientData(&target);
  record->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
    auto* t = static_cast<Target*>(data);
    if (t->S->Renderer->GetSelector())
    {
      t->PerPass->push_back(t->S->Pass->GetLastTracedPixels());
    }
  });
  traced.Renderer->AddObserver(vtkCommand::EndEvent, record);
  const auto onceThenReused = [&perPass](vtkTypeInt64 pixels, std::size_t passes, const std::string& what) {
    std::ostringstream s;
    s << what << ": pixels traced per selector pass:";
    for (vtkTypeInt64 n : perPass)
    {
      s << " " << n;
    }
    s << " (" << pixels << ", then 0 in each of at least " << passes - 1 << " more)";
    const bool ok = perPass.size() >= passes && perPass[0] == pixels &&
      std::all_of(perPass.begin() + 1, perPass.end(), [](vtkTypeInt64 n) { return n == 0; });
    Check(ok, s.str());
    perPass.clear();
  };
  const double center[3] = { 0, 0, 1 };
  const std::array<int, 2> xy = traced.Project(center);
  vtkAssemblyPath* path = traced.Renderer->PickProp(xy[0], xy[1]);
  Check(path && traced.IndexOf(path->GetFirstNode()->GetViewProp()) == 0, "TracedArea: PickProp finds the mesh");
  onceThenReused(1, 2, "PickProp(x, y)");
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(traced.Renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(W - 20, H - 10, W + 30, H + 5); // partly outside the viewport
  // Traced by the first capture, read again by a second while nothing
  // changes, traced again after a camera move (no render in between) and
  // after the mesh changes.
  const char* steps[5] = { "an area at the corner", "the same area again", "after a camera move",
    "after the mesh changed", "after the mesh changed and a frame rebuilt it" };
  for (int step = 0; step < 5; ++step)
  {
    if (step == 2)
    {
      traced.Renderer->GetActiveCamera()->Azimuth(5.0);
    }
    if (step >= 3)
    {
      // The mesh's cells change, its bounds and data object do not.
      auto* sphere = vtkSphereSource::SafeDownCast(traced.Actors[0]->GetMapper()->GetInputAlgorithm());
      sphere->SetThetaResolution(step == 3 ? 32 : 16);
    }
    if (step == 4)
    {
      traced.Window->Render();
    }
    vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(selector->Select());
    Check(result != nullptr, "TracedArea: the selection answers");
    onceThenReused(step == 1 ? 0 : 20 * 10, 3, steps[step]);
  }
  NoVTKOutput("traced area");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "Cells", TestCells }, { "Points", TestPoints }, { "Composite", TestComposite },
      { "PropPicking", TestPropPicking }, { "Accumulation", TestAccumulation }, { "TracedArea", TestTracedArea },
      { "HighCellIds", TestHighCellIds }, { "PointCells", TestPointCells },
      { "BadInput", TestBadInput } });
}
