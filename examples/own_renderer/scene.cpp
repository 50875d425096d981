#include "scene.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace host {

namespace {

glm::mat4 localMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[size_t(i)]);
    return m;
  }
  glm::mat4 m(1.0f);
  if (n.translation.size() == 3) m = glm::translate(m, glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2])));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
  return m;
}

// An accessor's elements as floats (VEC2/VEC3 of floats) or indices (unsigned scalars); false when the
// accessor does not fit its buffer.
bool readFloats(const tinygltf::Model& model, int index, int components, std::vector<float>& out) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return false;
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.bufferView < 0) return false;
  const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
  const tinygltf::Buffer& b = model.buffers[size_t(v.buffer)];
  const size_t stride = v.byteStride ? v.byteStride : size_t(components) * 4, start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && start + stride * (a.count - 1) + size_t(components) * 4 > b.data.size()) return false;
  out.resize(a.count * size_t(components));
  for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i * size_t(components)], &b.data[start + i * stride], size_t(components) * 4);
  return true;
}

bool readIndices(const tinygltf::Model& model, int index, std::vector<uint32_t>& out) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return false;
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  if (a.bufferView < 0) return false;
  const size_t size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT     ? 4
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                                                                                   : 0;
  if (size == 0) return false;
  const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
  const tinygltf::Buffer& b = model.buffers[size_t(v.buffer)];
  const size_t stride = v.byteStride ? v.byteStride : size, start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && start + stride * (a.count - 1) + size > b.data.size()) return false;
  out.resize(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    uint32_t value = 0;
    std::memcpy(&value, &b.data[start + i * stride], size);
    out[i] = value;
  }
  return true;
}

std::string addPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& p, Scene& scene) {
  if (p.mode != TINYGLTF_MODE_TRIANGLES) return "only triangle primitives";
  auto pos = p.attributes.find("POSITION"), nrm = p.attributes.find("NORMAL");
  std::vector<float> positions, normals;
  if (pos == p.attributes.end() || !readFloats(model, pos->second, 3, positions)) return "a primitive without readable POSITION";
  if (nrm == p.attributes.end() || !readFloats(model, nrm->second, 3, normals) || normals.size() != positions.size())
    return "a primitive without NORMAL (this host does not make normals)";
  Mesh m;
  for (size_t i = 0; i + 2 < positions.size(); i += 3) {
    m.positions.emplace_back(positions[i], positions[i + 1], positions[i + 2]);
    m.normals.emplace_back(normals[i], normals[i + 1], normals[i + 2]);
  }
  if (p.indices >= 0) {
    if (!readIndices(model, p.indices, m.indices)) return "unreadable indices";
  } else {
    for (uint32_t i = 0; i < m.positions.size(); ++i) m.indices.push_back(i);
  }
  for (uint32_t i : m.indices)
    if (i >= m.positions.size()) return "an index past the vertices";
  scene.meshes.push_back(std::move(m));
  return {};
}

void addMaterials(const tinygltf::Model& model, Scene& scene) {
  for (const tinygltf::Material& g : model.materials) {
    Material m;
    const auto& pbr = g.pbrMetallicRoughness;
    for (int i = 0; i < 4 && size_t(i) < pbr.baseColorFactor.size(); ++i) m.baseColor[i] = float(pbr.baseColorFactor[size_t(i)]);
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    float strength = 1.0f;
    if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end() && it->second.Has("emissiveStrength"))
      strength = float(it->second.Get("emissiveStrength").GetNumberAsDouble());
    for (int i = 0; i < 3 && size_t(i) < g.emissiveFactor.size(); ++i) m.emissive[i] = float(g.emissiveFactor[size_t(i)]) * strength;
    scene.materials.push_back(m);
  }
  scene.materials.push_back(Material{});  // for primitives without one
}

void addLight(const tinygltf::Light& g, const glm::mat4& world, Scene& scene) {
  Light l;
  l.type = g.type == "directional" ? 0 : g.type == "spot" ? 2 : 1;
  if (g.color.size() == 3) l.color = glm::vec3(float(g.color[0]), float(g.color[1]), float(g.color[2]));
  l.intensity = float(g.intensity);
  l.range = float(g.range);
  l.innerCone = float(g.spot.innerConeAngle);
  l.outerCone = float(g.spot.outerConeAngle);
  l.position = glm::vec3(world[3]);
  l.direction = glm::normalize(-glm::vec3(world[2]));
  scene.lights.push_back(l);
}

}  // namespace

std::string loadScene(const std::string& path, Scene& scene) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) return path + ": not a readable glTF file" + (err.empty() ? "" : " (" + err.substr(0, err.find('\n')) + ")");
  addMaterials(model, scene);
  const uint32_t defaultMaterial = uint32_t(scene.materials.size() - 1);
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> meshPrimitives(model.meshes.size());  // (mesh, material)
  for (size_t i = 0; i < model.meshes.size(); ++i)
    for (const tinygltf::Primitive& p : model.meshes[i].primitives) {
      if (std::string problem = addPrimitive(model, p, scene); !problem.empty()) return path + ": mesh " + std::to_string(i) + ": " + problem;
      const uint32_t material = p.material >= 0 && size_t(p.material) < model.materials.size() ? uint32_t(p.material) : defaultMaterial;
      meshPrimitives[i].push_back({uint32_t(scene.meshes.size() - 1), material});
    }
  bool haveCamera = false;
  std::function<void(int, const glm::mat4&, int)> visit = [&](int node, const glm::mat4& parent, int depth) {
    if (node < 0 || size_t(node) >= model.nodes.size() || depth > 64) return;
    const tinygltf::Node& n = model.nodes[size_t(node)];
    const glm::mat4 world = parent * localMatrix(n);
    if (n.mesh >= 0 && size_t(n.mesh) < model.meshes.size())
      for (auto [mesh, material] : meshPrimitives[size_t(n.mesh)]) scene.instances.push_back({mesh, material, world});
    if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end() && it->second.Has("light")) {
      const int light = it->second.Get("light").GetNumberAsInt();
      if (light >= 0 && size_t(light) < model.lights.size()) addLight(model.lights[size_t(light)], world, scene);
    }
    if (!haveCamera && n.camera >= 0 && size_t(n.camera) < model.cameras.size() && model.cameras[size_t(n.camera)].type == "perspective") {
      const auto& p = model.cameras[size_t(n.camera)].perspective;
      scene.camera = {world, float(p.yfov), float(p.znear), p.zfar > 0 ? float(p.zfar) : 1000.0f};
      haveCamera = true;
    }
    for (int child : n.children) visit(child, world, depth + 1);
  };
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (size_t(sceneIndex) < model.scenes.size())
    for (int root : model.scenes[size_t(sceneIndex)].nodes) visit(root, glm::mat4(1.0f), 0);
  if (scene.instances.empty()) return path + ": no triangles in its scene";
  if (!haveCamera) {  // frame the scene's bounds from the +Z side, as dyngi does
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Instance& i : scene.instances)
      for (const glm::vec3& p : scene.meshes[i.mesh].positions) {
        const glm::vec3 w = glm::vec3(i.transform * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w), hi = glm::max(hi, w);
      }
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f), yfov = 0.8f;
    const float dist = radius / std::sin(0.5f * yfov) * 1.05f;
    const glm::vec3 eye = center + glm::vec3(0.0f, 0.25f * radius, dist);
    scene.camera = {glm::inverse(glm::lookAtRH(eye, center, glm::vec3(0, 1, 0))), yfov, std::max(dist - radius * 1.5f, dist * 1e-3f),
                    dist + radius * 2.0f};
  }
  return {};
}

}  // namespace host
