#include "play/interaction.h"

#include <GLFW/glfw3.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/render/frame_uniforms.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/picking.h"
#include "dyngi/engine/scene/scripted_motion.h"

namespace dyngi::sample {
namespace {

constexpr float kLightPickPixels = 14.0f;
constexpr float kTurnDegrees = 15.0f;
constexpr float kScaleStep = 1.1f;

// Where the ray meets the horizontal plane y = height, if ahead of it.
std::optional<glm::vec3> onPlane(const scene::Ray& r, float height) {
  if (std::abs(r.direction.y) < 1e-6f) return std::nullopt;
  const float t = (height - r.origin.y) / r.direction.y;
  if (!(t > 0.0f) || t > 1e4f) return std::nullopt;
  return r.origin + t * r.direction;
}

// A light near the cursor (screen distance), nearer to the camera than `maxDistance`.
ecs::Entity lightUnderCursor(const ecs::World& world, const glm::mat4& viewProj, const glm::vec3& eye, glm::dvec2 mouse, uint32_t width,
                             uint32_t height, float maxDistance) {
  ecs::Entity best{};
  float bestPixels = kLightPickPixels;
  world.each<scene::Light, scene::WorldTransform>([&](ecs::Entity e, const scene::Light& l, const scene::WorldTransform& wt) {
    if (l.type == scene::LightType::Directional) return;  // no position to click on
    const glm::vec3 p(wt.matrix[3]);
    const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    if (clip.w <= 0.0f || glm::length(p - eye) > maxDistance) return;
    const glm::vec2 px((clip.x / clip.w * 0.5f + 0.5f) * float(width), (clip.y / clip.w * 0.5f + 0.5f) * float(height));
    const float d = glm::length(px - glm::vec2(mouse));
    if (d < bestPixels) bestPixels = d, best = e;
  });
  return best;
}

ecs::Entity addBox(ecs::World& world, scene::AssetStore& assets, glm::vec3 at, int index) {
  constexpr float kHalf = 0.1f;
  const ecs::Entity e = world.create();
  scene::Transform t;
  t.translation = at + glm::vec3(0.0f, kHalf, 0.0f);
  world.add(e, t);
  world.add(e, scene::WorldTransform{t.matrix()});
  scene::MeshData mesh = scene::makeBox(glm::vec3(kHalf));
  mesh.name = "box_" + std::to_string(index);
  world.add(e, scene::MeshInstance{assets.addMesh(std::move(mesh)), true});
  // A colour of its own, so its bleeding shows: a turn of the hue wheel per box.
  const float h = std::fmod(0.13f + 0.38f * float(index), 1.0f) * 6.0f;
  const glm::vec3 hue = glm::clamp(glm::vec3(std::abs(h - 3.0f) - 1.0f, 2.0f - std::abs(h - 2.0f), 2.0f - std::abs(h - 4.0f)), 0.0f, 1.0f);
  scene::Material m;
  m.baseColor = glm::vec4(0.15f + 0.7f * hue, 1.0f);
  world.add(e, m);
  world.add(e, scene::Name{"box_" + std::to_string(index)});
  world.add(e, scene::DynamicTag{});
  return e;
}

ecs::Entity addPointLight(ecs::World& world, glm::vec3 at, int index) {
  const ecs::Entity e = world.create();
  scene::Transform t;
  t.translation = at + glm::vec3(0.0f, 0.4f, 0.0f);
  world.add(e, t);
  world.add(e, scene::WorldTransform{t.matrix()});
  scene::Light l;
  l.type = scene::LightType::Point;
  l.color = {1.0f, 0.85f, 0.6f};
  l.intensity = 1.5f;
  world.add(e, l);
  world.add(e, scene::Name{"light_" + std::to_string(index)});
  return e;
}

}  // namespace

std::string entityLabel(const ecs::World& world, ecs::Entity e) {
  if (e.isNull() || !world.alive(e)) return "nothing";
  if (const scene::Name* n = world.tryGet<scene::Name>(e); n && !n->value.empty()) return n->value;
  return "entity " + std::to_string(e.index);
}

void SceneInteraction::update(const InputFrame& in, bool uiHasMouse, ecs::World& world, scene::AssetStore& assets,
                              const render::CameraView& camera, uint32_t width, uint32_t height, PlayState& play) {
  if (!play.selected.isNull() && !world.alive(play.selected)) play.selected = {};
  if (in.keyPressed(GLFW_KEY_P)) {
    play.paused = !play.paused;
    play.lastAction = play.paused ? "paused" : "resumed";
  }
  if (width == 0 || height == 0) return;
  const glm::mat4 viewProj = render::cameraUniforms(camera, width, height).viewProj;
  const bool haveCursor = in.mouse.x >= 0 && in.mouse.y >= 0 && in.mouse.x < width && in.mouse.y < height;
  const scene::Ray ray = scene::pixelRay(viewProj, width, height, in.mouse.x, in.mouse.y);

  // Select (and start a drag) on a press over the scene.
  if (in.pressed[kLeft] && !uiHasMouse && haveCursor) {
    const auto hit = scene::pickClosest(world, assets, ray);
    const ecs::Entity light = lightUnderCursor(world, viewProj, camera.position, in.mouse, width, height, hit ? hit->distance + 0.5f : 1e30f);
    play.selected = !light.isNull() ? light : hit ? hit->entity : ecs::Entity{};
    play.lastAction = "selected " + entityLabel(world, play.selected);
    dragging_ = false;
    if (!play.selected.isNull() && world.has<scene::Transform>(play.selected)) {
      dragPlaneY_ = !light.isNull() ? world.get<scene::Transform>(light).translation.y : hit->position.y;
      if (auto p = onPlane(ray, dragPlaneY_)) dragging_ = true, dragLast_ = *p;
    }
  }
  if (!in.down[kLeft]) dragging_ = false;
  if (dragging_ && haveCursor && !play.selected.isNull() && (in.mouseDelta.x != 0.0 || in.mouseDelta.y != 0.0)) {
    if (auto p = onPlane(ray, dragPlaneY_)) {
      // The user places it now: scripted motion would put it back.
      if (world.has<scene::ScriptedMotion>(play.selected)) world.remove<scene::ScriptedMotion>(play.selected);
      world.write<scene::Transform>(play.selected).translation += *p - dragLast_;
      dragLast_ = *p;
      play.lastAction = "moved " + entityLabel(world, play.selected);
    }
  }

  const ecs::Entity sel = play.selected;
  const bool shift = in.keyDown(GLFW_KEY_LEFT_SHIFT) || in.keyDown(GLFW_KEY_RIGHT_SHIFT);
  if (!sel.isNull() && world.has<scene::Transform>(sel)) {
    if (in.keyPressed(GLFW_KEY_R)) {
      if (world.has<scene::ScriptedMotion>(sel)) world.remove<scene::ScriptedMotion>(sel);
      scene::Transform& t = world.write<scene::Transform>(sel);
      t.rotation = glm::angleAxis(glm::radians(shift ? -kTurnDegrees : kTurnDegrees), glm::vec3(0, 1, 0)) * t.rotation;
      play.lastAction = "turned " + entityLabel(world, sel);
    }
    const float factor = in.keyPressed(GLFW_KEY_EQUAL) ? kScaleStep : in.keyPressed(GLFW_KEY_MINUS) ? 1.0f / kScaleStep : 1.0f;
    if (factor != 1.0f) {
      if (world.has<scene::Light>(sel)) {
        scene::Light& l = world.write<scene::Light>(sel);
        l.intensity = std::min(l.intensity * factor, scene::kMaxLightIntensity);
      }
      else world.write<scene::Transform>(sel).scale *= factor;
      play.lastAction = "scaled " + entityLabel(world, sel);
    }
    if (in.keyPressed(GLFW_KEY_DELETE)) {
      play.lastAction = "removed " + entityLabel(world, sel);
      world.destroy(sel);
      play.selected = {};
    }
  }
  if ((in.keyPressed(GLFW_KEY_B) || in.keyPressed(GLFW_KEY_L)) && haveCursor) {
    if (const auto hit = scene::pickClosest(world, assets, ray)) {
      const int index = ++play.added;
      play.selected = in.keyPressed(GLFW_KEY_B) ? addBox(world, assets, hit->position, index) : addPointLight(world, hit->position, index);
      play.lastAction = "added " + entityLabel(world, play.selected);
    }
  }
}

}  // namespace dyngi::sample
