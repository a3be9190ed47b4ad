#include "vtkRayTraceRecords.h"

#include "vtkRayTracePacker.h"
#include "vtkRayTraceTextures.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderer.h"

#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/Math.h"

#include <algorithm>
#include <cmath>

namespace vtkrt
{
namespace pass
{

void CameraFrame::Set(vtkOpenGLRenderer* ren, vtkOpenGLCamera* cam, bool worldCoordinates, double scale)
{
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  ren->GetTiledSizeAndOrigin(size, size + 1, origin, origin + 1);
  this->Set(ren, cam, worldCoordinates, scale, size, origin);
}

void CameraFrame::Set(vtkOpenGLRenderer* ren, vtkOpenGLCamera* cam, bool worldCoordinates, double scale,
  const int viewportSize[2], const int viewportOrigin[2])
{
  this->Scale = scale;
  std::copy(viewportSize, viewportSize + 2, this->ViewportSize);
  std::copy(viewportOrigin, viewportOrigin + 2, this->ViewportOrigin);
  vtkMatrix4x4* wcvc;
  vtkMatrix3x3* normalMatrix;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  cam->GetKeyMatrices(ren, wcvc, normalMatrix, vcdc, wcdc);
  // The rays are in the coordinates the camera's model-view transform
  // takes to its view (world coordinates but for a model transform, and
  // with a user view transform): the eye and the view direction are the
  // view's origin and -z taken back through it, as raster lights in view
  // coordinates (a scale or shear in a user view transform only about:
  // raster normalizes each normal after it). A singular one keeps the
  // camera's own position and direction.
  vtkMatrix4x4* modelView = cam->GetModelViewTransformMatrix();
  vtkNew<vtkMatrix4x4> viewToModel;
  const bool invertible = modelView->Determinant() != 0.0;
  if (invertible)
  {
    vtkMatrix4x4::Invert(modelView, viewToModel);
  }
  double eye[4] = { 0.0, 0.0, 0.0, 1.0 };
  double dop[4] = { 0.0, 0.0, -1.0, 0.0 };
  if (invertible)
  {
    viewToModel->MultiplyPoint(eye, eye);
    viewToModel->MultiplyPoint(dop, dop);
  }
  else
  {
    cam->GetPosition(eye);
    cam->GetDirectionOfProjection(dop);
  }
  for (int k = 0; k < 3; ++k)
  {
    this->Eye[k] = eye[k] / eye[3];
    this->Origin[k] = worldCoordinates ? 0.0 : this->Eye[k];
  }
  vtkNew<vtkMatrix4x4> worldToClip; // row-major P * V
  vtkMatrix4x4::Transpose(wcdc, worldToClip);
  vtkNew<vtkMatrix4x4> shaderToWorld;
  for (int k = 0; k < 3; ++k)
  {
    shaderToWorld->SetElement(k, k, 1.0 / scale);
    shaderToWorld->SetElement(k, 3, this->Origin[k]);
  }
  vtkMatrix4x4::Multiply4x4(worldToClip, shaderToWorld, this->CameraToClip);
  // Clip coordinates are homogeneous: a power of two brings the entries
  // near 1 (float holds them at any scene size) and changes no image.
  double largest = 0.0;
  for (int i = 0; i < 16; ++i)
  {
    largest = std::max(largest, std::abs(this->CameraToClip->GetData()[i]));
  }
  const double normalize = core::powerOfTwoScale(largest);
  for (int i = 0; i < 16; ++i)
  {
    this->CameraToClip->GetData()[i] *= normalize;
  }
  vtkMatrix4x4::Invert(this->CameraToClip, this->ClipToCamera);
  this->SetAffineRays();
  const int width = this->ViewportSize[0], height = this->ViewportSize[1];
  this->CameraToPixels->DeepCopy(this->CameraToClip);
  for (int c = 0; c < 4; ++c)
  {
    this->CameraToPixels->SetElement(0, c, 0.5 * width * this->CameraToClip->GetElement(0, c));
    this->CameraToPixels->SetElement(1, c, 0.5 * height * this->CameraToClip->GetElement(1, c));
  }
  vtkMath::Normalize(dop);
  std::copy(dop, dop + 3, this->DirectionOfProjection);
}

void CameraFrame::UnprojectRay(double x, double y, double org[3], double dir[3]) const
{
  const double nearClip[4] = { x, y, -1.0, 1.0 };
  const double farClip[4] = { x, y, 1.0, 1.0 };
  double nearPoint[4], farPoint[4];
  this->ClipToCamera->MultiplyPoint(nearClip, nearPoint);
  this->ClipToCamera->MultiplyPoint(farClip, farPoint);
  for (int k = 0; k < 3; ++k)
  {
    org[k] = nearPoint[k] / nearPoint[3];
    dir[k] = farPoint[k] / farPoint[3] - org[k];
  }
}

void CameraFrame::AffineRay(double x, double y, double org[3], double dir[3]) const
{
  for (int k = 0; k < 3; ++k)
  {
    org[k] = this->RayOrigin[0][k] + x * this->RayOrigin[1][k] + y * this->RayOrigin[2][k];
    dir[k] = this->RayDirection[0][k] + x * this->RayDirection[1][k] + y * this->RayDirection[2][k];
  }
}

double CameraFrame::NearPlaneW() const
{
  const double w = this->RayDepth[2]; // clip w where the rays start
  return this->AffineRays && w > 0.0 && std::isfinite(w) ? w : 0.0;
}

void CameraFrame::SetAffineRays()
{
  // The ray at (0, 0) and its steps along x and y; affine when the rays at
  // the viewport's corners are where those steps put them, to a relative
  // 1e-6 of the origins' and the directions' sizes: exactly so for VTK's
  // cameras up to the inverse's rounding, far from it for a projective
  // matrix (and a matrix too ill-conditioned to tell keeps the per-pixel
  // unprojection, as good as any).
  double org[3], dir[3], orgX[3], dirX[3], orgY[3], dirY[3];
  this->UnprojectRay(0.0, 0.0, org, dir);
  this->UnprojectRay(1.0, 0.0, orgX, dirX);
  this->UnprojectRay(0.0, 1.0, orgY, dirY);
  double originSize = 0.0, directionSize = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    this->RayOrigin[0][k] = org[k];
    this->RayOrigin[1][k] = orgX[k] - org[k];
    this->RayOrigin[2][k] = orgY[k] - org[k];
    this->RayDirection[0][k] = dir[k];
    this->RayDirection[1][k] = dirX[k] - dir[k];
    this->RayDirection[2][k] = dirY[k] - dir[k];
    for (int r = 0; r < 3; ++r)
    {
      originSize = std::max(originSize, std::abs(this->RayOrigin[r][k]));
      directionSize = std::max(directionSize, std::abs(this->RayDirection[r][k]));
    }
  }
  const double tolerance = 1e-6;
  bool affine = std::isfinite(originSize) && std::isfinite(directionSize) && directionSize > 0.0;
  for (const double x : { -1.0, 1.0 })
  {
    for (const double y : { -1.0, 1.0 })
    {
      double cornerOrg[3], cornerDir[3], o[3], d[3];
      this->UnprojectRay(x, y, cornerOrg, cornerDir);
      this->AffineRay(x, y, o, d);
      for (int k = 0; k < 3; ++k)
      {
        affine = affine && std::abs(o[k] - cornerOrg[k]) <= tolerance * originSize &&
          std::abs(d[k] - cornerDir[k]) <= tolerance * directionSize;
      }
    }
  }
  this->AffineRays = affine;
  // Clip z and w at both ends of the ray at (0, 0).
  double nearPoint[4] = { org[0], org[1], org[2], 1.0 };
  double farPoint[4] = { org[0] + dir[0], org[1] + dir[1], org[2] + dir[2], 1.0 };
  this->CameraToClip->MultiplyPoint(nearPoint, nearPoint);
  this->CameraToClip->MultiplyPoint(farPoint, farPoint);
  this->RayDepth[0] = nearPoint[2];
  this->RayDepth[1] = farPoint[2] - nearPoint[2];
  this->RayDepth[2] = nearPoint[3];
  this->RayDepth[3] = farPoint[3] - nearPoint[3];
}

ScreenSphereRadii ComputeScreenSphereRadii(const Instance& inst, vtkRenderer* ren, int viewportHeight,
  const double localToShader[16], const double eyeInShader[3], const double dop[3], double shaderScale)
{
  ScreenSphereRadii out;
  const Geometry& g = *inst.Geom;
  // Wires (a diameter: twice what is drawn off the edge): half a wire
  // along its minor axis is up to sqrt(2) half widths off the edge; an
  // eighth of a pixel more for float rounding (every pixel of margin
  // visits more leaves: the wire walk's main cost on fine meshes).
  const double pixelsWide = g.ScreenSized ? inst.PointSize
    : inst.Wireframe                      ? std::sqrt(2.0) * std::max(1.0f, inst.LineWidth) + 0.25
                                          : 0.0;
  if (!(pixelsWide > 0.0) || !ren || !ren->GetActiveCamera())
  {
    return out;
  }
  vtkCamera* cam = ren->GetActiveCamera();
  const double pixels = static_cast<double>(std::max(1, viewportHeight));
  // Radius per unit of view depth (perspective) or constant (parallel), in
  // shader units.
  const double perDepth =
    pixelsWide * std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2.0) / pixels;
  const double constant = pixelsWide * cam->GetParallelScale() * shaderScale / pixels;
  // Local units -> shader units: the actor's (uniform) scale.
  double m3[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m3[r][c] = localToShader[4 * r + c];
    }
  }
  const double scale = std::cbrt(std::abs(vtkMath::Determinant3x3(m3)));
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return out;
  }
  if (cam->GetParallelProjection())
  {
    out.Plane[3] = constant / scale;
  }
  else
  {
    // depth(c) = dop . (M c + t - eye), affine in the local center c.
    double w = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      w += dop[r] * (localToShader[4 * r + 3] - eyeInShader[r]);
    }
    for (int c = 0; c < 3; ++c)
    {
      out.Plane[c] = perDepth / scale * (dop[0] * m3[0][c] + dop[1] * m3[1][c] + dop[2] * m3[2][c]);
    }
    out.Plane[3] = perDepth / scale * w;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[3] = { g.LocalBounds[(corner & 1) ? 1 : 0], g.LocalBounds[(corner & 2) ? 3 : 2],
      g.LocalBounds[(corner & 4) ? 5 : 4] };
    out.MaxLocal = std::max(out.MaxLocal,
      out.Plane[0] * p[0] + out.Plane[1] * p[1] + out.Plane[2] * p[2] + out.Plane[3]);
  }
  out.MaxWorld = out.MaxLocal * scale / shaderScale;
  return out;
}

namespace
{
/// The instance's local (Geometry) to shader matrix: (M (l / scale +
/// origin) - camera origin) * camera scale, composed in double.
void localToShader(const Instance& inst, const CameraFrame& camera, vtkMatrix4x4* out)
{
  const Geometry& g = *inst.Geom;
  out->DeepCopy(inst.Matrix.data());
  for (int r = 0; r < 3; ++r)
  {
    double t = out->GetElement(r, 3);
    for (int c = 0; c < 3; ++c)
    {
      t += out->GetElement(r, c) * g.Origin[c];
      out->SetElement(r, c, out->GetElement(r, c) / g.Scale * camera.Scale);
    }
    out->SetElement(r, 3, (t - camera.Origin[r]) * camera.Scale);
  }
}

/// The instance's world box: its local box's 8 corners through its matrix.
core::AABB<double> worldBox(const Instance& inst)
{
  const Geometry& g = *inst.Geom;
  core::AABB<double> box;
  for (int corner = 0; corner < 8; ++corner)
  {
    double p[4] = { g.LocalBounds[(corner & 1) ? 1 : 0] / g.Scale + g.Origin[0],
      g.LocalBounds[(corner & 2) ? 3 : 2] / g.Scale + g.Origin[1],
      g.LocalBounds[(corner & 4) ? 5 : 4] / g.Scale + g.Origin[2], 1.0 };
    double w[4];
    for (int r = 0; r < 4; ++r)
    {
      w[r] = inst.Matrix[4 * r] * p[0] + inst.Matrix[4 * r + 1] * p[1] +
        inst.Matrix[4 * r + 2] * p[2] + inst.Matrix[4 * r + 3];
    }
    box.extend(core::Vec3<double>(w[0] / w[3], w[1] / w[3], w[2] / w[3]));
  }
  return box;
}

/// The shader-space box of the instance, padded for the float rounding of
/// the transformed ray and by the largest screen-sphere radius.
void shaderBox(const Instance& inst, vtkMatrix4x4* toShader, double grow, core::gpu::InstanceRecord& rec)
{
  const Geometry& g = *inst.Geom;
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (int corner = 0; corner < 8; ++corner)
  {
    double p[4] = { g.LocalBounds[(corner & 1) ? 1 : 0], g.LocalBounds[(corner & 2) ? 3 : 2],
      g.LocalBounds[(corner & 4) ? 5 : 4], 1.0 };
    toShader->MultiplyPoint(p, p);
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  double pad = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    pad = std::max({ pad, std::abs(lo[k]), std::abs(hi[k]) });
  }
  pad = pad * 1e-6 + grow;
  for (int k = 0; k < 3; ++k)
  {
    rec.boxMin[k] = core::roundDownToFloat(lo[k] - pad);
    rec.boxMax[k] = core::roundUpToFloat(hi[k] + pad);
  }
}

/// An instance's half-size in shader units, from its local box through the
/// largest entry of its linear part.
double shaderHalfSize(const Instance& inst, vtkMatrix4x4* toShader)
{
  const Geometry& g = *inst.Geom;
  double stretch = 0.0, half = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      stretch = std::max(stretch, std::abs(toShader->GetElement(r, c)));
    }
    half = std::max(half, 0.5 * (g.LocalBounds[2 * r + 1] - g.LocalBounds[2 * r]));
  }
  return stretch * half;
}

/// Cell edges: their color, width, and the local-to-shader rows the shader
/// projects the triangles' vertices with (zero without edges).
void fillEdges(const Instance& inst, vtkMatrix4x4* toShader, core::gpu::InstanceRecord& rec)
{
  if (!inst.SurfaceEdges && !inst.Wireframe)
  {
    return;
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      rec.localToCamera[r][c] = static_cast<float>(toShader->GetElement(r, c));
    }
    rec.edgeColor[r] = inst.EdgeColor[r];
  }
  rec.lineWidth = inst.LineWidth;
}

std::uint32_t instanceFlags(const Instance& inst, bool mirrored)
{
  using namespace core::gpu;
  const Geometry& g = *inst.Geom;
  std::uint32_t flags = g.Spheres ? kInstanceSpheres : 0u;
  flags |= g.Ellipsoids ? kInstanceEllipsoids : 0u;
  flags |= g.Tubes ? kInstanceTubes : 0u;
  flags |= g.SphereCellIds.empty() ? 0u : kInstanceSphereCellIds;
  flags |= g.IsScreenSphereSet() ? kInstanceScreenSpheres : 0u;
  flags |= inst.Lit ? kInstanceLit : 0u;
  flags |= inst.UseVertexNormals ? kInstanceVertexNormals : 0u;
  flags |= inst.UseCellNormals ? kInstanceCellNormals : 0u;
  if (inst.Color)
  {
    flags |= inst.Color->CellColors ? kInstanceCellColors : kInstancePointColors;
    flags |= inst.Color->Texture ? kInstanceColorTexture : 0u;
  }
  flags |= mirrored ? kInstanceMirrored : 0u;
  flags |= inst.Texture ? kInstanceTextured : 0u;
  flags |= inst.Texture && inst.TextureOnBackface ? kInstanceTextureOnBackface : 0u;
  flags |= inst.Texture && inst.Texture->CutOuts ? kInstanceTextureCutOuts : 0u;
  flags |= inst.BackfaceProperty ? kInstanceBackfaceProperty : 0u;
  flags |= inst.CullBackfaces ? kInstanceCullBackfaces : 0u;
  flags |= inst.CullFrontfaces ? kInstanceCullFrontfaces : 0u;
  flags |= inst.Translucent ? kInstanceTranslucent : 0u;
  flags |= inst.SurfaceEdges ? kInstanceSurfaceEdges : 0u;
  flags |= inst.Wireframe ? kInstanceWireframe : 0u;
  return flags;
}
} // namespace

double ViewScale(vtkCamera* cam)
{
  double range[2] = { 0.0, 0.0 };
  cam->GetClippingRange(range);
  if (!(range[1] > 0.0) || !std::isfinite(range[1]))
  {
    return 1.0;
  }
  int exponent = 0;
  std::frexp(range[1], &exponent); // far in [0.5, 1) * 2^exponent
  // The multiple of 16 that puts far * scale in [2^-8, 2^8).
  const int power = 16 * static_cast<int>(std::ceil((-7 - exponent) / 16.0));
  return std::ldexp(1.0, std::max(-1008, std::min(1008, power)));
}

double FrameRecords::SceneDiagonal() const
{
  core::AABB<double> all;
  for (const auto& b : this->WorldBoxes)
  {
    all.extend(b.min);
    all.extend(b.max);
  }
  const auto diagonal = all.max - all.min;
  return std::sqrt(diagonal.x * diagonal.x + diagonal.y * diagonal.y + diagonal.z * diagonal.z);
}

double FrameRecords::DefaultOcclusionRadius() const
{
  return 0.1 * this->SceneDiagonal();
}

bool MakeFrameRecords(const std::vector<Instance>& instances, const ScenePlacements& places,
  const CameraFrame& camera, vtkRenderer* ren, FrameRecords& out)
{
  out.Records.assign(instances.size(), core::gpu::InstanceRecord{});
  out.ClipPlanes.clear();
  out.TooSmallProps.clear();
  out.WorldBoxes.resize(instances.size());
  out.Outlines.resize(instances.size());
  out.RootNodes.assign(instances.size(), core::gpu::Node{});
  const int outlineDepth = OutlineDepth(instances.size());
  double eyeInShader[3];
  camera.ToShader(camera.Eye, eyeInShader);
  for (std::size_t i = 0; i < instances.size(); ++i)
  {
    const Instance& inst = instances[i];
    const auto place = places.Geometry.Placements.find(inst.Geom);
    const auto colorPlace =
      inst.Color ? places.Colors.Placements.find(inst.Color) : places.Colors.Placements.end();
    const auto textureBase = places.TextureBases.find(inst.Texture);
    const auto coordinateBase = places.TextureBases.find(inst.TextureCoordinates);
    if (place == places.Geometry.Placements.end() || (inst.Color && colorPlace == places.Colors.Placements.end()) ||
      (inst.Texture &&
        (textureBase == places.TextureBases.end() || coordinateBase == places.TextureBases.end())))
    {
      return false;
    }
    vtkNew<vtkMatrix4x4> toShader;
    localToShader(inst, camera, toShader);
    vtkNew<vtkMatrix4x4> shaderToLocal;
    vtkMatrix4x4::Invert(toShader, shaderToLocal);
    // Points and lines drawn PointSize or LineWidth pixels wide are shaded
    // at that size, however close together they lie.
    const double size = inst.Geom->ScreenSized ? 0.0 : shaderHalfSize(inst, toShader);
    if (size > 0.0 && size < kSmallestShadedSize &&
      std::find(out.TooSmallProps.begin(), out.TooSmallProps.end(), inst.PropIndex) ==
        out.TooSmallProps.end())
    {
      out.TooSmallProps.push_back(inst.PropIndex);
    }
    // Points drawn as spheres: radii from this frame's camera.
    const ScreenSphereRadii screen =
      ComputeScreenSphereRadii(inst, ren, camera.ViewportSize[1], toShader->GetData(), eyeInShader, camera.DirectionOfProjection, camera.Scale);
    out.WorldBoxes[i] = worldBox(inst);
    out.Outlines[i] = OutlineOf(inst, toShader->GetData(), outlineDepth);
    if (screen.MaxWorld > 0.0)
    {
      // Grown by the radius bound rounded up to a power of two, so the top
      // level is rebuilt only when a zoom crosses one.
      const double grow = std::exp2(std::ceil(std::log2(screen.MaxWorld)));
      out.WorldBoxes[i].min -= core::Vec3<double>(grow);
      out.WorldBoxes[i].max += core::Vec3<double>(grow);
    }
    core::gpu::InstanceRecord& rec = out.Records[i];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        rec.cameraToLocal[r][c] = static_cast<float>(shaderToLocal->GetElement(r, c));
      }
    }
    shaderBox(inst, toShader, screen.MaxWorld * camera.Scale, rec);
    rec.root = place->second.Root;
    // (The scene makes no instance of an empty geometry; a root left
    // empty would walk from node 0.)
    if (!inst.Geom->Empty())
    {
      out.RootNodes[i] = PlacedNode(*inst.Geom, place->second, 0);
    }
    rec.flags = instanceFlags(inst, toShader->Determinant() < 0.0);
    for (int k = 0; k < 3; ++k)
    {
      rec.ambient[k] = inst.Ambient[k];
      rec.diffuse[k] = inst.Diffuse[k];
      rec.specular[k] = inst.Specular[k];
      rec.backAmbient[k] = inst.BackAmbient[k];
      rec.backDiffuse[k] = inst.BackDiffuse[k];
      rec.backSpecular[k] = inst.BackSpecular[k];
    }
    rec.specularPower = inst.SpecularPower;
    rec.colorBase = inst.Color ? colorPlace->second.Base : 0u;
    rec.normalBase = inst.UseCellNormals ? place->second.CellNormalBase : place->second.NormalBase;
    rec.firstClipPlane = static_cast<std::uint32_t>(out.ClipPlanes.size() / 4);
    rec.clipPlaneCount = static_cast<std::uint32_t>(inst.ClipPlanes.size());
    rec.propIndex = static_cast<std::uint32_t>(inst.PropIndex);
    rec.compositeIndex = inst.CompositeIndex;
    rec.ambientIntensity = inst.AmbientIntensity;
    rec.diffuseIntensity = inst.DiffuseIntensity;
    rec.sphereGrow = static_cast<float>(screen.MaxLocal);
    rec.opacity = inst.Opacity;
    for (int k = 0; k < 4; ++k)
    {
      rec.screenRadiusPlane[k] = static_cast<float>(screen.Plane[k]);
    }
    rec.backSpecularPower = inst.BackSpecularPower;
    rec.textureBase = inst.Texture ? textureBase->second : 0u;
    rec.textureCoordinateBase = inst.Texture ? coordinateBase->second : 0u;
    rec.sphereCellIdBase = SphereCellIdBase(*inst.Geom, place->second);
    fillEdges(inst, toShader, rec);
    for (const auto& pl : inst.ClipPlanes)
    {
      const double d = (pl[3] + pl[0] * camera.Origin[0] + pl[1] * camera.Origin[1] +
                         pl[2] * camera.Origin[2]) * camera.Scale;
      out.ClipPlanes.insert(out.ClipPlanes.end(),
        { static_cast<float>(pl[0]), static_cast<float>(pl[1]), static_cast<float>(pl[2]),
          static_cast<float>(d) });
    }
  }
  return true;
}

void KeepPickableInstances(
  const std::vector<bool>& traced, const std::vector<Instance>& instances, FrameRecords& frame)
{
  std::size_t kept = 0;
  for (std::size_t i = 0; i < frame.Records.size(); ++i)
  {
    const std::uint32_t prop = frame.Records[i].propIndex;
    if (prop < traced.size() && traced[prop] && (i >= instances.size() || instances[i].Pickable))
    {
      frame.Records[kept] = frame.Records[i];
      frame.WorldBoxes[kept] = frame.WorldBoxes[i];
      frame.Outlines[kept] = frame.Outlines[i];
      frame.RootNodes[kept] = frame.RootNodes[i];
      ++kept;
    }
  }
  frame.Records.resize(kept);
  frame.WorldBoxes.resize(kept);
  frame.Outlines.resize(kept);
  frame.RootNodes.resize(kept);
}

} // namespace pass
} // namespace vtkrt
