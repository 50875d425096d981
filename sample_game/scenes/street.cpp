// A world far larger than a room: a straight street between two rows of building blocks under a low sun
// (StreetLayout). "street-near" keeps only what lies within StreetLayout::kNearReach of the camera along
// the street: the same near view with a room-sized voxel volume, what the large world should look like
// there.
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

using namespace scene;

void buildStreet(bool nearOnly, ecs::World& w, AssetStore& assets) {
  using L = StreetLayout;
  const float x0 = -L::kHalfLength, x1 = nearOnly ? L::kCamera.x + L::kNearReach : L::kHalfLength;
  const float depth = L::kHalfWidth + L::kBlockDepth;
  // The ground under the street and the blocks (normal up).
  addSceneMesh(w, assets, makeQuad({x0, 0, depth}, {x1 - x0, 0, 0}, {0, 0, -2 * depth}), glm::vec3(0.45f), {}, false, "ground");
  // Blocks of kBlockLength every kBlockLength + kAlley along the street, their facades at z = +-kHalfWidth,
  // 8 to 20 m tall and in four colours in a fixed pattern.
  const glm::vec3 facades[] = {{0.62f, 0.36f, 0.26f}, {0.72f, 0.66f, 0.50f}, {0.52f, 0.52f, 0.52f}, {0.44f, 0.54f, 0.66f}};
  int i = 0;
  for (float x = x0; x + L::kBlockLength <= x1 + 1e-3f; x += L::kBlockLength + L::kAlley, ++i)
    for (int side = 0; side < 2; ++side) {
      const int pattern = (i * 7 + side * 3) % 4;
      const float height = 8.0f + 4.0f * float((i * 5 + side) % 4);
      Transform t;
      t.translation = {x + 0.5f * L::kBlockLength, 0.5f * height, (side ? 1.0f : -1.0f) * (L::kHalfWidth + 0.5f * L::kBlockDepth)};
      const std::string name = "block_" + std::to_string(i) + (side ? "_south" : "_north");
      addSceneMesh(w, assets, makeBox({0.5f * L::kBlockLength, 0.5f * height, 0.5f * L::kBlockDepth}), facades[pattern], t, false, name.c_str());
    }
  // The sun, low over the north row: it lights the south row's facades and part of the street; the
  // north facades and the rest of the street get bounce light only.
  Entity sun = w.create();
  Transform st;
  st.rotation = glm::quatLookAtRH(glm::normalize(L::kSunDirection), glm::vec3(0, 1, 0));  // local -Z along the light
  w.add(sun, st);
  w.add(sun, WorldTransform{st.matrix()});
  Light light;
  light.type = LightType::Directional;
  light.intensity = L::kSunIntensity;
  w.add(sun, light);
  w.add(sun, Name{"sun"});
  // The camera at eye height near the west end, looking east down the street.
  Entity cam = w.create();
  Transform ct;
  ct.translation = L::kCamera;
  ct.rotation = glm::angleAxis(glm::radians(-90.0f + L::kCameraYawDeg), glm::vec3(0, 1, 0));  // local -Z -> world +x, turned
  w.add(cam, ct);
  w.add(cam, WorldTransform{ct.matrix()});
  w.add(cam, Camera{.yfov = glm::radians(60.0f), .znear = 0.1f, .zfar = 2.0f * L::kHalfLength + 50.0f});
  w.add(cam, ActiveCamera{});
  w.add(cam, Name{"camera"});
}

void addStreetFlight(ecs::World& w) {
  using L = StreetLayout;
  w.each<ActiveCamera, Transform>([&](Entity e, const ActiveCamera&, const Transform& t) {
    ScriptedMotion flight;
    flight.origin = t.translation;
    flight.baseRotation = t.rotation;
    flight.path = {glm::vec3(0.0f), glm::vec3(L::kFlightLength, 0.0f, 0.0f)};  // there and back, facing east
    flight.pathSpeed = L::kFlightSpeed;
    w.commands().add(e, flight);
  });
  w.flushCommands();
}

}  // namespace dyngi::sample
