#pragma once
// The game's own scene, loaded from glTF with tinygltf: triangles, metallic-roughness factors,
// KHR_lights_punctual lights, the first camera, and the first animation clip with its skins: nodes keep
// their local transforms so the clip can move them, and skinned meshes are deformed on the CPU.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace host {

struct Mesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
  std::vector<glm::uvec4> joints;  // JOINTS_0 and WEIGHTS_0: empty unless skinned
  std::vector<glm::vec4> weights;
};

struct Material {
  glm::vec4 baseColor{1.0f};
  glm::vec3 emissive{0.0f};
  float metallic = 0.0f, roughness = 1.0f;
};

struct Instance {
  uint32_t mesh = 0, material = 0;  // a skinned instance's mesh is its own copy, deformed in place
  glm::mat4 transform{1.0f};
  int node = -1;                    // whose world matrix places it
  int skin = -1;
  uint32_t bindPose = 0;            // skinned: the undeformed mesh
  bool dynamic = false;             // skinned, or under a node the clip moves
};

struct Node {
  int parent = -1;
  glm::vec3 translation{0.0f}, scale{1.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::mat4 matrix{1.0f};  // glTF's "matrix" when it has one (then not animated)
  bool hasMatrix = false;
};

struct Skin {
  std::vector<int> joints;
  std::vector<glm::mat4> inverseBind;
};

struct Channel {
  int node = 0;
  int path = 0;             // 0 translation, 1 rotation, 2 scale
  int interpolation = 1;    // 0 step, 1 linear, 2 cubic spline (three values a key)
  std::vector<float> times;
  std::vector<glm::vec4> values;
};

struct Light {
  int type = 1;  // 0 directional, 1 point, 2 spot
  glm::vec3 color{1.0f};
  float intensity = 1.0f, range = 0.0f, innerCone = 0.0f, outerCone = 0.7853982f;
  glm::vec3 position{0.0f}, direction{0.0f, 0.0f, -1.0f};
};

struct Camera {
  glm::mat4 world{1.0f};  // looks down its -Z
  float yfov = 0.8f, znear = 0.05f, zfar = 100.0f;
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  Camera camera;
  std::vector<Node> nodes;
  std::vector<Skin> skins;
  std::vector<Channel> animation;  // the first clip, played in a loop
  float animationDuration = 0.0f;
};

// An error line ("" on success) for a file it cannot read or use.
std::string loadScene(const std::string& path, Scene& scene);

// Poses the nodes at `seconds` of the clip (looped) and updates the instances: their transforms, and
// skinned meshes re-deformed. Returns the instances that changed.
std::vector<size_t> animate(Scene& scene, float seconds);

}  // namespace host
