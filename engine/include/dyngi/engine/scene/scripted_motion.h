#pragma once
// Reproducible motion for built-in and test scenes: the pose is a pure function of time, so frame N of
// a headless run is the same on every machine (headless runs use a fixed time step).
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/ecs/scheduler.h"

namespace dyngi::scene {

struct ScriptedMotion {
  glm::vec3 origin{0.0f};                      // translation at t = 0 (before path/orbit/oscillation)
  glm::quat baseRotation{1.0f, 0.0f, 0.0f, 0.0f};
  // Closed polyline through these offsets from origin, traversed at `pathSpeed` units per second.
  std::vector<glm::vec3> path;
  float pathSpeed = 0.0f;
  // Orbit in the plane orthogonal to `orbitAxis` around origin.
  glm::vec3 orbitAxis{0.0f, 1.0f, 0.0f};
  float orbitRadius = 0.0f;
  float orbitSpeed = 0.0f;  // radians per second
  // Spin about `spinAxis` (local), radians per second.
  glm::vec3 spinAxis{0.0f, 1.0f, 0.0f};
  float spinSpeed = 0.0f;
  // Sinusoidal offset: amplitude vector and frequency in Hz.
  glm::vec3 oscillation{0.0f};
  float oscillationHz = 0.0f;
  float phase = 0.0f;       // seconds added to time
};

// A light that is on only from `onAt` until `offAt` (seconds of scripted time): a scripted load change.
struct ScriptedLightSwitch {
  double onAt = 0.0;
  double offAt = 1e30;
};

// Pose at time t (translation, rotation). Scale is left to the Transform.
void evaluateMotion(const ScriptedMotion& m, double t, glm::vec3& translation, glm::quat& rotation);

// Moves every entity with a ScriptedMotion and switches every light with a ScriptedLightSwitch (writing
// only what changed, so the change ticks say exactly that).
class ScriptedMotionSystem final : public ecs::System {
 public:
  const char* name() const override { return "scripted_motion"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
};

}  // namespace dyngi::scene
