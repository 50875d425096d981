#include "dyngi/engine/scene/light_units.h"

#include <algorithm>
#include <cmath>

namespace dyngi::scene {

float spotFalloff(float cosAngle, float innerConeAngle, float outerConeAngle) {
  float cosOuter = std::cos(outerConeAngle);
  float cosInner = std::cos(innerConeAngle);
  float t = std::clamp((cosAngle - cosOuter) / std::max(cosInner - cosOuter, 1e-4f), 0.0f, 1.0f);
  return t * t;
}

float rangeWindow(float distance, float range) {
  if (range <= 0.0f) return 1.0f;
  float r = distance / range;
  float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  return w * w;
}

glm::vec3 directIrradiance(const Light& light, const glm::vec3& lightPos, const glm::vec3& lightDir,
                           const glm::vec3& p, const glm::vec3& n) {
  if (!light.enabled) return glm::vec3(0.0f);
  glm::vec3 radiant = light.color * light.intensity;
  if (light.type == LightType::Directional) {
    return radiant * std::max(0.0f, glm::dot(n, -lightDir));
  }
  glm::vec3 toLight = lightPos - p;
  float d2 = glm::dot(toLight, toLight);
  float d = std::sqrt(d2);
  glm::vec3 l = toLight / d;
  float e = std::max(0.0f, glm::dot(n, l)) / d2 * rangeWindow(d, light.range);
  if (light.type == LightType::Spot) e *= spotFalloff(glm::dot(-l, lightDir), light.innerConeAngle, light.outerConeAngle);
  return radiant * e;
}

}  // namespace dyngi::scene
