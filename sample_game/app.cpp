#include "dyngi/engine/platform/files.h"
#include "app.h"

#include <cstdio>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "outputs.h"
#include "play/input.h"
#include "runs.h"
#include "scene_loading.h"

namespace dyngi::sample {

int runApp(const Options& o) {
  if (!o.inputScript.empty()) {  // a bad script is bad input: refused before anything runs
    std::string error;
    if (!InputScript::load(o.inputScript, &error)) {
      std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(error, 1000).c_str());
      return 2;
    }
  }
  ecs::World world;
  scene::AssetStore assets;
  if (int status = loadScene(o, world, assets); status != 0) return status;
  RunStats stats;
  stats.scene = sceneLabel(o);
  stats.gi = o.gi;
  int status = 0;
  if (o.gi == "path" && o.headless) {
    status = runPathTracer(o, world, assets, stats);
  } else {  // --gi path in a window: the progressive preview (runRealtime falls back to the above headless)
    status = runRealtime(o, world, assets, stats);
  }
  // The stats and the table come after the images, and before a validation-error exit (their order on
  // stdout as before the split).
  return status | writeStats(o, stats);
}

}  // namespace dyngi::sample
