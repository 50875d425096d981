#include "support/sample_run.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace dyngi::test {

SampleRun runSample(const std::string& exe, const std::string& args, const TempDir& dir, int timeoutSeconds) {
  std::string errFile = dir.file("stderr.txt"), outFile = dir.file("stdout.txt");
  std::string cmd = "timeout -s KILL " + std::to_string(timeoutSeconds) + " " + exe + " " + args + " >" + outFile + " 2>" + errFile;
  int status = std::system(cmd.c_str());
  SampleRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (r.exitCode == 128 + 9 || r.exitCode == 137) r.exitCode = 124;  // killed by timeout's SIGKILL
  auto read = [](const std::string& path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  r.err = read(errFile);
  r.out = read(outFile);
  return r;
}

}  // namespace dyngi::test
