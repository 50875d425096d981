#pragma once
// The game's own scene, loaded from glTF with tinygltf: triangles, metallic-roughness factors,
// KHR_lights_punctual lights and the first camera, every node's world matrix applied.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace host {

struct Mesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
};

struct Material {
  glm::vec4 baseColor{1.0f};
  glm::vec3 emissive{0.0f};
  float metallic = 0.0f, roughness = 1.0f;
};

struct Instance {
  uint32_t mesh = 0, material = 0;
  glm::mat4 transform{1.0f};
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
};

// An error line ("" on success) for a file it cannot read or use.
std::string loadScene(const std::string& path, Scene& scene);

}  // namespace host
