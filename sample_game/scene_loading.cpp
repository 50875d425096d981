#include "dyngi/engine/platform/files.h"
#include "scene_loading.h"

#include <cstdio>

#include "dyngi/engine/scene/gltf_import.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

std::string sceneLabel(const Options& o) { return o.animate.empty() ? o.scene : "animate:" + o.animate; }

int loadScene(const Options& o, ecs::World& world, scene::AssetStore& assets) {
  if (!o.animate.empty()) {
    std::string err = buildAnimatedScene(o.animate, world, assets, DYNGI_SHARED_SCENES_DEFAULT);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_sample: --animate %s: %s\n", platform::oneLine(o.animate).c_str(), platform::oneLine(err, 1000).c_str());
      return 2;
    }
  } else if (isBuiltinScene(o.scene)) {
    buildBuiltinScene(o.scene, world, assets);
  } else {
    scene::ImportReport report;
    scene::ImportOptions io;
    io.clip = o.clip;
    std::string err = scene::importGltf(o.scene, world, assets, &report, io);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(err, 1000).c_str());
      return 2;
    }
    if (report.missingClip) {
      std::string names;
      for (auto& c : report.clips) names += (names.empty() ? "" : ", ") + c;
      std::fprintf(stderr, "dyngi_sample: %s: no animation clip '%s' (available: %s)\n", platform::oneLine(o.scene).c_str(), platform::oneLine(o.clip).c_str(),
                   names.empty() ? "none" : names.c_str());
      return 2;
    }
    if (!report.ignoredExtensions.empty()) {
      std::string names;
      for (auto& e : report.ignoredExtensions) names += (names.empty() ? "" : ", ") + e;
      std::fprintf(stderr, "dyngi_sample: note: %s uses glTF extensions dyngi ignores (optional in the file): %s\n", o.scene.c_str(),
                   names.c_str());
    }
    for (const std::string& note : report.notes) std::fprintf(stderr, "dyngi_sample: note: %s: %s\n", o.scene.c_str(), note.c_str());
    if (addDefaultLightIfUnlit(world))
      std::fprintf(stderr, "dyngi_sample: note: %s has no lights and no emissive surfaces; added a default directional light\n",
                   o.scene.c_str());
    else if (report.lights == 0)
      std::fprintf(stderr, "dyngi_sample: note: %s has no punctual lights; its light comes from emissive surfaces only\n",
                   o.scene.c_str());
  }

  return 0;
}

}  // namespace dyngi::sample
