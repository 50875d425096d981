// dyngi_make_example_scene [OUT] [--skinned-bar]: writes the example glTF (support/example_scene.h), by
// default to assets/cornell_box.gltf in the source tree. --skinned-bar adds the skinned, bending bar
// (support/skinned_bar.h) at the front left: the skinned scene the host API is compared on.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "support/example_scene.h"
#include "support/skinned_bar.h"

int main(int argc, char** argv) {
  const char* out = DYNGI_ASSETS_DIR "/cornell_box.gltf";
  bool skinnedBar = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--skinned-bar") == 0) skinnedBar = true;
    else out = argv[i];
  }
  const dyngi::test::GltfSpec cornell = dyngi::test::cornellBoxGltfSpec();
  std::ofstream f(out, std::ios::binary);
  f << dyngi::test::writeGltf(skinnedBar ? dyngi::test::withSkinnedBar(cornell, glm::vec3(-0.4f, 0.0f, 0.45f), glm::vec3(0.25f, 0.35f, 0.85f))
                                         : cornell);
  if (!f) {
    std::fprintf(stderr, "dyngi_make_example_scene: cannot write %s\n", out);
    return 1;
  }
  std::printf("wrote %s\n", out);
  return 0;
}
