#include "dyngi/engine/render/image_io.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>

#include "dyngi/engine/platform/files.h"

namespace dyngi::render {
// Output paths are written where they point: a missing parent directory is an error for the caller to
// report, never a directory tree made on the side (the sample checks its output paths before a run).

std::string writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
  if (rgba8.size() < size_t(width) * height * 4) return path + ": image data smaller than its size";
  // Encoded to memory, then written with every write and the close checked (a full disk is an error).
  std::vector<uint8_t> png;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &png, int(width), int(height), 4, rgba8.data(), int(width * 4))) return path + ": could not encode PNG";
  return platform::writeOutputFile(path, png.data(), png.size());
}

std::string writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<glm::vec4>& rgba) {
  size_t n = size_t(width) * height;
  if (rgba.size() < n) return path + ": image data smaller than its size";
  // Encoded to memory, then written here: tinyexr's own file writer leaks its header when the file
  // cannot be opened, and every array below is ours, so no error path can leak.
  std::vector<float> planes[4];  // A, B, G, R: the channel order EXR viewers expect
  for (auto& plane : planes) plane.resize(n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) planes[3 - c][i] = rgba[i][c];
  float* planePtrs[4] = {planes[0].data(), planes[1].data(), planes[2].data(), planes[3].data()};
  EXRChannelInfo channels[4] = {};
  const char* names[4] = {"A", "B", "G", "R"};
  for (int c = 0; c < 4; ++c) std::strncpy(channels[c].name, names[c], sizeof(channels[c].name) - 1);
  int pixelTypes[4], requested[4];
  for (int c = 0; c < 4; ++c) pixelTypes[c] = requested[c] = TINYEXR_PIXELTYPE_FLOAT;
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = 4;
  header.channels = channels;
  header.pixel_types = pixelTypes;
  header.requested_pixel_types = requested;
  header.compression_type = width < 16 && height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = 4;
  image.width = int(width);
  image.height = int(height);
  image.images = reinterpret_cast<unsigned char**>(planePtrs);
  unsigned char* raw = nullptr;
  const char* err = nullptr;
  size_t bytes = SaveEXRImageToMemory(&image, &header, &raw, &err);
  std::unique_ptr<unsigned char, decltype(&std::free)> memory(raw, &std::free);
  if (bytes == 0) {
    std::string msg = path + ": could not encode EXR" + (err ? std::string(" (") + err + ")" : "");
    if (err) FreeEXRErrorMessage(err);
    return msg;
  }
  return platform::writeOutputFile(path, memory.get(), bytes);
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
