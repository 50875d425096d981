// Writes the fuzzer's seed corpus: small valid .gltf and .glb files made by the test support code
// (a quad, a lit and textured-free room with a camera, a skinned and animated two-bone bar) and the
// hostile shapes the importer refuses (image bytes that lie about their format, headers promising huge
// images, JSON near and past the depth limit, a graph that is not a forest), for the fuzzer to mutate.
// usage: dyngi_make_fuzz_corpus DIR
#include <cstdio>
#include <fstream>
#include <string>

#include "support/gltf_writer.h"
#include "support/hostile_content.h"

using namespace dyngi::test;

namespace {
GltfSpec quad() {
  GltfSpec s;
  s.meshes = {{quadPrimitive(1.0f)}};
  s.nodes = {{.name = "floor", .mesh = 0}};
  return s;
}

GltfSpec litRoom() {
  GltfSpec s;
  auto floor = quadPrimitive(2.0f);
  floor.material = 0;
  auto box = quadPrimitive(0.5f);
  box.material = 1;
  box.normals.clear();
  s.meshes = {{floor}, {box}};
  s.materialsJson = {R"({"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.2,0.2,1],"metallicFactor":0.1,"roughnessFactor":0.6}})",
                     R"({"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":3}}})"};
  s.lightsJson = {R"({"type":"spot","intensity":10,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.6}})",
                  R"({"type":"point","intensity":5,"range":4})", R"({"type":"directional","intensity":2})"};
  s.camerasJson = {R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.05,"zfar":40}})"};
  s.nodes = {{.name = "root", .children = {1, 2, 3, 4, 5, 6}},
             {.name = "floor", .mesh = 0},
             {.name = "box", .mesh = 1, .transformJson = R"("translation":[0,0.5,0],"rotation":[0,0.38,0,0.92],"scale":[1,2,1])"},
             {.name = "spot", .light = 0, .transformJson = R"("translation":[0,2,0],"rotation":[-0.7071,0,0,0.7071])"},
             {.name = "bulb", .light = 1, .transformJson = R"("translation":[1,1,1])"},
             {.name = "sun", .light = 2},
             {.name = "cam", .camera = 0, .transformJson = R"("matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,1,4,1])"}};
  return s;
}

GltfSpec skinnedBar() {
  GltfSpec s;
  GltfPrimitiveSpec bar;
  for (int i = 0; i < 3; ++i)
    for (float x : {-0.1f, 0.1f}) {
      bar.positions.push_back({x, float(i), 0.0f});
      bar.normals.push_back({0, 0, 1});
      bar.joints.push_back({0, 1, 0, 0});
      float w = float(i) / 2.0f;
      bar.weights.push_back({1.0f - w, w, 0, 0});
    }
  bar.indices = {0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4};
  s.meshes = {{bar}};
  s.nodes = {{.name = "bar", .mesh = 0, .skin = 0}, {.name = "root", .children = {2}}, {.name = "tip", .transformJson = R"("translation":[0,1,0])"}};
  glm::mat4 ibm1(1.0f);
  ibm1[3][1] = -1.0f;
  s.skins = {{.joints = {1, 2}, .inverseBind = {glm::mat4(1.0f), ibm1}}};
  s.animations = {{.name = "bend",
                   .channels = {{.node = 2, .path = "rotation", .times = {0, 1}, .values = {{0, 0, 0, 1}, {0, 0, 0.38f, 0.92f}}},
                                {.node = 1, .path = "translation", .times = {0, 0.5f, 1}, .values = {glm::vec4(0), {0, 0.2f, 0, 0}, glm::vec4(0)}}}}};
  return s;
}

GltfSpec texturedWith(const std::string& mime, const std::vector<uint8_t>& bytes) {
  GltfSpec s = texturedQuad();
  s.imagesJson = {R"({"uri":")" + dataUri(mime, bytes) + R"("})"};
  return s;
}

GltfSpec deepExtras(int depth) {
  GltfSpec s = quad();
  s.extraMembersJson = "\"extras\":" + deepJsonArray(depth);
  return s;
}

bool write(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f << bytes;
  return bool(f);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: dyngi_make_fuzz_corpus DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  const std::pair<const char*, GltfSpec> scenes[] = {{"quad", quad()},
                                                      {"lit_room", litRoom()},
                                                      {"skinned_bar", skinnedBar()},
                                                      {"png_texture", texturedWith("image/png", smallPng())},
                                                      {"pgm_as_png", texturedWith("image/png", pgm16(4, 4, true))},
                                                      {"huge_png_header", texturedWith("image/png", pngHeader(16384, 16384))},
                                                      {"huge_jpeg_header", texturedWith("image/jpeg", jpegHeader(9000, 9000))},
                                                      {"hdr_as_png", texturedWith("image/png", truncatedRadianceHdr())},
                                                      {"json_depth_60", deepExtras(60)},
                                                      {"json_depth_200", deepExtras(200)},
                                                      {"diamond_graph", diamondGraph(24)}};
  int written = 0;
  for (const auto& [name, spec] : scenes) {
    if (!write(dir + "/" + name + ".gltf", writeGltf(spec)) || !write(dir + "/" + name + ".glb", writeGlb(spec))) {
      std::fprintf(stderr, "dyngi_make_fuzz_corpus: cannot write into %s\n", dir.c_str());
      return 1;
    }
    written += 2;
  }
  std::printf("wrote %d seed files to %s\n", written, dir.c_str());
  return 0;
}
