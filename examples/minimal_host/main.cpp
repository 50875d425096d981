// The smallest host of dyngi: loads a glTF, adds the GI system to its ECS, renders N frames headless and
// writes the last one to a PNG. It builds against the installed package (find_package(dyngi)), as your
// engine would; docs/INTEGRATION.md explains each step.
//
//   minimal_host SCENE.gltf OUT.png [FRAMES=16] [TECHNIQUE=temporal]    (exit 2 on bad input)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/context.h"
#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/gi_system.h"

using namespace dyngi;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: minimal_host SCENE.gltf OUT.png [FRAMES=16] [TECHNIQUE=temporal]\n");
    return 2;
  }
  const std::string scenePath = argv[1], outPath = argv[2];
  const int frames = argc > 3 ? std::atoi(argv[3]) : 16;
  if (frames < 1 || frames > 100000) {
    std::fprintf(stderr, "minimal_host: FRAMES must be 1..100000\n");
    return 2;
  }
  gi::GiSettings settings;  // every default lives in its options struct
  if (argc > 4) settings.technique = argv[4];
  if (!gi::findTechnique(settings.technique)) {
    std::string names;
    for (const gi::TechniqueEntry& t : gi::techniqueRegistry()) names += std::string(names.empty() ? "" : ", ") + t.name;
    std::fprintf(stderr, "minimal_host: no GI technique '%s' (there are: %s)\n", settings.technique.c_str(), names.c_str());
    return 2;
  }
  constexpr uint32_t kWidth = 512, kHeight = 512;

  // 1. The scene: the host's world and assets (here from a glTF).
  ecs::World world;
  scene::AssetStore assets;
  if (std::string err = scene::importGltf(scenePath, world, assets); !err.empty()) {
    std::fprintf(stderr, "minimal_host: %s\n", err.c_str());
    return 2;
  }
  try {
    // 2. The device and the renderer (headless: no window, no swapchain).
    render::VulkanContext vulkan(render::ContextOptions{});
    render::Renderer renderer(vulkan);
    if (!renderer.resize(kWidth, kHeight)) return 2;

    // 3. The GI: one ECS system whose render features the renderer runs each frame.
    auto gi = std::make_unique<gi::GiSystem>(vulkan, assets, settings);
    gi->attach(renderer);
    ecs::Scheduler scheduler;
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
    scheduler.add(ecs::Phase::PostUpdate, std::move(gi));  // after the transforms it reads

    // 4. The frame loop: the systems, one snapshot of the world, the renderer.
    for (int frame = 0; frame < frames; ++frame) {
      const uint64_t f = uint64_t(frame);
      scheduler.runFrame(world, ecs::FrameTime{1.0 / 60.0, double(frame) / 60.0, f});
      renderer.render(render::extractSnapshot(world, assets, f));
    }

    // 5. The image.
    if (std::string err = render::writePng(outPath, kWidth, kHeight, renderer.readbackLdr()); !err.empty()) {
      std::fprintf(stderr, "minimal_host: %s\n", err.c_str());
      return 1;
    }
  } catch (const std::exception& e) {  // no Vulkan device, out of device memory, ...
    std::fprintf(stderr, "minimal_host: %s\n", e.what());
    return 1;
  }
  std::printf("minimal_host: wrote %s (%d frames, %ux%u)\n", outPath.c_str(), frames, kWidth, kHeight);
  return 0;
}
