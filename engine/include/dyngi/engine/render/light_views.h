#pragma once
// How each light sees the scene: the projections the shadow pass renders (and that a reflective
// shadow map renders too), and the GPU light record. One definition for every pass that needs them.
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/snapshot.h"
#include "shared/gpu_types.h"

namespace dyngi::render {

struct LightView {
  glm::mat4 viewProj{1.0f};
  glm::vec3 axis{0.0f, 0.0f, -1.0f};  // the view's forward direction
  // Perspective views: 2 tan(fov/2) (texel footprint per unit distance x resolution).
  // Orthographic views (directional lights): the side of the square the view covers, in world units.
  float extent = 2.0f;
  bool orthographic = false;
};

// One view for a spot or directional light, six (+X,-X,+Y,-Y,+Z,-Z) for a point light. A directional
// light's view covers the scene, or with `window` only that box across the light (a reflective shadow map
// kept near the camera), still seen from outside the scene: whatever stands towards the light is in it.
std::vector<LightView> lightViews(const LightItem& light, const scene::Aabb& sceneBounds, const scene::Aabb* window = nullptr);
gpu::GpuLight toGpuLight(const LightItem& light);

}  // namespace dyngi::render
