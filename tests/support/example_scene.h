#pragma once
// assets/cornell_box.gltf, the glTF the embedding example renders: the built-in "cornell" scene (the
// same walls, boxes, materials, spot and camera, from the same CornellLayout constants) written as a
// glTF file. The committed file is this generator's output (tests check it byte for byte, and that it
// renders as the built-in scene does); `dyngi_make_example_scene` rewrites it.
#include <string>

#include "support/gltf_writer.h"

namespace dyngi::test {

GltfSpec cornellBoxGltfSpec();
inline std::string cornellBoxGltf() { return writeGltf(cornellBoxGltfSpec()); }

}  // namespace dyngi::test
