#pragma once
// Runs the real sample binary (DYNGI_SAMPLE_EXE) with arguments and collects its exit code and stderr.
#include <string>

#include "support/temp_dir.h"

namespace dyngi::test {

struct SampleRun {
  int exitCode = -1;   // 128 + signal when it died of one; 124 when `timeoutSeconds` ran out
  std::string err;     // everything it wrote to stderr
  std::string out;     // and to stdout
};

// `args` go to the shell as they are. A run longer than timeoutSeconds is killed (a hang is a failure,
// not a stalled suite).
SampleRun runSample(const std::string& exe, const std::string& args, const TempDir& dir, int timeoutSeconds = 120);

}  // namespace dyngi::test
