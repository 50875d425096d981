// Two closed rooms side by side with a thin shared wall (a leak test: light in one room must not reach
// the other through the wall). Room A x in [-2, 0] holds the spot; room B x in [0, 2] holds the camera,
// looking at the shared wall. With a doorway, light reaches B through a 0.6 m x 1.4 m opening.
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/components.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

using namespace scene;

namespace {
Entity addStatic(ecs::World& w, AssetStore& assets, MeshData mesh, const glm::vec3& albedo, const glm::vec3& at, const char* name) {
  Transform t;
  t.translation = at;
  return addSceneMesh(w, assets, std::move(mesh), albedo, t, /*dynamic=*/false, name);
}
}  // namespace

void buildTwoRooms(bool doorway, ecs::World& w, AssetStore& assets) {
  const glm::vec3 white(CornellLayout::kWhite), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
  // The shell: quads facing in, x in [-2, 2], y in [0, 2], z in [-1, 1].
  addStatic(w, assets, makeQuad({-2, 0, 1}, {4, 0, 0}, {0, 0, -2}), white, {}, "floor");
  addStatic(w, assets, makeQuad({-2, 2, -1}, {4, 0, 0}, {0, 0, 2}), white, {}, "ceiling");
  addStatic(w, assets, makeQuad({-2, 0, -1}, {4, 0, 0}, {0, 2, 0}), white, {}, "back_wall");
  addStatic(w, assets, makeQuad({2, 0, 1}, {-4, 0, 0}, {0, 2, 0}), white, {}, "front_wall");
  addStatic(w, assets, makeQuad({-2, 0, 1}, {0, 0, -2}, {0, 2, 0}), red, {}, "left_wall_red");
  addStatic(w, assets, makeQuad({2, 0, -1}, {0, 0, 2}, {0, 2, 0}), green, {}, "right_wall_green");
  // The shared wall at x = 0, TwoRoomsLayout::kWallThickness thick (thinner than two voxels at the default resolution).
  const float h = 0.5f * TwoRoomsLayout::kWallThickness;
  if (!doorway) {
    addStatic(w, assets, makeBox({h, 1.0f, 1.0f}), white, {0.0f, 1.0f, 0.0f}, "shared_wall");
  } else {
    // A 0.6 m wide, 1.4 m high opening at z in [-0.3, 0.3].
    addStatic(w, assets, makeBox({h, 1.0f, 0.35f}), white, {0.0f, 1.0f, -0.65f}, "shared_wall_back");
    addStatic(w, assets, makeBox({h, 1.0f, 0.35f}), white, {0.0f, 1.0f, 0.65f}, "shared_wall_front");
    addStatic(w, assets, makeBox({h, 0.3f, 0.3f}), white, {0.0f, 1.7f, 0.0f}, "shared_wall_lintel");
  }
  // Room A: the spot, pointing down at its floor.
  Entity spot = w.create();
  Transform st;
  st.translation = {-1.0f, CornellLayout::kSpotHeight, 0.0f};
  st.rotation = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));
  w.add(spot, st);
  w.add(spot, WorldTransform{st.matrix()});
  Light light;
  light.type = LightType::Spot;
  light.intensity = CornellLayout::kSpotIntensity;
  light.outerConeAngle = glm::radians(CornellLayout::kSpotOuterDeg);
  light.innerConeAngle = glm::radians(CornellLayout::kSpotInnerDeg);
  w.add(spot, light);
  w.add(spot, Name{"spot"});
  // Room B: the camera by the right wall, looking at the shared wall.
  Entity cam = w.create();
  Transform ct;
  ct.translation = {1.85f, 1.0f, 0.0f};
  ct.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));  // local -Z -> world -X
  w.add(cam, ct);
  w.add(cam, WorldTransform{ct.matrix()});
  w.add(cam, Camera{.yfov = glm::radians(70.0f), .znear = 0.05f, .zfar = 50.0f});
  w.add(cam, ActiveCamera{});
  w.add(cam, Name{"camera"});
}

}  // namespace dyngi::sample
