#pragma once
// Where directional lights put their VPLs (both VPL techniques). A sun's VPLs are spread over a disc
// across its direction that covers what it lights: over a whole 400 m street that is a few VPLs per
// block, and the camera's surroundings get a handful. When the scene is wider than
// VplOptions::directionalReach (a radius, in metres), the disc covers only the sphere of that radius
// around a focus near the camera instead: the camera's position snapped to a grid of half the reach, so
// the focus moves in steps (for the temporal paths, as if the light had moved: its paths are reshot) and holds
// still while the camera moves within a cell. Past the focus, surfaces get no light from the sun's VPLs.
// A camera outside the scene's bounds (an object framed from afar) keeps the whole scene.
#include <glm/glm.hpp>

#include "dyngi/engine/render/snapshot.h"

namespace dyngi::gi {

struct DirectionalFocus {
  // What lightPower() and render::lightViews() take for a directional light: the scene's bounds, or a
  // cube around the focus whose circumscribed sphere is the focus sphere.
  scene::Aabb bounds;
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
  bool wholeScene = true;  // the scene fits within the reach (every room): its bounds, as without a focus
};

DirectionalFocus directionalFocus(const render::RenderSnapshot& snapshot, float reach);

}  // namespace dyngi::gi
