#include "fly_camera.h"

#include <GLFW/glfw3.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/components.h"

namespace dyngi::sample {

void FlyCameraSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  ecs::Entity cam{};
  world.each<scene::ActiveCamera, scene::Transform>([&](ecs::Entity e, const scene::ActiveCamera&, const scene::Transform&) { cam = e; });
  if (cam.isNull()) return;
  const scene::Transform& t = world.get<scene::Transform>(cam);
  if (!initialised_) {
    glm::vec3 fwd = t.rotation * glm::vec3(0, 0, -1);
    yaw_ = std::atan2(-fwd.x, -fwd.z);
    pitch_ = std::asin(glm::clamp(fwd.y, -1.0f, 1.0f));
    initialised_ = true;
  }
  const double dx = input_.mouseDelta.x, dy = input_.mouseDelta.y;
  const bool look = input_.down[kRight] && !uiHasMouse_;
  if (look) {
    yaw_ -= float(dx) * 0.003f;
    pitch_ = glm::clamp(pitch_ - float(dy) * 0.003f, -1.5f, 1.5f);
  }
  glm::quat rot = glm::angleAxis(yaw_, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch_, glm::vec3(1, 0, 0));
  glm::vec3 move(0.0f);
  if (input_.keyDown(GLFW_KEY_W)) move.z -= 1;
  if (input_.keyDown(GLFW_KEY_S)) move.z += 1;
  if (input_.keyDown(GLFW_KEY_A)) move.x -= 1;
  if (input_.keyDown(GLFW_KEY_D)) move.x += 1;
  if (input_.keyDown(GLFW_KEY_Q)) move.y -= 1;
  if (input_.keyDown(GLFW_KEY_E)) move.y += 1;
  if (move == glm::vec3(0.0f) && !look) return;  // untouched: no write, no change tick
  float speed = input_.keyDown(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.5f;
  scene::Transform& w = world.write<scene::Transform>(cam);
  w.rotation = rot;
  if (move != glm::vec3(0.0f)) w.translation += rot * glm::normalize(move) * speed * float(ctx.time.dt);
}

}  // namespace dyngi::sample
