#include "dyngi/engine/render/frame_uniforms.h"

#include <algorithm>

namespace dyngi::render {

gpu::FrameUniforms cameraUniforms(const CameraView& camera, uint32_t width, uint32_t height) {
  gpu::FrameUniforms fu{};
  width = std::max(width, 1u);
  height = std::max(height, 1u);
  const double w = width, h = height;
  fu.view = camera.view;
  fu.proj = camera.projection(float(width) / float(height));
  fu.viewProj = fu.proj * fu.view;
  fu.invViewProj = glm::inverse(fu.viewProj);
  fu.cameraPos = glm::vec4(camera.position, 1.0f);
  // Pixel rays in double precision: the per-pixel steps are small differences of nearly equal rays.
  const glm::dmat4 inv = glm::inverse(glm::dmat4(fu.proj) * glm::dmat4(fu.view));
  const glm::dvec3 eye(camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(glm::inverse(glm::dmat4(fu.view)) * glm::dvec4(0, 0, -1, 0)));
  auto ray = [&](double x, double y) {  // through pixel coordinate (x, y), scaled to unit view depth
    glm::dvec4 p = inv * glm::dvec4(x / w * 2.0 - 1.0, y / h * 2.0 - 1.0, 0.5, 1.0);
    glm::dvec3 d = glm::dvec3(p) / p.w - eye;
    return d / glm::dot(d, forward);
  };
  const glm::dvec3 r0 = ray(0.5, 0.5);
  fu.viewForward = glm::vec4(glm::vec3(forward), 0.0f);
  fu.pixelRay0 = glm::vec4(glm::vec3(r0), 0.0f);
  fu.pixelRayStepX = glm::vec4(glm::vec3(ray(1.5, 0.5) - r0), 0.0f);  // exact in double: rays are affine in x
  fu.pixelRayStepY = glm::vec4(glm::vec3(ray(0.5, 1.5) - r0), 0.0f);
  return fu;
}

}  // namespace dyngi::render
