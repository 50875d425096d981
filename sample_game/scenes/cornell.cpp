#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <unordered_set>

#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

using namespace scene;

namespace {
// The Cornell box's spot: its power and cone (CornellLayout), in a colour.
Light cornellSpot(glm::vec3 color) {
  Light light;
  light.type = LightType::Spot;
  light.color = color;
  light.intensity = CornellLayout::kSpotIntensity;
  light.outerConeAngle = glm::radians(CornellLayout::kSpotOuterDeg);
  light.innerConeAngle = glm::radians(CornellLayout::kSpotInnerDeg);
  return light;
}

void addCornellCamera(ecs::World& w) {
  Entity cam = w.create();
  Transform ct;
  ct.translation = {0.0f, 1.0f, 3.9f};
  w.add(cam, ct);
  w.add(cam, WorldTransform{ct.matrix()});
  w.add(cam, Camera{.yfov = glm::radians(40.0f), .znear = 0.05f, .zfar = 50.0f});
  w.add(cam, ActiveCamera{});
  w.add(cam, Name{"camera"});
}
}  // namespace

const std::vector<std::string>& builtinSceneNames() {
  static const std::vector<std::string> names = {"cornell", "cornell-dynamic", "cornell-emissive", "showcase", "two-rooms",
                                                 "two-rooms-door",  "street",          "street-near"};
  return names;
}

const std::vector<std::string>& animatedSceneNames() {
  static const std::vector<std::string> names = {"static",      "moving-spot",  "rotating-object",  "moving-camera",
                                                 "walking-fox", "fox-and-spot", "fox-spot-light-on", "street-flight"};
  return names;
}

bool isBuiltinScene(const std::string& name) {
  const std::vector<std::string>& names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Entity addSceneMesh(ecs::World& w, AssetStore& assets, MeshData mesh, const glm::vec3& albedo, const Transform& t, bool dynamic,
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

void buildBuiltinScene(const std::string& name, ecs::World& w, AssetStore& assets) {
  if (name == "two-rooms" || name == "two-rooms-door") return buildTwoRooms(name == "two-rooms-door", w, assets);
  if (name == "street" || name == "street-near") return buildStreet(name == "street-near", w, assets);
  const bool dynamic = name == "cornell-dynamic" || name == "showcase";
  const glm::vec3 white(CornellLayout::kWhite), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
  // Walls: quads whose normal (U x V) faces into the room.
  addSceneMesh(w, assets, makeQuad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}), white, {}, false, "floor");
  addSceneMesh(w, assets, makeQuad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}), white, {}, false, "ceiling");
  addSceneMesh(w, assets, makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}), white, {}, false, "back_wall");
  addSceneMesh(w, assets, makeQuad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}), red, {}, false, "left_wall_red");
  addSceneMesh(w, assets, makeQuad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}), green, {}, false, "right_wall_green");

  Transform shortBox;
  shortBox.translation = {0.35f, 0.3f, 0.3f};
  shortBox.rotation = glm::angleAxis(glm::radians(-17.0f), glm::vec3(0, 1, 0));
  Entity shortE = addSceneMesh(w, assets, makeBox({0.3f, 0.3f, 0.3f}), white, shortBox, dynamic, "short_box");
  Transform tallBox;
  tallBox.translation = {-0.35f, 0.6f, -0.35f};
  tallBox.rotation = glm::angleAxis(glm::radians(17.0f), glm::vec3(0, 1, 0));
  Entity tallE = addSceneMesh(w, assets, makeBox({0.3f, 0.6f, 0.3f}), white, tallBox, dynamic, "tall_box");

  if (name == "cornell-emissive") {
    // The only light: an emissive quad just under the ceiling (black, so it reflects nothing).
    const float h = CornellLayout::kEmitterHalfSize;
    Entity lamp = addSceneMesh(w, assets, makeQuad({-h, CornellLayout::kEmitterHeight, -h}, {2 * h, 0, 0}, {0, 0, 2 * h}),
                               glm::vec3(0.0f), {}, false, "ceiling_lamp");
    w.write<Material>(lamp).emissive = glm::vec3(CornellLayout::kEmitterRadiance);
    addCornellCamera(w);
    return;
  }

  Entity spot = w.create();
  Transform st;
  st.translation = {0.0f, CornellLayout::kSpotHeight, 0.0f};
  st.rotation = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));  // local -Z -> world -Y
  w.add(spot, st);
  w.add(spot, WorldTransform{st.matrix()});
  w.add(spot, cornellSpot({1.0f, 1.0f, 1.0f}));
  w.add(spot, Name{"spot"});

  if (name == "showcase") {
    // An uplight at the front of the room, sliding from side to side: it lights the ceiling and little
    // else directly, so most of what the room shows is bounce light, red and green included.
    Transform& up = w.write<Transform>(spot);
    up.translation = ShowcaseLayout::kUplight;
    up.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(1, 0, 0));  // local -Z -> world +Y
    w.write<Light>(spot).intensity = ShowcaseLayout::kUplightIntensity;
    w.write<Light>(spot).outerConeAngle = glm::radians(ShowcaseLayout::kUplightOuterDeg);
    w.write<Light>(spot).innerConeAngle = glm::radians(ShowcaseLayout::kUplightInnerDeg);
    ScriptedMotion sway;
    sway.origin = up.translation;
    sway.baseRotation = up.rotation;
    sway.oscillation = {ShowcaseLayout::kUplightSway, 0.0f, 0.0f};
    sway.oscillationHz = 0.15f;
    w.add(spot, sway);
  } else if (dynamic) {
    ScriptedMotion lightPath;
    lightPath.origin = st.translation;
    lightPath.baseRotation = st.rotation;
    lightPath.orbitRadius = 0.35f;
    lightPath.orbitSpeed = 0.9f;
    lightPath.phase = 3.14159265f / 0.9f;  // start on the camera side of the room (z > 0)
    w.add(spot, lightPath);
  }
  if (dynamic) {
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

  addCornellCamera(w);
}

namespace {
// Every entity with component C oscillates about where it stands (amplitude in world units, in Hz).
template <class C>
void oscillateAll(ecs::World& w, glm::vec3 amplitude, float hz) {
  w.each<C, Transform>([&](Entity e, const C&, const Transform& t) {
    ScriptedMotion m;
    m.origin = t.translation;
    m.baseRotation = t.rotation;
    m.oscillation = amplitude;
    m.oscillationHz = hz;
    w.commands().add(e, m);
  });
  w.flushCommands();
}
}  // namespace

namespace {
// Adds scripted scene `name`'s motion and extras to a Cornell box already in `w` (scenes build on each
// other: each builds the box once, in buildAnimatedScene).
std::string addAnimation(const std::string& name, ecs::World& w, AssetStore& assets, const std::string& sharedScenesDir) {
  if (name == "static") return {};
  if (name == "moving-spot") {
    oscillateAll<Light>(w, {0.6f, 0.0f, 0.0f}, 0.25f);
    return {};
  }
  if (name == "moving-camera") {
    // A camera strafing sideways (a player walking past): every pixel moves every frame, so the temporal
    // technique reprojects every set for every pixel.
    oscillateAll<ActiveCamera>(w, {0.3f, 0.0f, 0.0f}, 0.25f);
    return {};
  }
  if (name == "rotating-object") {
    Entity pivot = w.create();
    Transform pt;
    pt.translation = {0.1f, 1.05f, 0.25f};
    w.add(pivot, pt);
    ScriptedMotion spin;
    spin.origin = pt.translation;
    spin.spinAxis = {0.3f, 1.0f, 0.2f};
    spin.spinSpeed = 1.2f;
    w.add(pivot, spin);
    w.add(pivot, Name{"rotating_object"});
    const glm::vec3 colours[2] = {{0.8f, 0.1f, 0.1f}, {0.1f, 0.2f, 0.85f}};
    for (int i = 0; i < 2; ++i) {
      Transform ht;
      ht.translation = {i == 0 ? -0.13f : 0.13f, 0.0f, 0.0f};
      ht.parent = pivot;
      addSceneMesh(w, assets, makeBox({0.13f, 0.2f, 0.2f}), colours[i], ht, true, i == 0 ? "rotating_red" : "rotating_blue");
    }
    return {};
  }
  if (name == "fox-and-spot") {  // the soak scene: a skinned mesh deforming and a light moving, both at once
    std::string err = addAnimation("walking-fox", w, assets, sharedScenesDir);
    if (!err.empty()) return err;
    oscillateAll<Light>(w, {0.6f, 0.0f, 0.0f}, 0.25f);
    return {};
  }
  if (name == "fox-spot-light-on") {  // the GI budget's load change: fox-and-spot, then a second spot at 4 s
    std::string err = addAnimation("fox-and-spot", w, assets, sharedScenesDir);
    if (!err.empty()) return err;
    Entity second = w.create();
    Transform t;
    t.translation = {-0.5f, CornellLayout::kSpotHeight, 0.4f};
    t.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f)), glm::vec3(0, 1, 0));
    w.add(second, t);
    Light light = cornellSpot({1.0f, 0.85f, 0.6f});
    light.enabled = false;
    w.add(second, light);
    w.add(second, ScriptedLightSwitch{kSecondLightOnAt});
    w.add(second, Name{"second_spot"});
    return {};
  }
  if (name == "walking-fox") {
    std::string path = sharedScenesDir + "/Fox.glb";
    std::vector<Entity> existing;
    w.each<Transform>([&](Entity e, const Transform&) { existing.push_back(e); });
    ImportOptions io;
    io.clip = "Walk";
    io.markStatic = false;
    std::string err = importGltf(path, w, assets, nullptr, io);
    if (!err.empty()) return err;
    // Put the fox's roots under a pivot that scales it to the room (~1 m long) and walks it in a circle.
    Entity pivot = w.create();
    Transform pt;
    pt.scale = glm::vec3(0.0065f);
    w.add(pivot, pt);
    ScriptedMotion circle;
    circle.orbitRadius = 0.45f;
    circle.orbitSpeed = 0.5f;
    circle.spinSpeed = 0.5f;
    w.add(pivot, circle);
    w.add(pivot, Name{"fox_pivot"});
    std::unordered_set<Entity> old(existing.begin(), existing.end());
    std::vector<Entity> roots;
    w.each<Transform>([&](Entity e, const Transform& t) {
      if (!old.count(e) && e != pivot && t.parent.isNull()) roots.push_back(e);
    });
    for (Entity e : roots) w.write<Transform>(e).parent = pivot;
    // The boxes would be in its way.
    std::vector<Entity> boxes;
    w.each<Name>([&](Entity e, const Name& n) {
      if (n.value == "short_box" || n.value == "tall_box") boxes.push_back(e);
    });
    for (Entity e : boxes) w.destroy(e);
    return {};
  }
  return "unknown animated scene '" + name + "'";
}
}  // namespace

std::string buildAnimatedScene(const std::string& name, ecs::World& w, AssetStore& assets, const std::string& sharedScenesDir) {
  if (name == "street-flight") {
    buildStreet(false, w, assets);
    addStreetFlight(w);
    return {};
  }
  buildBuiltinScene("cornell", w, assets);
  return addAnimation(name, w, assets, sharedScenesDir);
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
