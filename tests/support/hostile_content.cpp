#include "support/hostile_content.h"

#include <stb_image_write.h>

namespace dyngi::test {

namespace {
uint32_t crc32(const uint8_t* p, size_t n) {
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void putBe32(std::vector<uint8_t>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(uint8_t(v >> s));
}

void pngChunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
  putBe32(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  putBe32(out, crc32(out.data() + start, out.size() - start));
}
}  // namespace

std::string deepJsonArray(int depth) { return std::string(size_t(depth), '[') + "0" + std::string(size_t(depth), ']'); }

std::vector<uint8_t> pgm16(uint32_t width, uint32_t height, bool withData) {
  const std::string header = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n65535\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  if (withData) out.resize(out.size() + size_t(width) * height * 2, 0x7f);
  return out;
}

std::vector<uint8_t> truncatedRadianceHdr() {
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 64\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  for (uint8_t b : std::initializer_list<uint8_t>{0x02, 0x02, 0x00, 0x40, 0x80}) out.push_back(b);  // an RLE scanline of 64, one run byte, then the end
  return out;
}

std::vector<uint8_t> pngHeader(uint32_t width, uint32_t height) {
  std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> ihdr;
  putBe32(ihdr, width);
  putBe32(ihdr, height);
  for (uint8_t b : std::initializer_list<uint8_t>{8, 6, 0, 0, 0}) ihdr.push_back(b);  // 8-bit RGBA, deflate, no filter method, no interlace
  pngChunk(out, "IHDR", ihdr);
  pngChunk(out, "IDAT", {0x78, 0x9c, 0x03, 0x00});
  pngChunk(out, "IEND", {});
  return out;
}

std::vector<uint8_t> jpegHeader(uint16_t width, uint16_t height) {
  return {0xff, 0xd8, 0xff, 0xc0, 0x00, 0x11, 0x08, uint8_t(height >> 8), uint8_t(height), uint8_t(width >> 8), uint8_t(width), 0x03,
          0x01, 0x11, 0x00, 0x02, 0x11, 0x01, 0x03, 0x11, 0x01};
}

std::vector<uint8_t> smallPng() {
  const uint8_t texels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  std::vector<uint8_t> out;
  stbi_write_png_to_func([](void* c, void* d, int n) { static_cast<std::vector<uint8_t>*>(c)->insert(static_cast<std::vector<uint8_t>*>(c)->end(), static_cast<uint8_t*>(d), static_cast<uint8_t*>(d) + n); },
                         &out, 2, 2, 4, texels, 8);
  return out;
}

GltfSpec texturedQuad() {
  GltfSpec s;
  auto quad = quadPrimitive(1.0f);
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.material = 0;
  s.meshes = {{quad}};
  s.nodes = {{.name = "floor", .mesh = 0}};
  s.materialsJson = {R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})"};
  s.texturesJson = {R"({"source":0})"};
  return s;
}

GltfSpec diamondGraph(int layers) {
  GltfSpec s;
  s.meshes = {{quadPrimitive(1.0f)}};
  s.nodes.push_back({.name = "root", .children = {1, 2}});
  for (int l = 0; l < layers; ++l)
    for (int k = 0; k < 2; ++k) {
      GltfNodeSpec n;
      n.name = std::to_string(l);
      n.name += k ? 'b' : 'a';
      n.mesh = l + 1 == layers ? 0 : -1;
      if (l + 1 < layers) n.children = {1 + 2 * (l + 1), 2 + 2 * (l + 1)};
      s.nodes.push_back(n);
    }
  s.sceneNodes = {0};
  return s;
}

}  // namespace dyngi::test
