#pragma once
// Third-party test scenes live beside the project in ../shared/scenes (never copied in). A test that
// needs one skips on a machine without them, except under CI (CI=true), where the directory is always
// laid beside the clone: there a missing scene fails the test, so CI never passes by skipping.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/ci.h"

namespace dyngi::test {

// The scene's path, or "" when it is absent.
inline std::string sharedScenePath(const char* name) {
  std::string p = std::string(DYNGI_SHARED_SCENES) + "/" + name;
  return std::filesystem::exists(p) ? p : std::string();
}

}  // namespace dyngi::test

// In a test body: `path` = the scene's path, or the test skips (fails under CI=true).
#define DYNGI_SHARED_SCENE_OR_SKIP(path, name)                                                                   \
  const std::string path = ::dyngi::test::sharedScenePath(name);                                                 \
  if (path.empty()) {                                                                                            \
    if (::dyngi::test::runningInCi()) FAIL() << "CI=true but " << name << " is missing from " << DYNGI_SHARED_SCENES; \
    GTEST_SKIP() << name << " absent (" << DYNGI_SHARED_SCENES << ")";                                          \
  }
