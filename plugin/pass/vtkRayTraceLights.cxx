#include "vtkRayTraceLights.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"

namespace vtkrt
{
namespace pass
{

std::vector<core::gpu::Light> CollectLights(vtkRenderer* ren, const double origin[3], double scale)
{
  std::vector<core::gpu::Light> out;
  vtkLightCollection* lights = ren->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    const double intensity = light->GetIntensity();
    double* color = light->GetDiffuseColor();
    double* position = light->GetTransformedPosition();
    double* focal = light->GetTransformedFocalPoint();
    double direction[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
    vtkMath::Normalize(direction);
    double* attenuation = light->GetAttenuationValues();
    core::gpu::Light l;
    for (int k = 0; k < 3; ++k)
    {
      l.color[k] = static_cast<float>(color[k] * intensity);
      l.direction[k] = static_cast<float>(direction[k]);
      l.position[k] = static_cast<float>((position[k] - origin[k]) * scale);
    }
    // 1 / (a + b d + c d^2) with d in world units, the shader's d' = d * scale.
    l.attenuation[0] = static_cast<float>(attenuation[0]);
    l.attenuation[1] = static_cast<float>(attenuation[1] / scale);
    l.attenuation[2] = static_cast<float>(attenuation[2] / scale / scale);
    l.cone[0] = static_cast<float>(light->GetConeAngle());
    l.cone[1] = static_cast<float>(light->GetExponent());
    l.cone[2] = light->GetPositional() ? 1.0f : 0.0f;
    out.push_back(l);
  }
  return out;
}

void SetLightUniforms(vtkShaderProgram* program, const std::vector<core::gpu::Light>& lights)
{
  if (lights.empty())
  {
    return;
  }
  const int n = static_cast<int>(lights.size());
  std::vector<float> values(3 * lights.size());
  using Field = float(core::gpu::Light::*)[3];
  auto set = [&](const char* name, Field member) {
    for (std::size_t i = 0; i < lights.size(); ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        values[3 * i + k] = (lights[i].*member)[k];
      }
    }
    program->SetUniform3fv(name, n, values.data());
  };
  set("uLightColor", &core::gpu::Light::color);
  set("uLightDirection", &core::gpu::Light::direction);
  set("uLightPosition", &core::gpu::Light::position);
  set("uLightAttenuation", &core::gpu::Light::attenuation);
  set("uLightCone", &core::gpu::Light::cone);
}

} // namespace pass
} // namespace vtkrt
