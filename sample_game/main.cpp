// dyngi_sample: renders a scene with the dyngi engine, windowed or headless.
#include <cstdio>
#include <exception>

#include "app.h"
#include "options.h"

int main(int argc, char** argv) {
  std::string error;
  auto options = dyngi::sample::parseOptions(argc, argv, error);
  if (!options) {
    std::fprintf(stderr, "dyngi_sample: %s\n", error.c_str());
    return 2;
  }
  if (options->help) {
    std::printf("%s", dyngi::sample::usage().c_str());
    return 0;
  }
  try {
    return dyngi::sample::runApp(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dyngi_sample: error: %s\n", e.what());
    return 1;
  }
}
