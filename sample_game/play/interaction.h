#pragma once
// Playing with the scene: click to select an object or a light, drag to move it on the horizontal plane
// through the point grabbed, keys to turn, scale, add and remove things and to pause scripted motion.
// Every change is a component write through the ECS, so the GI sees it exactly as it sees a game's.
//
//   left click       select what is under the cursor (a light: within 14 px of where it is)
//   left drag        move the selection (its scripted motion, if any, stops)
//   R / shift+R      turn the selection 15 degrees about the vertical
//   = / -            scale the selection (a light: its intensity) up / down by 10 percent
//   B                drop a 0.2 m box onto the surface under the cursor
//   L                drop a point light 0.4 m above the surface under the cursor
//   DELETE           remove the selection
//   P                pause / resume scripted motion and animation
#include <string>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/assets.h"
#include "play/input.h"

namespace dyngi::sample {

struct PlayState {
  ecs::Entity selected{};
  bool paused = false;
  std::string lastAction;  // one line for the panel and the stats ("selected short_box", ...)
  int added = 0;           // boxes and lights dropped so far (their names)
};

class SceneInteraction {
 public:
  // `camera`: the last frame's, whose image the user clicked on; width x height: that image's size.
  void update(const InputFrame& input, bool uiHasMouse, ecs::World& world, scene::AssetStore& assets, const render::CameraView& camera,
              uint32_t width, uint32_t height, PlayState& play);

 private:
  bool dragging_ = false;
  float dragPlaneY_ = 0;
  glm::vec3 dragLast_{0.0f};
};

std::string entityLabel(const ecs::World& world, ecs::Entity e);

}  // namespace dyngi::sample
