#include "dyngi/engine/scene/scripted_motion.h"

#include <cmath>

#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

void evaluateMotion(const ScriptedMotion& m, double time, glm::vec3& translation, glm::quat& rotation) {
  float t = float(time) + m.phase;
  glm::vec3 p = m.origin;
  if (m.path.size() >= 2 && m.pathSpeed > 0.0f) {
    float total = 0.0f;
    for (size_t i = 0; i < m.path.size(); ++i) total += glm::length(m.path[(i + 1) % m.path.size()] - m.path[i]);
    float s = total > 0.0f ? std::fmod(t * m.pathSpeed, total) : 0.0f;
    for (size_t i = 0; i < m.path.size(); ++i) {
      glm::vec3 a = m.path[i], b = m.path[(i + 1) % m.path.size()];
      float len = glm::length(b - a);
      if (s <= len || i + 1 == m.path.size()) {
        p += len > 0.0f ? glm::mix(a, b, std::min(s / len, 1.0f)) : a;
        break;
      }
      s -= len;
    }
  }
  if (m.orbitRadius != 0.0f && m.orbitSpeed != 0.0f) {
    glm::vec3 axis = glm::normalize(m.orbitAxis);
    glm::vec3 u = std::abs(axis.x) < 0.9f ? glm::normalize(glm::cross(axis, {1, 0, 0})) : glm::normalize(glm::cross(axis, {0, 0, 1}));
    glm::vec3 v = glm::cross(axis, u);
    float a = t * m.orbitSpeed;
    p += m.orbitRadius * (std::cos(a) * u + std::sin(a) * v);
  }
  if (m.oscillationHz != 0.0f) p += m.oscillation * std::sin(2.0f * 3.14159265f * m.oscillationHz * t);
  translation = p;
  rotation = m.baseRotation;
  if (m.spinSpeed != 0.0f) rotation = m.baseRotation * glm::angleAxis(t * m.spinSpeed, glm::normalize(m.spinAxis));
}

void ScriptedMotionSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  std::vector<std::pair<Entity, const ScriptedMotion*>> movers;
  world.each<ScriptedMotion, Transform>([&](Entity e, const ScriptedMotion& m, const Transform&) { movers.push_back({e, &m}); });
  for (auto& [e, m] : movers) {
    glm::vec3 tr;
    glm::quat rot;
    evaluateMotion(*m, ctx.time.time, tr, rot);
    const Transform& cur = world.get<Transform>(e);
    if (cur.translation != tr || cur.rotation != rot) {
      Transform& t = world.write<Transform>(e);
      t.translation = tr;
      t.rotation = rot;
    }
  }
  std::vector<std::pair<Entity, bool>> switches;
  world.each<ScriptedLightSwitch, Light>([&](Entity e, const ScriptedLightSwitch& s, const Light& l) {
    const bool on = ctx.time.time >= s.onAt && ctx.time.time < s.offAt;
    if (on != l.enabled) switches.push_back({e, on});
  });
  for (auto& [e, on] : switches) world.write<Light>(e).enabled = on;
}

}  // namespace dyngi::scene
