#include "support/virtual_display.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace dyngi::test {

VirtualDisplay::VirtualDisplay() {
  const std::string pidFile = dir_.file("xvfb.pid"), displayFile = dir_.file("xvfb.display");
  std::string cmd = "Xvfb -displayfd 3 -screen 0 1024x800x24 -nolisten tcp 3>";
  cmd += displayFile;
  cmd += " >/dev/null 2>&1 & echo $! > ";
  cmd += pidFile;
  if (std::system(cmd.c_str()) != 0) return;
  std::ifstream(pidFile) >> pid_;
  for (int i = 0; i < 200; ++i) {
    std::stringstream text;
    text << std::ifstream(displayFile).rdbuf();
    int n = -1;
    if (text.str().find('\n') != std::string::npos && (text >> n) && n >= 0) {
      display_ = std::string(":").append(std::to_string(n));
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

VirtualDisplay::~VirtualDisplay() {
  if (pid_ > 0) kill(pid_, SIGTERM);
}

bool haveProgram(const char* name) { return std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0; }

}  // namespace dyngi::test
