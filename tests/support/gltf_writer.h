#pragma once
// Writes small glTF 2.0 files for tests: `.gltf` text with the binary buffer embedded as a base64 data
// URI, or a `.glb` container. Knobs let a test break one thing at a time (accessor counts and offsets,
// modes, transforms, non-finite binary data) and build skinned, animated meshes in code.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::test {

struct GltfPrimitiveSpec {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // may be empty
  std::vector<glm::vec2> uvs;       // TEXCOORD_0; may be empty
  std::vector<uint32_t> indices;    // may be empty (non-indexed)
  std::vector<glm::uvec4> joints;   // JOINTS_0 (unsigned short), with weights; may be empty
  std::vector<glm::vec4> weights;   // WEIGHTS_0
  int mode = 4;                     // 4 = triangles
  int material = -1;
  int positionCountOverride = -1;   // >= 0: lie about the POSITION accessor count
  // Raw JSON numbers that replace the POSITION accessor's count / its bufferView's byteOffset, so a test
  // can write values no C++ integer type of the writer holds (2^62, 2^64 - 16).
  std::string positionCountRaw;
  std::string positionViewOffsetRaw;
};

struct GltfNodeSpec {
  std::string name;
  int mesh = -1;
  int camera = -1;
  int light = -1;
  int skin = -1;
  std::vector<int> children;
  std::string transformJson;        // e.g. "\"translation\":[0,1,0]" (raw, so tests can put NaN-ish text)
};

struct GltfSkinSpec {
  std::vector<int> joints;               // node indices
  std::vector<glm::mat4> inverseBind;    // one per joint; empty: no inverseBindMatrices accessor
};

struct GltfChannelSpec {
  int node = 0;
  std::string path = "translation";      // translation | rotation | scale
  std::vector<float> times;
  std::vector<glm::vec4> values;         // xyz for translation/scale, xyzw for rotation
};

struct GltfAnimationSpec {
  std::string name;
  std::vector<GltfChannelSpec> channels;
};

struct GltfSpec {
  std::vector<std::vector<GltfPrimitiveSpec>> meshes;
  std::vector<GltfNodeSpec> nodes;
  std::vector<int> sceneNodes;      // empty: all nodes without parents
  std::vector<std::string> materialsJson;  // raw material objects
  std::vector<std::string> lightsJson;     // raw KHR_lights_punctual light objects
  std::vector<std::string> camerasJson;    // raw camera objects
  std::vector<std::string> imagesJson;     // raw image objects (e.g. {"uri":"a.png"} beside the file)
  std::vector<std::string> texturesJson;   // raw texture objects
  std::vector<std::string> extensionsUsed, extensionsRequired;  // names, beside the ones the writer adds
  std::vector<GltfSkinSpec> skins;
  std::vector<GltfAnimationSpec> animations;
  int sceneIndex = 0;               // the file's "scene" (a test may point it past the list)
  std::string extraMembersJson;     // raw top-level members, e.g. "\"samplers\":[...]" or a deep "extras"
};

// `bytes` as a data URI: "data:MIME;base64,...".
std::string dataUri(const std::string& mime, const std::vector<uint8_t>& bytes);

std::string writeGltf(const GltfSpec& spec);  // returns the .gltf JSON text
std::string writeGlb(const GltfSpec& spec);   // returns the .glb bytes (JSON chunk + BIN chunk)

// A unit quad in the XZ plane facing +Y (two triangles), and a triangle.
GltfPrimitiveSpec quadPrimitive(float halfSize = 1.0f);

}  // namespace dyngi::test
