#pragma once
// CI=true: CI lays ../shared/scenes beside the clone and scripts/setup.sh installs every program a test
// needs, so a test that would skip on a developer's machine fails there instead.
#include <cstdlib>
#include <string>

namespace dyngi::test {

inline bool runningInCi() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

}  // namespace dyngi::test
