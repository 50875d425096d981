// dyngi_sample: renders a scene with the dyngi engine, windowed or headless.
#include <cstdio>
#include <exception>

#include "dyngi/engine/platform/files.h"
#include "app.h"
#include "dyngi/engine/render/vk_common.h"
#include "options.h"

int main(int argc, char** argv) {
  std::string error;
  auto options = dyngi::sample::parseOptions(argc, argv, error);
  if (!options) {
    std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(error, 1000).c_str());
    return 2;
  }
  if (options->help || options->helpMarkdown) {
    std::printf("%s", options->help ? dyngi::sample::usage().c_str() : dyngi::sample::usageMarkdown().c_str());
    return 0;
  }
  if (std::string bad = dyngi::sample::checkOutputPaths(*options); !bad.empty()) {
    std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(bad, 1000).c_str());
    return 2;
  }
  try {
    return dyngi::sample::runApp(*options);
  } catch (const dyngi::render::DeviceMemoryError& e) {  // the settings ask for more than the device holds
    std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(e.what(), 1000).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dyngi_sample: error: %s\n", dyngi::platform::oneLine(e.what(), 1000).c_str());
    return 1;
  }
}
