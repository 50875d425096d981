#pragma once
// The run's scene: a built-in one, an --animate benchmark scene or a glTF file, with the notes a user
// needs (no lights, missing clip). Returns the exit status: 0, or 2 after one error line.
#include <string>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "options.h"

namespace dyngi::sample {

int loadScene(const Options& o, ecs::World& world, scene::AssetStore& assets);
// The name the stats give the scene.
std::string sceneLabel(const Options& o);

}  // namespace dyngi::sample
