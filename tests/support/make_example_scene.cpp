// dyngi_make_example_scene [OUT] [--skinned-bar | --instances N]: writes the example glTF
// (support/example_scene.h), by default to assets/cornell_box.gltf in the source tree. --skinned-bar adds
// the skinned, bending bar (support/skinned_bar.h) at the front left: the skinned scene the host API is
// compared on. --instances N writes instead N nodes instancing one quad on a square field, lit by a sun
// (scripts/many_instances.sh measures it).
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "support/example_scene.h"
#include "support/skinned_bar.h"

namespace {
dyngi::test::GltfSpec quadField(int count) {
  dyngi::test::GltfSpec s;
  s.meshes = {{dyngi::test::quadPrimitive(0.5f)}};
  s.lightsJson = {R"({"type":"directional","intensity":3})"};
  const int side = int(std::ceil(std::sqrt(double(count))));
  dyngi::test::GltfNodeSpec root{.name = "field"};
  for (int i = 0; i < count; ++i) {
    root.children.push_back(int(s.nodes.size()) + 1);
    s.nodes.push_back({.mesh = 0, .transformJson = "\"translation\":[" + std::to_string(i % side) + ",0," + std::to_string(i / side) + "]"});
  }
  root.children.push_back(count + 1);
  s.nodes.push_back({.name = "sun", .light = 0, .transformJson = R"("rotation":[-0.5,0.2,0.1,0.84])"});
  s.nodes.insert(s.nodes.begin(), root);
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  const char* out = DYNGI_ASSETS_DIR "/cornell_box.gltf";
  bool skinnedBar = false;
  int instances = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--skinned-bar") == 0) skinnedBar = true;
    else if (std::strcmp(argv[i], "--instances") == 0 && i + 1 < argc) instances = std::atoi(argv[++i]);
    else out = argv[i];
  }
  const dyngi::test::GltfSpec cornell = dyngi::test::cornellBoxGltfSpec();
  std::ofstream f(out, std::ios::binary);
  if (instances > 0) f << dyngi::test::writeGltf(quadField(instances));
  else
    f << dyngi::test::writeGltf(skinnedBar ? dyngi::test::withSkinnedBar(cornell, glm::vec3(-0.4f, 0.0f, 0.45f), glm::vec3(0.25f, 0.35f, 0.85f))
                                           : cornell);
  if (!f) {
    std::fprintf(stderr, "dyngi_make_example_scene: cannot write %s\n", out);
    return 1;
  }
  std::printf("wrote %s\n", out);
  return 0;
}
