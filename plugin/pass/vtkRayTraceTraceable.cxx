#include "vtkRayTraceScene.h"

#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCommand.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkDataSetMapper.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLODProp3D.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkPropAssembly.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSkybox.h"

#include <algorithm>
#include <unordered_set>

namespace vtkrt
{
namespace pass
{

namespace
{
/// The shader code a vtkOpenGLPolyDataMapper was given through VTK 9.0's
/// deprecated mapper API (AddShaderReplacement, SetFragmentShaderCode ...):
/// read through a pointer to the protected member, as its getter would
/// create one; null where VTK has no such member (ParaView 5.11's).
struct LegacyShaderPropertyOf : vtkOpenGLPolyDataMapper
{
  template <class P>
  static auto Read(vtkOpenGLPolyDataMapper* mapper, P*, int)
    -> decltype((mapper->*(&P::LegacyShaderProperty)).GetPointer())
  {
    return (mapper->*(&P::LegacyShaderProperty)).GetPointer();
  }
  template <class P>
  static vtkShaderProperty* Read(vtkOpenGLPolyDataMapper*, P*, long)
  {
    return nullptr;
  }
  static vtkShaderProperty* Get(vtkOpenGLPolyDataMapper* mapper)
  {
    return Read<LegacyShaderPropertyOf>(mapper, nullptr, 0);
  }
};

/// Whether raster runs shader code of the application's for the actor,
/// which the tracer cannot run.
bool hasCustomShaders(vtkActor* actor, vtkMapper* mapper)
{
  auto custom = [](vtkShaderProperty* p) {
    return p &&
      (p->HasVertexShaderCode() || p->HasFragmentShaderCode() || p->HasGeometryShaderCode() ||
        p->GetNumberOfShaderReplacements() > 0);
  };
  auto* gl = vtkOpenGLPolyDataMapper::SafeDownCast(mapper);
  return custom(actor->GetShaderProperty()) || (gl && custom(LegacyShaderPropertyOf::Get(gl)));
}

/// Whether the application sets uniforms of raster's program for the
/// mapper (an UpdateShaderEvent observer, e.g. a color of its own).
bool hasShaderObservers(vtkMapper* mapper)
{
  return mapper->HasObserver(vtkCommand::UpdateShaderEvent) != 0;
}

/// Whether raster draws more than the cells' surfaces over them: a
/// selection handed to the mapper (VTK draws the selected cells' or points'
/// outlines in the property's selection color) or vertices (VTK draws them,
/// in the vertex color, beside the edges of a surface with edges).
bool drawsHighlights(vtkActor* actor, vtkMapper* mapper)
{
  vtkProperty* property = actor->GetProperty();
  return (mapper->GetSelection() && mapper->GetSelection()->GetNumberOfNodes() > 0) ||
    (property->GetVertexVisibility() && property->GetEdgeVisibility() &&
      property->GetRepresentation() == VTK_SURFACE);
}

/// Whether a prop's matrix is affine (last row 0 0 0 1): raster divides by
/// w after a projective one (a planar shadow's flattening), the tracer's
/// instance transforms are affine.
bool IsAffine(vtkMatrix4x4* m)
{
  return m->GetElement(3, 0) == 0.0 && m->GetElement(3, 1) == 0.0 && m->GetElement(3, 2) == 0.0 &&
    m->GetElement(3, 3) == 1.0;
}

/// Mappers that draw something other than their data's cells: VTK's point
/// splats, its molecule mapper's sphere and stick impostors and ParaView's
/// surface LIC.
bool drawsOtherThanCells(vtkMapper* mapper)
{
  return mapper->IsA("vtkPointGaussianMapper") || mapper->IsA("vtkOpenGLSphereMapper") ||
    mapper->IsA("vtkOpenGLStickMapper") || mapper->IsA("vtkSurfaceLICMapper") ||
    mapper->IsA("vtkCompositeSurfaceLICMapper");
}

/// VTK blends every fragment, so an actor forced opaque whose colors are
/// not opaque is blended over what raster drew before it, in its opaque
/// pass; the tracer would draw it opaque.
bool forcedOpaqueButTranslucent(vtkActor* actor, vtkMapper* mapper)
{
  return actor->GetForceOpaque() &&
    (actor->GetProperty()->GetOpacity() < 1.0 || mapper->HasTranslucentPolygonalGeometry());
}
} // namespace

namespace
{
/// The level a vtkLODProp3D draws (chosen in its SetAllocatedRenderTime,
/// which the renderer calls before the pass): VTK 9.1 keeps it protected.
struct SelectedLevel : vtkLODProp3D
{
  static vtkProp3D* Of(vtkLODProp3D* lod)
  {
    const int index = lod->*(&SelectedLevel::SelectedLODIndex);
    const int entries = lod->*(&SelectedLevel::NumberOfEntries);
    vtkLODProp3DEntry* levels = lod->*(&SelectedLevel::LODs);
    return levels && index >= 0 && index < entries && levels[index].ID >= 0 ? levels[index].Prop3D
                                                                          : nullptr;
  }
};
} // namespace

bool PartsOf(vtkProp* prop, std::vector<PropPart>& parts)
{
  parts.clear();
  if (auto* actor = vtkActor::SafeDownCast(prop))
  {
    parts.push_back({ prop, 0, actor, nullptr });
    return true;
  }
  if (auto* lod = vtkLODProp3D::SafeDownCast(prop))
  {
    // Its level under its matrix, as it pushes that matrix into the level
    // (chosen by hand, or by the render times the pass reports).
    auto* level = vtkActor::SafeDownCast(SelectedLevel::Of(lod));
    if (level && level->GetMapper())
    {
      parts.push_back({ prop, 0, level, lod->GetMatrix() });
    }
    return level != nullptr;
  }
  if (auto* group = vtkPropAssembly::SafeDownCast(prop))
  {
    // vtkPropAssembly::RenderOpaqueGeometry's walk: each visible part as it
    // draws itself (an actor with a mapper, an assembly). A LOD prop among
    // them chooses its level when the group renders (the renderer gives
    // the group its time, the group its parts): the group goes to raster.
    vtkCollectionSimpleIterator it;
    vtkPropCollection* children = group->GetParts();
    std::vector<PropPart> inner;
    for (children->InitTraversal(it); vtkProp* child = children->GetNextProp(it);)
    {
      auto* actor = vtkActor::SafeDownCast(child);
      if (!child->GetVisibility() || (actor && !actor->GetMapper()))
      {
        continue;
      }
      if (vtkLODProp3D::SafeDownCast(child) || !PartsOf(child, inner))
      {
        parts.clear();
        return false;
      }
      for (PropPart& part : inner)
      {
        parts.push_back({ prop, static_cast<int>(parts.size()), part.Actor, part.Matrix });
      }
    }
    return true;
  }
  auto* assembly = vtkAssembly::SafeDownCast(prop);
  if (!assembly)
  {
    return false;
  }
  // vtkAssembly::RenderOpaqueGeometry's walk: the leaves of its paths, each
  // drawn under its path's matrix when visible.
  assembly->InitPathTraversal();
  while (vtkAssemblyPath* path = assembly->GetNextPath())
  {
    vtkAssemblyNode* leaf = path->GetLastNode();
    vtkProp* part = leaf->GetViewProp();
    if (!part->GetVisibility())
    {
      continue;
    }
    auto* actor = vtkActor::SafeDownCast(part);
    if (!actor)
    {
      parts.clear();
      return false;
    }
    // An actor without a mapper draws nothing (vtkActor::RenderOpaqueGeometry).
    if (actor->GetMapper())
    {
      parts.push_back({ prop, static_cast<int>(parts.size()), actor, leaf->GetMatrix() });
    }
  }
  return true;
}

bool Scene::IsTraceable(vtkProp* prop, const TraceRules& rules)
{
  std::vector<PropPart> parts;
  return TraceableParts(prop, rules, parts);
}

bool Scene::TraceableParts(vtkProp* prop, const TraceRules& rules, std::vector<PropPart>& parts)
{
  // Hidden line removal: raster's pass for it hides wires behind every
  // wireframe's surfaces, which the tracer does not model; it takes lone
  // actors only (an assembly's wireframe parts draw plainly). An assembly
  // is traced whole or left to raster whole, as its selection reports one
  // prop.
  auto* lone = vtkActor::SafeDownCast(prop);
  if (rules.HiddenLineRemoval && !rules.Kept && lone &&
    lone->GetProperty()->GetRepresentation() == VTK_WIREFRAME)
  {
    return false;
  }
  return prop && (prop->GetVisibility() || rules.Kept) && PartsOf(prop, parts) && !parts.empty() &&
    std::all_of(parts.begin(), parts.end(), [&rules](const PropPart& part) {
      return IsTraceableActor(part.Actor, rules) &&
        (rules.Kept || IsAffine(part.Matrix ? part.Matrix.Get() : part.Actor->GetMatrix()));
    });
}

bool Scene::IsTraceableActor(vtkActor* actor, const TraceRules& rules)
{
  // A skybox is the environment drawn behind the scene, not its data.
  if ((!actor->GetVisibility() && !rules.Kept) || !actor->GetMapper() || vtkSkybox::SafeDownCast(actor))
  {
    return false;
  }
  vtkMapper* mapper = actor->GetMapper();
  const bool glyphs = vtkGlyph3DMapper::SafeDownCast(mapper) != nullptr;
  const bool dataSetMapper = vtkDataSetMapper::SafeDownCast(mapper) != nullptr;
  if (!glyphs && !dataSetMapper && !vtkPolyDataMapper::SafeDownCast(mapper) &&
    !vtkCompositePolyDataMapper::SafeDownCast(mapper))
  {
    return false;
  }
  // A vtkDataSetMapper without input: raster reports it (kept or not).
  if (dataSetMapper && mapper->GetNumberOfInputConnections(0) == 0)
  {
    return false;
  }
  if (rules.Kept)
  {
    return true;
  }
  if (drawsOtherThanCells(mapper) || hasCustomShaders(actor, mapper) || hasShaderObservers(mapper) ||
    drawsHighlights(actor, mapper) || forcedOpaqueButTranslucent(actor, mapper))
  {
    return false;
  }
  vtkProperty* property = actor->GetProperty();
  const int representation = property->GetRepresentation();
  // Edges and wires of glyphs stay with raster (and of polygons drawn as
  // tubes, VTK's shaded fake tubes: decided with the data, in
  // hasUntraceableCells).
  const bool edges = property->GetEdgeVisibility() || representation == VTK_WIREFRAME;
  if (property->GetInterpolation() == VTK_PBR || (edges && glyphs))
  {
    return false;
  }
  // Translucent: polygonal surfaces without edges. Not glyphs (raster's
  // glyph mapper blends their layers unlike a mesh's, docs/pass.md), a
  // translucent back face (a property of its own) or edges and wires
  // (raster blends them as lines over the layers); points as spheres and
  // tubes are decided with the data (hasUntraceableCells).
  if (actor->HasTranslucentPolygonalGeometry() &&
    (!rules.Translucency || glyphs || edges || actor->GetBackfaceProperty()))
  {
    return false;
  }
  // Textures, culling and back-face colors: on polygonal surfaces (a
  // translucent back face is left to raster, as a translucent front).
  vtkProperty* back = actor->GetBackfaceProperty();
  const bool surfaceLooks = actor->GetTexture() || property->GetNumberOfTextures() > 0 || back ||
    property->GetBackfaceCulling() || property->GetFrontfaceCulling();
  // Raster's wires are lines: never culled, never back faces, untextured.
  if (surfaceLooks &&
    (glyphs || representation == VTK_WIREFRAME || (back && back->GetOpacity() < 1.0) ||
      !TextureCache::Untraceable(actor).empty() ||
      (actor->GetTexture() && representation != VTK_SURFACE)))
  {
    return false;
  }
  return representation != VTK_POINTS || (!glyphs && property->GetRenderPointsAsSpheres());
}

void Scene::KeepCulledProps(
  vtkRenderer* ren, const std::unordered_set<vtkProp*>& previous, FrameCounters& counters)
{
  std::vector<vtkProp*> kept;
  std::vector<PropPart> parts;
  // Hidden props too, and props left to raster this frame for their looks
  // (points representation, PBR, ...): showing or tracing one again builds
  // and uploads nothing, as raster keeps an invisible actor's buffers.
  TraceRules rules = this->Rules;
  rules.Kept = true;
  const KeepingScope scope(*this, true);
  vtkCollectionSimpleIterator it;
  vtkPropCollection* all = ren->GetViewProps();
  all->InitTraversal(it);
  while (vtkProp* prop = all->GetNextProp(it))
  {
    // Only what the last frame traced or kept and this one does not trace:
    // a prop never traced yet is built when it first is, as raster makes
    // its buffers.
    if (this->Present.count(prop) || !previous.count(prop) || !TraceableParts(prop, rules, parts))
    {
      continue;
    }
    // What it has cached marked used (nothing built, as raster does
    // nothing for it), its instances dropped.
    const std::size_t first = this->Instances.size();
    std::vector<vtkProp*> standIns;
    if (this->AddParts(parts, -1, counters, standIns))
    {
      kept.push_back(prop);
    }
    this->Instances.resize(first);
  }
  this->Present.insert(kept.begin(), kept.end());
}

} // namespace pass
} // namespace vtkrt
