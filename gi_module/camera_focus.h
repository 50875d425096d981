#pragma once
// The part of a wide world the GI looks after: the camera's surroundings. In a scene wider than a
// reach (a radius, in metres), a cube around a focus near the camera, its circumscribed sphere of that
// radius; the focus is the camera's position snapped to a grid (half the reach, or a step the caller
// gives), so it moves in steps and holds still while the camera moves within a cell. A camera outside the scene's bounds (an object
// framed from afar) and a scene within the reach keep the whole scene. Two users:
//  - directional lights' VPLs (VplOptions::directionalReach): a sun's VPLs over a 400 m street would
//    leave the camera's surroundings a handful, so they are shot over the focus only (for the temporal
//    paths a focus step is as if the light had moved: its paths are reshot); surfaces past it get no
//    light from the sun's VPLs;
//  - the voxel volume (VoxelSettings::reach): the cube around the focus instead of the scene's bounds,
//    so a voxel stays the size of a room's detail, on a grid of an eighth of the reach
//    (VoxelScene::kWindowStep); what lies outside is not voxelized.
#include <glm/glm.hpp>

#include "dyngi/engine/render/snapshot.h"

namespace dyngi::gi {

struct CameraFocus {
  // What lightPower() and render::lightViews() take for a directional light: the scene's bounds, or a
  // cube around the focus whose circumscribed sphere is the focus sphere.
  scene::Aabb bounds;
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
  bool wholeScene = true;  // the scene fits within the reach (every room): its bounds, as without a focus
};

// `step`: the grid the focus snaps to (0: half the reach).
CameraFocus cameraFocus(const render::RenderSnapshot& snapshot, float reach, float step = 0.0f);

}  // namespace dyngi::gi
