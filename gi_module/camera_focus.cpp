#include "camera_focus.h"

#include <cmath>

namespace dyngi::gi {

CameraFocus cameraFocus(const render::RenderSnapshot& snapshot, float reach, float step) {
  CameraFocus f;
  const scene::Aabb& scene = snapshot.sceneBounds;
  f.bounds = scene;
  if (!scene.valid()) return f;
  f.centre = scene.center();
  f.radius = 0.5f * glm::length(scene.extent());
  // A camera outside the scene's bounds sees all of it from afar (an object framed from outside): no focus.
  const glm::vec3 camera = snapshot.camera.position;
  const bool inside = glm::all(glm::greaterThanEqual(camera, scene.min)) && glm::all(glm::lessThanEqual(camera, scene.max));
  if (!(reach > 0.0f) || f.radius <= reach || !inside) return f;
  const float cell = step > 0.0f ? std::min(step, reach) : 0.5f * reach;
  f.centre = (glm::floor(camera / cell) + 0.5f) * cell;
  const glm::vec3 half(reach / std::sqrt(3.0f));
  f.bounds.min = f.centre - half;
  f.bounds.max = f.centre + half;
  f.radius = reach;
  f.wholeScene = false;
  return f;
}

}  // namespace dyngi::gi
