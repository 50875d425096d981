#pragma once
// An Xvfb server for a test's window, and the skip-or-fail rule for programs a test needs.
#include <string>

#include "support/ci.h"
#include "support/temp_dir.h"

namespace dyngi::test {

// An Xvfb server on a free display for the test's lifetime. Xvfb picks the display itself (-displayfd)
// and writes its number once it accepts connections, so two tests starting at once never share one.
class VirtualDisplay {
 public:
  VirtualDisplay();
  ~VirtualDisplay();
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;
  const std::string& display() const { return display_; }  // ":N", or empty when Xvfb did not start

 private:
  TempDir dir_;
  int pid_ = 0;
  std::string display_;
};

bool haveProgram(const char* name);

}  // namespace dyngi::test

// In a test body: skips without `program`, except under CI=true, where scripts/setup.sh installs it.
#define DYNGI_REQUIRE_PROGRAM(program)                                                                                  \
  if (!::dyngi::test::haveProgram(program)) {                                                                            \
    if (::dyngi::test::runningInCi()) FAIL() << "CI=true but " << program << " is missing (scripts/setup.sh installs it)"; \
    GTEST_SKIP() << "no " << program;                                                                                  \
  }
