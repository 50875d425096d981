#pragma once
// Writes small glTF 2.0 files for tests, with the binary buffer embedded as a base64 data URI.
// Knobs let a test break one thing at a time (accessor counts, modes, transforms).
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::test {

struct GltfPrimitiveSpec {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // may be empty
  std::vector<uint32_t> indices;    // may be empty (non-indexed)
  int mode = 4;                     // 4 = triangles
  int material = -1;
  int positionCountOverride = -1;   // >= 0: lie about the POSITION accessor count
};

struct GltfNodeSpec {
  std::string name;
  int mesh = -1;
  int camera = -1;
  int light = -1;
  std::vector<int> children;
  std::string transformJson;        // e.g. "\"translation\":[0,1,0]" (raw, so tests can put NaN-ish text)
};

struct GltfSpec {
  std::vector<std::vector<GltfPrimitiveSpec>> meshes;
  std::vector<GltfNodeSpec> nodes;
  std::vector<int> sceneNodes;      // empty: all nodes without parents
  std::vector<std::string> materialsJson;  // raw material objects
  std::vector<std::string> lightsJson;     // raw KHR_lights_punctual light objects
  std::vector<std::string> camerasJson;    // raw camera objects
};

std::string writeGltf(const GltfSpec& spec);  // returns the .gltf JSON text

// A unit quad in the XZ plane facing +Y (two triangles), and a triangle.
GltfPrimitiveSpec quadPrimitive(float halfSize = 1.0f);

}  // namespace dyngi::test
