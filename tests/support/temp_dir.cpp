#include "support/temp_dir.h"

#include <atomic>
#include <fstream>
#include <random>
#include <unistd.h>

namespace dyngi::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("dyngi-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + "-" + std::to_string(rd() % 100000));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& contents) const {
  std::string p = file(name);
  std::ofstream f(p, std::ios::binary);
  f << contents;
  return p;
}

}  // namespace dyngi::test
