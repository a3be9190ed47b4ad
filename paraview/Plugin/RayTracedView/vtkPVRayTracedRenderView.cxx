#include "vtkPVRayTracedRenderView.h"

#include "vtkActor.h"
#include "vtkBVHCellLocator.h"
#include "vtkCamera.h"
#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkGenericCell.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPVHardwareSelector.h"
#include "vtkPVSession.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRayTracePass.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace
{
/// vtkPVHardwareSelector's prop ids (the ones ParaView maps back to
/// representations) are behind a protected virtual; a member pointer named
/// through a derived class reaches it without instantiating anything.
struct PropIdAccess : public vtkPVHardwareSelector
{
  static int Get(vtkPVHardwareSelector* selector, vtkProp* prop)
  {
    return (selector->*(&PropIdAccess::GetPropID))(0, prop);
  }
};

/// One polygonal block a selection ray may hit.
struct Candidate
{
  int PropId = -1;
  int CompositeIndex = -1; ///< -1: the mapper's input is not composite
  vtkPolyData* Data = nullptr;
  vtkBVHCellLocator* Locator = nullptr;
  vtkSmartPointer<vtkMatrix4x4> WorldToLocal; ///< null: identity
  vtkDataArray* OriginalCellIds = nullptr;
  vtkDataArray* OriginalPointIds = nullptr;
  vtkDataArray* CompositeIds = nullptr;
  vtkDataArray* ProcessIds = nullptr;
};

double idAt(vtkDataArray* a, vtkIdType i, vtkIdType fallback)
{
  return a && i >= 0 && i < a->GetNumberOfTuples() ? a->GetTuple1(i) : static_cast<double>(fallback);
}
} // namespace

struct vtkPVRayTracedRenderView::Internals
{
  vtkNew<vtkRayTracePass> Pass;
  // The knob properties' values (never rendered with): the pass takes them
  // under the CUSTOM preset.
  vtkNew<vtkRayTracePass> Knobs;
  struct CachedLocator
  {
    vtkSmartPointer<vtkBVHCellLocator> Locator;
    vtkMTimeType DataTime = 0;
  };
  // Keyed by the block; the locator holds a reference to it, so a key stays
  // valid while it is cached. Entries not used by a selection are dropped.
  std::map<vtkPolyData*, CachedLocator> Locators;

  /// Adds a block to the candidates of a selection, with its locator (built
  /// when the block is new or modified). Returns 1 when a tree was built.
  int AddBlock(vtkPolyData* pd, Candidate c, std::map<vtkPolyData*, CachedLocator>& used,
    std::vector<Candidate>& candidates)
  {
    if (!pd || pd->GetNumberOfCells() == 0)
    {
      return 0;
    }
    int built = 0;
    CachedLocator& entry = used[pd];
    auto it = this->Locators.find(pd);
    if (it != this->Locators.end())
    {
      entry = it->second;
    }
    if (!entry.Locator || entry.DataTime != pd->GetMTime())
    {
      entry.Locator = vtkSmartPointer<vtkBVHCellLocator>::New();
      entry.Locator->SetDataSet(pd);
      entry.Locator->BuildLocator();
      entry.DataTime = pd->GetMTime();
      built = 1;
    }
    c.Data = pd;
    c.Locator = entry.Locator;
    candidates.push_back(c);
    return built;
  }
};

vtkStandardNewMacro(vtkPVRayTracedRenderView);

vtkPVRayTracedRenderView::vtkPVRayTracedRenderView()
  : Internal(new Internals)
{
  // Serial: the renderer's pass; parallel: the pass IceT's composite pass
  // runs on each rank's piece before compositing by depth.
  this->SynchronizedRenderers->SetRenderPass(this->Internal->Pass);
}

vtkPVRayTracedRenderView::~vtkPVRayTracedRenderView() = default;

void vtkPVRayTracedRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnableRayTracing: " << this->EnableRayTracing << "\n";
  os << indent << "QualityPreset: " << this->QualityPreset << "\n";
  os << indent << "LastSelectionRays: " << this->LastSelectionRays << "\n";
  os << indent << "LastSelectionLocatorBuilds: " << this->LastSelectionLocatorBuilds << "\n";
  os << indent << "RayTracePass:\n";
  this->Internal->Pass->PrintSelf(os, indent.GetNextIndent());
}

vtkRayTracePass* vtkPVRayTracedRenderView::GetRayTracePass()
{
  return this->Internal->Pass;
}

void vtkPVRayTracedRenderView::SetEnableRayTracing(bool enable)
{
  if (enable == this->EnableRayTracing)
  {
    return;
  }
  this->EnableRayTracing = enable;
  this->SynchronizedRenderers->SetRenderPass(enable ? this->Internal->Pass.GetPointer() : nullptr);
  this->Modified();
}

void vtkPVRayTracedRenderView::SetQualityPreset(int preset)
{
  if (preset != this->QualityPreset)
  {
    this->QualityPreset = preset;
    this->ApplyKnobs();
    this->Modified();
  }
}

void vtkPVRayTracedRenderView::ApplyKnobs()
{
  vtkRayTracePass* pass = this->Internal->Pass;
  vtkRayTracePass* knobs = this->Internal->Knobs;
  pass->SetSamplesPerPixel(knobs->GetSamplesPerPixel());
  pass->SetProgressiveAccumulation(knobs->GetProgressiveAccumulation());
  pass->SetShadows(knobs->GetShadows());
  pass->SetAmbientOcclusionSamples(knobs->GetAmbientOcclusionSamples());
  pass->SetAmbientOcclusionRadius(knobs->GetAmbientOcclusionRadius());
  pass->SetBuildQuality(knobs->GetBuildQuality());
  pass->SetMaximumTraversalSteps(knobs->GetMaximumTraversalSteps());
  pass->SetLeafSize(knobs->GetLeafSize());
  pass->SetPrecisionMode(knobs->GetPrecisionMode());
  pass->SetTraceTranslucency(knobs->GetTraceTranslucency());
  pass->SetQualityPreset(this->QualityPreset);
}

#define vtkrtForwardKnob(Name, Type)                                                                \
  void vtkPVRayTracedRenderView::Set##Name(Type value)                                              \
  {                                                                                                 \
    if (this->Internal->Knobs->Get##Name() != value)                                                \
    {                                                                                               \
      this->Internal->Knobs->Set##Name(value);                                                      \
      this->ApplyKnobs();                                                                           \
      this->Modified();                                                                             \
    }                                                                                               \
  }                                                                                                 \
  Type vtkPVRayTracedRenderView::Get##Name() { return this->Internal->Knobs->Get##Name(); }

vtkrtForwardKnob(SamplesPerPixel, int);
vtkrtForwardKnob(ProgressiveAccumulation, bool);
vtkrtForwardKnob(Shadows, bool);
vtkrtForwardKnob(AmbientOcclusionSamples, int);
vtkrtForwardKnob(AmbientOcclusionRadius, double);
vtkrtForwardKnob(BuildQuality, int);
vtkrtForwardKnob(MaximumTraversalSteps, int);
vtkrtForwardKnob(LeafSize, int);
vtkrtForwardKnob(PrecisionMode, int);
vtkrtForwardKnob(TraceTranslucency, bool);
#undef vtkrtForwardKnob

vtkTypeInt64 vtkPVRayTracedRenderView::GetLastTracedPrimitives()
{
  return this->EnableRayTracing ? this->Internal->Pass->GetLastTracedPrimitives() : 0;
}

int vtkPVRayTracedRenderView::GetLastTracedInstances()
{
  return this->EnableRayTracing ? this->Internal->Pass->GetLastTracedInstances() : 0;
}

int vtkPVRayTracedRenderView::GetNumberOfBackgroundBuilds()
{
  return this->Internal->Pass->GetNumberOfBackgroundBuilds();
}

vtkIdType vtkPVRayTracedRenderView::GetNumberOfBackgroundBuildsTaken()
{
  return this->Internal->Pass->GetNumberOfBackgroundBuildsTaken();
}

void vtkPVRayTracedRenderView::SetBackgroundBuildThreshold(vtkIdType triangles)
{
  if (triangles != this->Internal->Pass->GetBackgroundBuildThreshold())
  {
    this->Internal->Pass->SetBackgroundBuildThreshold(triangles);
    this->Modified();
  }
}

vtkIdType vtkPVRayTracedRenderView::GetBackgroundBuildThreshold()
{
  return this->Internal->Pass->GetBackgroundBuildThreshold();
}

void vtkPVRayTracedRenderView::SelectCells(int region[4], const char* array)
{
  if (!this->EnableRayTracing)
  {
    this->Superclass::SelectCells(region, array);
    return;
  }
  this->SelectWithLocator(vtkDataObject::FIELD_ASSOCIATION_CELLS, region, array);
}

void vtkPVRayTracedRenderView::SelectPoints(int region[4], const char* array)
{
  if (!this->EnableRayTracing)
  {
    this->Superclass::SelectPoints(region, array);
    return;
  }
  this->SelectWithLocator(vtkDataObject::FIELD_ASSOCIATION_POINTS, region, array);
}

void vtkPVRayTracedRenderView::SelectPolygonPoints(int* polygon2DArray, vtkIdType arrayLen)
{
  this->SynchronizedRenderers->SetRenderPass(nullptr);
  this->Superclass::SelectPolygonPoints(polygon2DArray, arrayLen);
  this->SynchronizedRenderers->SetRenderPass(
    this->EnableRayTracing ? this->Internal->Pass.GetPointer() : nullptr);
}

void vtkPVRayTracedRenderView::SelectPolygonCells(int* polygon2DArray, vtkIdType arrayLen)
{
  this->SynchronizedRenderers->SetRenderPass(nullptr);
  this->Superclass::SelectPolygonCells(polygon2DArray, arrayLen);
  this->SynchronizedRenderers->SetRenderPass(
    this->EnableRayTracing ? this->Internal->Pass.GetPointer() : nullptr);
}

void vtkPVRayTracedRenderView::SelectWithLocator(
  int fieldAssociation, int region[4], const char* array)
{
  // Renders (full resolution), sets up the selector and saves what PostSelect
  // restores.
  if (!this->PrepareSelect(fieldAssociation, array))
  {
    return;
  }
  const bool cells = fieldAssociation == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkRenderer* ren = this->GetRenderer();
  this->LastSelectionRays = 0;
  this->LastSelectionLocatorBuilds = 0;

  // The blocks rays may hit: visible, pickable actors ParaView registered
  // for selection (representations' actors; not widgets or annotations).
  std::vector<Candidate> candidates;
  std::map<vtkPolyData*, Internals::CachedLocator> used;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor || !actor->GetVisibility() || !actor->GetPickable() || !actor->GetMapper())
    {
      continue;
    }
    // Rays meet surfaces: props drawn as points or wireframe are not
    // selectable in this view.
    if (actor->GetProperty()->GetRepresentation() != VTK_SURFACE)
    {
      continue;
    }
    const int propId = PropIdAccess::Get(this->Selector, prop);
    if (propId < 0)
    {
      continue;
    }
    vtkMapper* mapper = actor->GetMapper();
    vtkOpenGLPolyDataMapper* glMapper = vtkOpenGLPolyDataMapper::SafeDownCast(mapper);
    Candidate proto;
    proto.PropId = propId;
    if (!actor->GetIsIdentity())
    {
      proto.WorldToLocal = vtkSmartPointer<vtkMatrix4x4>::New();
      vtkMatrix4x4::Invert(actor->GetMatrix(), proto.WorldToLocal);
    }
    // The id arrays the hardware selector would read (ParaView names them on
    // the mapper: original cell/point ids, composite index, process id).
    auto withIdArrays = [glMapper](Candidate c, vtkPolyData* pd) {
      const char* cellIds = glMapper && glMapper->GetCellIdArrayName()
        ? glMapper->GetCellIdArrayName()
        : "vtkOriginalCellIds";
      const char* pointIds = glMapper && glMapper->GetPointIdArrayName()
        ? glMapper->GetPointIdArrayName()
        : "vtkOriginalPointIds";
      c.OriginalCellIds = pd->GetCellData()->GetArray(cellIds);
      c.OriginalPointIds = pd->GetPointData()->GetArray(pointIds);
      if (glMapper && glMapper->GetCompositeIdArrayName())
      {
        c.CompositeIds = pd->GetCellData()->GetArray(glMapper->GetCompositeIdArrayName());
      }
      if (glMapper && glMapper->GetProcessIdArrayName())
      {
        c.ProcessIds = pd->GetPointData()->GetArray(glMapper->GetProcessIdArrayName());
      }
      return c;
    };
    vtkDataObject* input = mapper->GetInputDataObject(0, 0);
    if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
    {
      vtkSmartPointer<vtkCompositeDataIterator> iter;
      iter.TakeReference(composite->NewIterator());
      for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
      {
        if (vtkPolyData* pd = vtkPolyData::SafeDownCast(iter->GetCurrentDataObject()))
        {
          Candidate c = withIdArrays(proto, pd);
          c.CompositeIndex = static_cast<int>(iter->GetCurrentFlatIndex());
          this->LastSelectionLocatorBuilds += this->Internal->AddBlock(pd, c, used, candidates);
        }
      }
    }
    else if (vtkPolyData* pd = vtkPolyData::SafeDownCast(input))
    {
      this->LastSelectionLocatorBuilds +=
        this->Internal->AddBlock(pd, withIdArrays(proto, pd), used, candidates);
    }
  }
  this->Internal->Locators.swap(used);

  // One ray per pixel of the region through the pixel's center, as the
  // tracer casts it: display -> view (NDC) by VTK, view -> world by the
  // inverse of the camera's composite projection, once.
  const int x0 = std::min(region[0], region[2]), x1 = std::max(region[0], region[2]);
  const int y0 = std::min(region[1], region[3]), y1 = std::max(region[1], region[3]);
  const vtkIdType width = x1 - x0 + 1;
  const vtkIdType pixels = width * (y1 - y0 + 1);
  vtkNew<vtkMatrix4x4> viewToWorld;
  viewToWorld->DeepCopy(ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1.0, 1.0));
  viewToWorld->Invert();
  double eye[3];
  ren->GetActiveCamera()->GetPosition(eye);
  std::vector<double> nearest(pixels, std::numeric_limits<double>::infinity());
  struct Hit
  {
    int Candidate = -1;
    vtkIdType CellId = -1;
    double Local[3] = { 0, 0, 0 };
  };
  std::vector<Hit> hits(pixels);
  vtkNew<vtkGenericCell> cell;
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      ren->SetDisplayPoint(x + 0.5, y + 0.5, 0.0);
      ren->DisplayToView();
      double view[3];
      ren->GetViewPoint(view);
      double ends[2][4];
      for (int e = 0; e < 2; ++e)
      {
        const double v[4] = { view[0], view[1], e == 0 ? -1.0 : 1.0, 1.0 };
        viewToWorld->MultiplyPoint(v, ends[e]);
        for (int k = 0; k < 3; ++k)
        {
          ends[e][k] /= ends[e][3];
        }
        ends[e][3] = 1.0;
      }
      // Hits are ranked by their distance from the eye along the ray (the
      // segment's ends depend on the clipping range, which need not be the
      // same on every rank).
      const double length = std::sqrt(vtkMath::Distance2BetweenPoints(ends[0], ends[1]));
      double direction[3] = { ends[1][0] - ends[0][0], ends[1][1] - ends[0][1],
        ends[1][2] - ends[0][2] };
      vtkMath::Normalize(direction);
      double toNear[3];
      vtkMath::Subtract(ends[0], eye, toNear);
      const double nearDistance = vtkMath::Dot(toNear, direction);
      const vtkIdType pixel = (y - y0) * width + (x - x0);
      ++this->LastSelectionRays;
      for (std::size_t c = 0; c < candidates.size(); ++c)
      {
        const Candidate& cand = candidates[c];
        double a[4], b[4];
        if (cand.WorldToLocal)
        {
          cand.WorldToLocal->MultiplyPoint(ends[0], a);
          cand.WorldToLocal->MultiplyPoint(ends[1], b);
          for (int k = 0; k < 3; ++k)
          {
            a[k] /= a[3];
            b[k] /= b[3];
          }
        }
        else
        {
          std::copy(ends[0], ends[0] + 3, a);
          std::copy(ends[1], ends[1] + 3, b);
        }
        // t is the same along the world and the (affinely) transformed
        // segment, so hits of different blocks compare by it.
        double t = 0.0, hitPoint[3], pcoords[3];
        int subId = 0;
        vtkIdType cellId = -1;
        if (!cand.Locator->IntersectWithLine(a, b, 0.0, t, hitPoint, pcoords, subId, cellId, cell))
        {
          continue;
        }
        const double distance = nearDistance + t * length;
        if (distance < nearest[pixel])
        {
          nearest[pixel] = distance;
          hits[pixel].Candidate = static_cast<int>(c);
          hits[pixel].CellId = cellId;
          std::copy(hitPoint, hitPoint + 3, hits[pixel].Local);
        }
      }
    }
  }

  // Several rendering processes: the nearest hit per pixel over all ranks
  // wins (ties: the lowest rank); the driver (rank 0) makes the selection.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool distributed = this->GetUseDistributedRenderingForRender() && controller &&
    controller->GetNumberOfProcesses() > 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  std::vector<int> owner(pixels, rank);
  if (distributed)
  {
    std::vector<double> global(pixels);
    controller->AllReduce(nearest.data(), global.data(), pixels, vtkCommunicator::MIN_OP);
    std::vector<int> mine(pixels);
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      mine[p] = std::isfinite(nearest[p]) && nearest[p] == global[p] ? rank : VTK_INT_MAX;
    }
    controller->AllReduce(mine.data(), owner.data(), pixels, vtkCommunicator::MIN_OP);
  }

  // (process, prop, composite index, id) of each pixel this rank owns.
  vtkNew<vtkIdTypeArray> records;
  records->SetNumberOfComponents(4);
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    const Hit& h = hits[p];
    if (h.Candidate < 0 || owner[p] != rank)
    {
      continue;
    }
    const Candidate& cand = candidates[h.Candidate];
    vtkIdType id = h.CellId;
    vtkIdType originalId;
    if (cells)
    {
      originalId = static_cast<vtkIdType>(idAt(cand.OriginalCellIds, id, id));
    }
    else
    {
      // The hit cell's point nearest the hit.
      vtkCell* hitCell = cand.Data->GetCell(id);
      double best = VTK_DOUBLE_MAX;
      vtkIdType pointId = -1;
      for (vtkIdType k = 0; k < hitCell->GetNumberOfPoints(); ++k)
      {
        double q[3];
        cand.Data->GetPoint(hitCell->GetPointId(k), q);
        const double d2 = vtkMath::Distance2BetweenPoints(q, h.Local);
        if (d2 < best)
        {
          best = d2;
          pointId = hitCell->GetPointId(k);
        }
      }
      id = pointId;
      originalId = static_cast<vtkIdType>(idAt(cand.OriginalPointIds, id, id));
    }
    // Geometry gathered for local rendering carries the rank that owns each
    // point (ParaView's vtkProcessId point array); a cell is its first point's.
    const vtkIdType processPoint = cells ? cand.Data->GetCell(h.CellId)->GetPointId(0) : id;
    const vtkIdType process = cand.ProcessIds
      ? static_cast<vtkIdType>(idAt(cand.ProcessIds, processPoint, rank))
      : rank;
    const vtkIdType compositeIndex = cand.CompositeIds
      ? static_cast<vtkIdType>(idAt(cand.CompositeIds, h.CellId, cand.CompositeIndex))
      : cand.CompositeIndex;
    const vtkIdType record[4] = { process, cand.PropId, compositeIndex, originalId };
    records->InsertNextTypedTuple(record);
  }
  vtkNew<vtkIdTypeArray> all;
  all->SetNumberOfComponents(4);
  if (distributed)
  {
    controller->GatherV(records, all, 0);
  }
  else
  {
    all->DeepCopy(records);
  }

  // Client/server with rendering on the server: ParaView fetches the
  // selection from the client's view, which holds no geometry, so the
  // server's root sends its records there.
  vtkPVSession* session = this->GetSession();
  const bool remoteRendering = this->GetUseDistributedRenderingForRender();
  vtkMultiProcessController* toClient =
    session && remoteRendering && rank == 0 ? session->GetController(vtkPVSession::CLIENT) : nullptr;
  vtkMultiProcessController* toServer = session && remoteRendering
    ? session->GetController(vtkPVSession::RENDER_SERVER_ROOT)
    : nullptr;
  constexpr int recordsTag = 0x7274;
  if (toClient)
  {
    vtkIdType count = all->GetNumberOfValues();
    toClient->Send(&count, 1, 1, recordsTag);
    if (count > 0)
    {
      toClient->Send(all->GetPointer(0), count, 1, recordsTag + 1);
    }
  }
  else if (toServer)
  {
    vtkIdType count = 0;
    toServer->Receive(&count, 1, 1, recordsTag);
    all->SetNumberOfValues(count);
    if (count > 0)
    {
      toServer->Receive(all->GetPointer(0), count, 1, recordsTag + 1);
    }
  }

  vtkSmartPointer<vtkSelection> selection;
  if (!distributed || rank == 0)
  {
    // One node per (process, prop, block), ids sorted and unique; the pixel
    // count is what ParaView's selection processing expects of a node.
    std::map<std::tuple<vtkIdType, vtkIdType, vtkIdType>, std::pair<std::set<vtkIdType>, int>> nodes;
    for (vtkIdType r = 0; r < all->GetNumberOfTuples(); ++r)
    {
      vtkIdType rec[4];
      all->GetTypedTuple(r, rec);
      auto& node = nodes[std::make_tuple(rec[0], rec[1], rec[2])];
      node.first.insert(rec[3]);
      ++node.second;
    }
    selection = vtkSmartPointer<vtkSelection>::New();
    for (const auto& n : nodes)
    {
      vtkNew<vtkSelectionNode> node;
      node->SetContentType(vtkSelectionNode::INDICES);
      node->SetFieldType(cells ? vtkSelectionNode::CELL : vtkSelectionNode::POINT);
      vtkInformation* info = node->GetProperties();
      info->Set(vtkSelectionNode::PROCESS_ID(), static_cast<int>(std::get<0>(n.first)));
      info->Set(vtkSelectionNode::PROP_ID(), static_cast<int>(std::get<1>(n.first)));
      if (std::get<2>(n.first) >= 0)
      {
        info->Set(vtkSelectionNode::COMPOSITE_INDEX(), static_cast<int>(std::get<2>(n.first)));
      }
      info->Set(vtkSelectionNode::PIXEL_COUNT(), n.second.second);
      vtkNew<vtkIdTypeArray> ids;
      ids->SetName("SelectedIds");
      for (vtkIdType id : n.second.first)
      {
        ids->InsertNextValue(id);
      }
      node->SetSelectionList(ids);
      selection->AddNode(node);
    }
  }
  this->PostSelect(selection, array);
}
