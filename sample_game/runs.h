#pragma once
// The sample's two kinds of run, on a loaded scene. Each fills `stats` and returns the exit status of
// what it wrote (0 or 1); runApp writes the stats.
#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "options.h"
#include "stats.h"

namespace dyngi::sample {

// --gi path: advance the scene `frames` frames (the BVH follows incrementally), then path-trace the
// last frame on the CPU. Needs no Vulkan device.
int runPathTracer(const Options& o, ecs::World& world, scene::AssetStore& assets, RunStats& stats);
// Everything else: the renderer with the chosen GI, windowed or headless, frame by frame.
int runRealtime(const Options& o, ecs::World& world, scene::AssetStore& assets, RunStats& stats);

}  // namespace dyngi::sample
