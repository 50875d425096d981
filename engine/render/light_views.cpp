#include "dyngi/engine/render/light_views.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace dyngi::render {
namespace {
float farthestCorner(const scene::Aabb& b, const glm::vec3& p) {
  float d = 0.0f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
    d = std::max(d, glm::length(c - p));
  }
  return d;
}
glm::vec3 anyUp(const glm::vec3& dir) { return std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0); }
float outerAngle(const scene::Light& l) { return std::clamp(l.outerConeAngle, 1e-3f, 1.5707f); }
}  // namespace

std::vector<LightView> lightViews(const LightItem& item, const scene::Aabb& bounds, const scene::Aabb* window) {
  const scene::Light& l = item.light;
  std::vector<LightView> views;
  float farZ = l.range > 0.0f ? l.range : (bounds.valid() ? farthestCorner(bounds, item.position) * 1.01f + 0.01f : 100.0f);
  float nearZ = std::max(farZ * 1e-3f, 0.02f);
  if (l.type == scene::LightType::Spot) {
    float fov = std::min(2.0f * outerAngle(l) + 0.05f, 3.0f);
    LightView v;
    v.viewProj = glm::perspectiveRH_ZO(fov, 1.0f, nearZ, farZ) * glm::lookAtRH(item.position, item.position + item.direction, anyUp(item.direction));
    v.axis = item.direction;
    v.extent = 2.0f * std::tan(0.5f * fov);
    views.push_back(v);
  } else if (l.type == scene::LightType::Point) {
    const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& d : dirs) {
      LightView v;
      v.viewProj = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, nearZ, farZ) * glm::lookAtRH(item.position, item.position + d, anyUp(d));
      v.axis = d;
      v.extent = 2.0f;
      views.push_back(v);
    }
  } else {
    const bool windowed = window && window->valid() && bounds.valid();
    const scene::Aabb& area = windowed ? *window : bounds;
    glm::vec3 c = area.valid() ? area.center() : glm::vec3(0.0f);
    float r = area.valid() ? 0.5f * glm::length(area.extent()) + 1e-3f : 1.0f;
    // Every point of the scene lies within `reach` of c: the eye stands twice that back along the light,
    // the far plane as far past c.
    const float reach = windowed ? 0.5f * glm::length(bounds.extent()) + glm::distance(c, bounds.center()) + 1e-3f : r;
    LightView v;
    glm::mat4 view = glm::lookAtRH(c - item.direction * (2.0f * reach), c, anyUp(item.direction));
    v.viewProj = glm::orthoRH_ZO(-r, r, -r, r, 0.0f, 4.0f * reach) * view;
    v.axis = item.direction;
    v.extent = 2.0f * r;
    v.orthographic = true;
    views.push_back(v);
  }
  return views;
}

gpu::GpuLight toGpuLight(const LightItem& item) {
  const scene::Light& l = item.light;
  gpu::GpuLight g{};
  g.positionType = glm::vec4(item.position, float(uint32_t(l.type)));
  g.directionRange = glm::vec4(item.direction, l.range);
  g.radiance = glm::vec4(l.color * l.intensity, l.enabled ? 1.0f : 0.0f);
  float outer = outerAngle(l);
  float inner = std::clamp(l.innerConeAngle, 0.0f, outer);
  g.cone = glm::vec4(std::cos(outer), std::cos(inner), -1.0f, 0.0f);
  return g;
}

}  // namespace dyngi::render
