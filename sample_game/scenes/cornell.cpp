#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

using namespace scene;

bool isBuiltinScene(const std::string& name) { return name == "cornell" || name == "cornell-dynamic"; }

namespace {
Entity addMesh(ecs::World& w, AssetStore& assets, MeshData mesh, const glm::vec3& albedo, const Transform& t, bool dynamic,
               const char* name) {
  Entity e = w.create();
  mesh.name = name;
  w.add(e, t);
  w.add(e, WorldTransform{t.matrix()});
  w.add(e, MeshInstance{assets.addMesh(std::move(mesh)), true});
  Material m;
  m.baseColor = glm::vec4(albedo, 1.0f);
  w.add(e, m);
  w.add(e, Name{name});
  if (dynamic) w.add(e, DynamicTag{});
  else w.add(e, StaticTag{});
  return e;
}
}  // namespace

void buildBuiltinScene(const std::string& name, ecs::World& w, AssetStore& assets) {
  const bool dynamic = name == "cornell-dynamic";
  const glm::vec3 white(CornellLayout::kWhite), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
  // Walls: quads whose normal (U x V) faces into the room.
  addMesh(w, assets, makeQuad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}), white, {}, false, "floor");
  addMesh(w, assets, makeQuad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}), white, {}, false, "ceiling");
  addMesh(w, assets, makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}), white, {}, false, "back_wall");
  addMesh(w, assets, makeQuad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}), red, {}, false, "left_wall_red");
  addMesh(w, assets, makeQuad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}), green, {}, false, "right_wall_green");

  Transform shortBox;
  shortBox.translation = {0.35f, 0.3f, 0.3f};
  shortBox.rotation = glm::angleAxis(glm::radians(-17.0f), glm::vec3(0, 1, 0));
  Entity shortE = addMesh(w, assets, makeBox({0.3f, 0.3f, 0.3f}), white, shortBox, dynamic, "short_box");
  Transform tallBox;
  tallBox.translation = {-0.35f, 0.6f, -0.35f};
  tallBox.rotation = glm::angleAxis(glm::radians(17.0f), glm::vec3(0, 1, 0));
  Entity tallE = addMesh(w, assets, makeBox({0.3f, 0.6f, 0.3f}), white, tallBox, dynamic, "tall_box");

  Entity spot = w.create();
  Transform st;
  st.translation = {0.0f, CornellLayout::kSpotHeight, 0.0f};
  st.rotation = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));  // local -Z -> world -Y
  w.add(spot, st);
  w.add(spot, WorldTransform{st.matrix()});
  Light light;
  light.type = LightType::Spot;
  light.color = {1.0f, 1.0f, 1.0f};
  light.intensity = CornellLayout::kSpotIntensity;
  light.outerConeAngle = glm::radians(CornellLayout::kSpotOuterDeg);
  light.innerConeAngle = glm::radians(CornellLayout::kSpotInnerDeg);
  w.add(spot, light);
  w.add(spot, Name{"spot"});

  if (dynamic) {
    ScriptedMotion lightPath;
    lightPath.origin = st.translation;
    lightPath.baseRotation = st.rotation;
    lightPath.orbitRadius = 0.35f;
    lightPath.orbitSpeed = 0.9f;
    lightPath.phase = 3.14159265f / 0.9f;  // start on the camera side of the room (z > 0)
    w.add(spot, lightPath);
    ScriptedMotion slide;
    slide.origin = shortBox.translation;
    slide.baseRotation = shortBox.rotation;
    slide.oscillation = {0.0f, 0.0f, 0.25f};
    slide.oscillationHz = 0.2f;
    w.add(shortE, slide);
    ScriptedMotion spin;
    spin.origin = tallBox.translation;
    spin.baseRotation = tallBox.rotation;
    spin.spinSpeed = 0.6f;
    w.add(tallE, spin);
  }

  Entity cam = w.create();
  Transform ct;
  ct.translation = {0.0f, 1.0f, 3.9f};
  w.add(cam, ct);
  w.add(cam, WorldTransform{ct.matrix()});
  w.add(cam, Camera{.yfov = glm::radians(40.0f), .znear = 0.05f, .zfar = 50.0f});
  w.add(cam, ActiveCamera{});
  w.add(cam, Name{"camera"});
}

bool addDefaultLightIfUnlit(ecs::World& w) {
  if (w.count<Light>() > 0) return false;
  bool emissive = false;
  w.each<Material>([&](Entity, const Material& m) { emissive |= glm::dot(m.emissive, m.emissive) > 0.0f; });
  if (emissive) return false;
  Entity sun = w.create();
  Transform t;
  // Light travels along local -Z: tilt it to come down from above, front-left.
  t.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(0.35f, -1.0f, -0.45f)), glm::vec3(0, 1, 0));
  w.add(sun, t);
  w.add(sun, WorldTransform{t.matrix()});
  Light l;
  l.type = LightType::Directional;
  l.intensity = 3.0f;
  w.add(sun, l);
  w.add(sun, Name{"default_sun"});
  return true;
}

}  // namespace dyngi::sample
