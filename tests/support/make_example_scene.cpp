// dyngi_make_example_scene [OUT]: writes the example glTF (support/example_scene.h), by default to
// assets/cornell_box.gltf in the source tree.
#include <cstdio>
#include <fstream>

#include "support/example_scene.h"

int main(int argc, char** argv) {
  const char* out = argc > 1 ? argv[1] : DYNGI_ASSETS_DIR "/cornell_box.gltf";
  std::ofstream f(out, std::ios::binary);
  f << dyngi::test::cornellBoxGltf();
  if (!f) {
    std::fprintf(stderr, "dyngi_make_example_scene: cannot write %s\n", out);
    return 1;
  }
  std::printf("wrote %s\n", out);
  return 0;
}
