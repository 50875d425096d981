#include "dyngi/engine/render/image_io.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <cstdlib>
#include <filesystem>

namespace dyngi::render {
namespace {
void makeParentDirs(const std::string& path) {
  std::error_code ec;
  auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
}
}  // namespace

std::string writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
  if (rgba8.size() < size_t(width) * height * 4) return path + ": image data smaller than its size";
  makeParentDirs(path);
  if (!stbi_write_png(path.c_str(), int(width), int(height), 4, rgba8.data(), int(width * 4))) return path + ": could not write PNG";
  return {};
}

std::string writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<glm::vec4>& rgba) {
  size_t n = size_t(width) * height;
  if (rgba.size() < n) return path + ": image data smaller than its size";
  makeParentDirs(path);
  std::vector<float> interleaved(n * 4);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) interleaved[i * 4 + size_t(c)] = rgba[i][c];
  const char* err = nullptr;
  int r = SaveEXR(interleaved.data(), int(width), int(height), 4, /*save_as_fp16=*/0, path.c_str(), &err);
  if (r != TINYEXR_SUCCESS) {
    std::string msg = path + ": could not write EXR" + (err ? std::string(" (") + err + ")" : "");
    if (err) FreeEXRErrorMessage(err);
    return msg;
  }
  return {};
}

std::string readExr(const std::string& path, uint32_t& width, uint32_t& height, std::vector<glm::vec4>& rgba) {
  float* data = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  int r = LoadEXR(&data, &w, &h, path.c_str(), &err);
  if (r != TINYEXR_SUCCESS) {
    std::string msg = path + ": could not read EXR" + (err ? std::string(" (") + err + ")" : "");
    if (err) FreeEXRErrorMessage(err);
    return msg;
  }
  width = uint32_t(w);
  height = uint32_t(h);
  rgba.resize(size_t(w) * size_t(h));
  for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = glm::vec4(data[i * 4], data[i * 4 + 1], data[i * 4 + 2], data[i * 4 + 3]);
  std::free(data);
  return {};
}

}  // namespace dyngi::render
