// A mapper's id arrays with the pass on: vtkHardwareSelector reports the
// cell ids and composite indices the arrays a mapper names give, as with
// raster (the selection of the same scene rasterized is the reference);
// unpickable blocks are looked through.
#include "vtkrtPassTestUtils.h"

#include "vtkActor.h"
#include "vtkCellData.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataObject.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropPicker.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkUnsignedIntArray.h"

#include <algorithm>
#include <functional>
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

/// The composite index NumberedPlane(.., base) gives its cell i: three
/// values a plane, apart for the planes the tests use.
unsigned int GroupOf(vtkIdType base, vtkIdType i)
{
  return static_cast<unsigned int>((base / 100) % 1000 + 2 + i % 3);
}

/// A plane of `nx` x `ny` quads whose cell array "original" holds
/// base + 7 i for cell i (a filter's map back to the cells of its input),
/// and "group" GroupOf(base, i) (a composite index per cell, as data
/// appended from several blocks carries).
vtkSmartPointer<vtkPolyData> NumberedPlane(double x0, int nx, int ny, vtkIdType base)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(x0, -1.0, 0.0);
  plane->SetPoint1(x0 + 1.8, -1.0, 0.0);
  plane->SetPoint2(x0, 1.0, 0.0);
  plane->SetResolution(nx, ny);
  plane->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(plane->GetOutput());
  vtkNew<vtkIdTypeArray> original;
  original->SetName("original");
  for (vtkIdType i = 0; i < poly->GetNumberOfCells(); ++i)
  {
    original->InsertNextValue(base + 7 * i);
  }
  poly->GetCellData()->AddArray(original);
  vtkNew<vtkUnsignedIntArray> group;
  group->SetName("group");
  for (vtkIdType i = 0; i < poly->GetNumberOfCells(); ++i)
  {
    group->InsertNextValue(GroupOf(base, i));
  }
  poly->GetCellData()->AddArray(group);
  return poly;
}

/// Every (composite index, id) a cell selection of the whole window reports.
std::set<std::pair<unsigned int, vtkIdType>> CompositeCells(vtkRenderer* ren)
{
  vtkNew<vtkHardwareSelector> sel;
  sel->SetRenderer(ren);
  sel->SetArea(0, 0, W - 1, H - 1);
  sel->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(sel->Select());
  std::set<std::pair<unsigned int, vtkIdType>> cells;
  for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = result->GetNode(n);
    vtkInformation* p = node->GetProperties();
    const unsigned int composite = p->Has(vtkSelectionNode::COMPOSITE_INDEX())
      ? static_cast<unsigned int>(p->Get(vtkSelectionNode::COMPOSITE_INDEX()))
      : 0u;
    vtkIdTypeArray* list = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    for (vtkIdType k = 0; list && k < list->GetNumberOfTuples(); ++k)
    {
      cells.insert({ composite, list->GetValue(k) });
    }
  }
  return cells;
}

/// A mapper of `input` (a composite mapper for blocks) naming the planes'
/// "original" array as its cell ids and their "group" array as its
/// composite ids, as asked.
vtkSmartPointer<vtkMapper> MapperNaming(vtkDataObject* input, bool cellIds, bool compositeIds)
{
  vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
  if (vtkPolyData::SafeDownCast(input))
  {
    mapper = vtkSmartPointer<vtkOpenGLPolyDataMapper>::New();
  }
  else
  {
    mapper = vtkSmartPointer<vtkCompositePolyDataMapper2>::New();
  }
  mapper->SetInputDataObject(input);
  mapper->SetCellIdArrayName(cellIds ? "original" : nullptr);
  mapper->SetCompositeIdArrayName(compositeIds ? "group" : nullptr);
  return mapper;
}

/// A mapper's CellIdArrayName (ParaView's vtkOriginalCellIds) maps the
/// selected cells through that array, and its CompositeIdArrayName gives
/// each selected cell its composite index, as raster does: a polydata
/// mapper, a composite mapper whose blocks have arrays of their own, ids
/// past 2^24 (the selector's high passes), both arrays at once.
void TestRemappedIds()
{
  struct Case
  {
    std::string Label;
    std::vector<vtkIdType> Bases; ///< of the planes' arrays
    bool CellIds;                 ///< the mapper names "original"
    bool CompositeIds;            ///< the mapper names "group"
    std::function<vtkSmartPointer<vtkDataObject>()> Input;
  };
  const vtkIdType high = (vtkIdType(1) << 24) + 3;
  auto plane = [](int nx, int ny, vtkIdType base) {
    return [=]() -> vtkSmartPointer<vtkDataObject> { return NumberedPlane(-0.9, nx, ny, base); };
  };
  auto blocks = []() -> vtkSmartPointer<vtkDataObject> {
    auto two = vtkSmartPointer<vtkMultiBlockDataSet>::New();
    two->SetBlock(0, NumberedPlane(-2.0, 5, 4, 500));
    two->SetBlock(2, NumberedPlane(0.2, 7, 3, 90000));
    return two;
  };
  const Case cases[] = {
    { "a polydata mapper", { 1000 }, true, false, plane(8, 6, 1000) },
    { "a composite mapper", { 500, 90000 }, true, false, blocks },
    { "ids past 2^24", { high }, true, false, plane(6, 5, high) },
    { "a composite id array", { 1000 }, false, true, plane(8, 6, 1000) },
    { "composite and cell id arrays of blocks", { 500, 90000 }, true, true, blocks },
  };
  for (const Case& c : cases)
  {
    std::set<std::pair<unsigned int, vtkIdType>> cells[2];
    for (const bool traced : { false, true })
    {
      auto win = MakeWindow(W, H);
      vtkNew<vtkRenderer> ren;
      win->AddRenderer(ren);
      vtkNew<vtkActor> actor;
      actor->SetMapper(MapperNaming(c.Input(), c.CellIds, c.CompositeIds));
      ren->AddActor(actor);
      ren->ResetCamera();
      vtkNew<vtkRayTracePass> pass;
      if (traced)
      {
        ren->SetPass(pass);
      }
      win->Render();
      Check(!traced || pass->GetNumberOfTracedProps() == 1, c.Label + ": traced");
      cells[traced] = CompositeCells(ren);
    }
    // Each traced cell's id and composite index come from the arrays the
    // mapper names (a block's own), so the planes' numbering shows in them.
    std::size_t mapped = 0;
    for (const auto& cell : cells[1])
    {
      mapped += std::any_of(c.Bases.begin(), c.Bases.end(), [&c, &cell](vtkIdType b) {
        const vtkIdType i = c.CellIds ? (cell.second - b) / 7 : cell.second;
        return (!c.CellIds || (cell.second >= b && (cell.second - b) % 7 == 0)) &&
          (!c.CompositeIds || cell.first == GroupOf(b, i));
      });
    }
    std::ostringstream s;
    s << c.Label << ": raster / traced select " << cells[0].size() << " / " << cells[1].size()
      << " cells, " << mapped << " traced ones from the array";
    Check(!cells[0].empty() && cells[0] == cells[1] && mapped == cells[1].size(), s.str());
  }
  NoVTKOutput("remapped ids");
}

/// Block pickability (vtkCompositeDataDisplayAttributes): a selection and
/// vtkPropPicker look through an unpickable block, and an unpickable root
/// hides the whole composite from them, as with raster; a plane behind
/// the blocks is what they find there.
void TestBlockPickability()
{
  for (const int unpickable : { -1, 1, 0 }) // none, the second plane, the root
  {
    std::set<std::pair<unsigned int, vtkIdType>> cells[2];
    vtkProp* picked[2] = { nullptr, nullptr };
    vtkNew<vtkActor> back, blocksActor;
    for (const bool traced : { false, true })
    {
      auto win = MakeWindow(W, H);
      vtkNew<vtkRenderer> ren;
      win->AddRenderer(ren);
      auto two = vtkSmartPointer<vtkMultiBlockDataSet>::New();
      two->SetBlock(0, NumberedPlane(-2.0, 5, 4, 500));
      two->SetBlock(1, NumberedPlane(0.2, 7, 3, 90000));
      vtkNew<vtkCompositePolyDataMapper2> mapper;
      mapper->SetInputDataObject(two);
      vtkNew<vtkCompositeDataDisplayAttributes> attributes;
      mapper->SetCompositeDataDisplayAttributes(attributes);
      if (unpickable >= 0)
      {
        attributes->SetBlockPickability(unpickable == 0 ? two.Get() : two->GetBlock(1), false);
      }
      blocksActor->SetMapper(mapper);
      ren->AddActor(blocksActor);
      vtkNew<vtkPlaneSource> behind;
      behind->SetOrigin(-2.5, -1.5, -0.5);
      behind->SetPoint1(2.5, -1.5, -0.5);
      behind->SetPoint2(-2.5, 1.5, -0.5);
      behind->SetResolution(4, 4);
      vtkNew<vtkPolyDataMapper> backMapper;
      backMapper->SetInputConnection(behind->GetOutputPort());
      back->SetMapper(backMapper);
      ren->AddActor(back);
      ren->ResetCamera();
      vtkNew<vtkRayTracePass> pass;
      if (traced)
      {
        ren->SetPass(pass);
      }
      win->Render();
      Check(!traced || pass->GetNumberOfTracedProps() == 2, "block pickability: traced");
      cells[traced] = CompositeCells(ren);
      // The second plane's middle, in front of the plane behind.
      double x[3] = { 1.1, 0.0, 0.0 };
      ren->SetWorldPoint(x[0], x[1], x[2], 1.0);
      ren->WorldToDisplay();
      double* d = ren->GetDisplayPoint();
      vtkNew<vtkPropPicker> picker;
      picker->Pick(d[0], d[1], 0.0, ren);
      picked[traced] = picker->GetViewProp();
    }
    std::ostringstream s;
    s << (unpickable < 0 ? "all pickable" : unpickable ? "the second plane unpickable" : "the root unpickable")
      << ": raster / traced select " << cells[0].size() << " / "
      << cells[1].size() << " cells; vtkPropPicker over the second plane picks "
      << (picked[1] == back.Get() ? "the plane behind" : picked[1] ? "the blocks" : "nothing");
    vtkProp* want = unpickable < 0 ? static_cast<vtkProp*>(blocksActor) : back.Get();
    Check(!cells[0].empty() && cells[0] == cells[1] && picked[0] == want && picked[1] == want, s.str());
  }
  NoVTKOutput("block pickability");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "RemappedIds", TestRemappedIds }, { "BlockPickability", TestBlockPickability } });
}
