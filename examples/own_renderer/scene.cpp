#include "scene.h"

#include <tiny_gltf.h>

#include <algorithm>
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

// A VEC4 accessor of unsigned bytes or shorts (JOINTS_0).
bool readJoints(const tinygltf::Model& model, int index, std::vector<glm::uvec4>& out) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return false;
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  const size_t size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2 : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 1 : 0;
  if (size == 0 || a.type != TINYGLTF_TYPE_VEC4 || a.bufferView < 0) return false;
  const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
  const tinygltf::Buffer& b = model.buffers[size_t(v.buffer)];
  const size_t stride = v.byteStride ? v.byteStride : 4 * size, start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && start + stride * (a.count - 1) + 4 * size > b.data.size()) return false;
  out.resize(a.count);
  for (size_t i = 0; i < a.count; ++i)
    for (int k = 0; k < 4; ++k) {
      uint32_t value = 0;
      std::memcpy(&value, &b.data[start + i * stride + size_t(k) * size], size);
      out[i][k] = value;
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
  auto joints = p.attributes.find("JOINTS_0"), weights = p.attributes.find("WEIGHTS_0");
  if (joints != p.attributes.end() && weights != p.attributes.end()) {
    std::vector<float> w;
    if (!readJoints(model, joints->second, m.joints) || !readFloats(model, weights->second, 4, w) || m.joints.size() != m.positions.size() ||
        w.size() != 4 * m.positions.size())
      return "unreadable JOINTS_0 / WEIGHTS_0 (this host reads byte or short joints and float weights)";
    for (size_t i = 0; i < m.positions.size(); ++i) m.weights.emplace_back(w[4 * i], w[4 * i + 1], w[4 * i + 2], w[4 * i + 3]);
  }
  scene.meshes.push_back(std::move(m));
  return {};
}

void addNodesSkinsAndClip(const tinygltf::Model& model, Scene& scene) {
  for (const tinygltf::Node& n : model.nodes) {
    Node node;
    node.hasMatrix = n.matrix.size() == 16;
    if (node.hasMatrix) node.matrix = localMatrix(n);
    if (n.translation.size() == 3) node.translation = glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
    if (n.rotation.size() == 4) node.rotation = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
    if (n.scale.size() == 3) node.scale = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
    scene.nodes.push_back(node);
  }
  for (size_t i = 0; i < model.nodes.size(); ++i)
    for (int child : model.nodes[i].children)
      if (child >= 0 && size_t(child) < scene.nodes.size()) scene.nodes[size_t(child)].parent = int(i);
  for (const tinygltf::Skin& g : model.skins) {
    Skin skin;
    skin.joints = g.joints;
    std::vector<float> m;
    if (readFloats(model, g.inverseBindMatrices, 16, m))
      for (size_t i = 0; i + 15 < m.size(); i += 16) skin.inverseBind.push_back(glm::make_mat4(&m[i]));
    scene.skins.push_back(skin);
  }
  if (model.animations.empty()) return;
  const tinygltf::Animation& clip = model.animations[0];
  for (const tinygltf::AnimationChannel& c : clip.channels) {
    if (c.sampler < 0 || size_t(c.sampler) >= clip.samplers.size() || c.target_node < 0 || size_t(c.target_node) >= scene.nodes.size()) continue;
    const tinygltf::AnimationSampler& sampler = clip.samplers[size_t(c.sampler)];
    Channel ch;
    ch.node = c.target_node;
    ch.path = c.target_path == "translation" ? 0 : c.target_path == "rotation" ? 1 : c.target_path == "scale" ? 2 : -1;
    ch.interpolation = sampler.interpolation == "STEP" ? 0 : sampler.interpolation == "CUBICSPLINE" ? 2 : 1;
    const int components = ch.path == 1 ? 4 : 3;
    std::vector<float> values;
    if (ch.path < 0 || !readFloats(model, sampler.input, 1, ch.times) || !readFloats(model, sampler.output, components, values)) continue;
    for (size_t i = 0; i + size_t(components) <= values.size(); i += size_t(components))
      ch.values.emplace_back(values[i], values[i + 1], values[i + 2], components == 4 ? values[i + 3] : 0.0f);
    if (ch.times.empty() || ch.values.size() != ch.times.size() * (ch.interpolation == 2 ? 3 : 1)) continue;
    scene.animationDuration = std::max(scene.animationDuration, ch.times.back());
    scene.animation.push_back(std::move(ch));
  }
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
  addNodesSkinsAndClip(model, scene);
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
      for (auto [mesh, material] : meshPrimitives[size_t(n.mesh)]) {
        Instance instance{mesh, material, world, node, -1, mesh};
        if (n.skin >= 0 && size_t(n.skin) < scene.skins.size() && !scene.meshes[mesh].joints.empty()) {
          instance.skin = n.skin;  // deformed in a copy of its own: another instance may share the bind pose
          instance.mesh = uint32_t(scene.meshes.size());
          scene.meshes.push_back(scene.meshes[mesh]);
        }
        scene.instances.push_back(instance);
      }
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
  for (Instance& instance : scene.instances) {
    instance.dynamic = instance.skin >= 0;
    for (int n = instance.node, depth = 0; n >= 0 && depth < 64 && !instance.dynamic; n = scene.nodes[size_t(n)].parent, ++depth)
      for (const Channel& c : scene.animation) instance.dynamic |= c.node == n;
  }
  animate(scene, 0.0f);  // skinned meshes in their pose at the clip's start
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

namespace {

glm::vec4 sample(const Channel& c, float t) {
  auto normalized = [&](glm::vec4 v) { return c.path == 1 ? glm::normalize(v) : v; };
  const bool cubic = c.interpolation == 2;
  auto value = [&](size_t k) { return c.values[cubic ? 3 * k + 1 : k]; };
  const size_t n = c.times.size();
  if (t <= c.times.front() || n == 1) return normalized(value(0));
  if (t >= c.times.back()) return normalized(value(n - 1));
  const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
  const float dt = c.times[k + 1] - c.times[k], u = dt > 0.0f ? (t - c.times[k]) / dt : 0.0f;
  if (c.interpolation == 0) return normalized(value(k));
  if (!cubic) {
    if (c.path != 1) return glm::mix(value(k), value(k + 1), u);
    const glm::vec4 a = value(k), b = value(k + 1);
    const glm::quat q = glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), u);
    return glm::normalize(glm::vec4(q.x, q.y, q.z, q.w));
  }
  const glm::vec4 p0 = value(k), m0 = c.values[3 * k + 2] * dt, p1 = value(k + 1), m1 = c.values[3 * (k + 1)] * dt;
  const float u2 = u * u, u3 = u2 * u;
  return normalized((2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1);
}

glm::mat4 worldOf(const std::vector<Node>& nodes, int node, std::vector<glm::mat4>& memo, std::vector<char>& done, int depth = 0) {
  if (done[size_t(node)]) return memo[size_t(node)];
  const Node& n = nodes[size_t(node)];
  const glm::mat4 local = n.hasMatrix ? n.matrix
                                      : glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) * glm::scale(glm::mat4(1.0f), n.scale);
  const glm::mat4 parent = n.parent >= 0 && depth < 64 ? worldOf(nodes, n.parent, memo, done, depth + 1) : glm::mat4(1.0f);
  memo[size_t(node)] = parent * local;
  done[size_t(node)] = 1;
  return memo[size_t(node)];
}

// glTF skinning: each vertex by its weighted joint matrices (weights renormalised when they do not sum to 1).
void deform(const Mesh& bind, const std::vector<glm::mat4>& joints, Mesh& out) {
  for (size_t i = 0; i < bind.positions.size(); ++i) {
    glm::mat4 m(0.0f);
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      const float w = bind.weights[i][k];
      if (w <= 0.0f || bind.joints[i][k] >= joints.size()) continue;
      m += w * joints[bind.joints[i][k]];
      sum += w;
    }
    if (sum <= 0.0f) m = glm::mat4(1.0f);
    else if (std::abs(sum - 1.0f) > 1e-3f) m /= sum;
    out.positions[i] = glm::vec3(m * glm::vec4(bind.positions[i], 1.0f));
    const glm::vec3 n = glm::mat3(m) * bind.normals[i];
    const float length = glm::length(n);
    out.normals[i] = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

}  // namespace

std::vector<size_t> animate(Scene& scene, float seconds) {
  if (scene.animationDuration > 0.0f) {
    const float t = std::fmod(std::fmod(seconds, scene.animationDuration) + scene.animationDuration, scene.animationDuration);
    for (const Channel& c : scene.animation) {
      const glm::vec4 v = sample(c, t);
      Node& n = scene.nodes[size_t(c.node)];
      if (c.path == 0) n.translation = glm::vec3(v);
      else if (c.path == 1) n.rotation = glm::quat(v.w, v.x, v.y, v.z);
      else n.scale = glm::vec3(v);
    }
  }
  std::vector<glm::mat4> world(scene.nodes.size());
  std::vector<char> done(scene.nodes.size(), 0);
  std::vector<size_t> changed;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    Instance& instance = scene.instances[i];
    if (instance.node < 0) continue;
    const glm::mat4 placed = worldOf(scene.nodes, instance.node, world, done);
    bool moved = placed != instance.transform;
    instance.transform = placed;
    if (instance.skin >= 0) {
      const Skin& skin = scene.skins[size_t(instance.skin)];
      const glm::mat4 toMesh = glm::inverse(placed);
      std::vector<glm::mat4> joints(skin.joints.size(), glm::mat4(1.0f));
      for (size_t j = 0; j < skin.joints.size(); ++j)
        if (skin.joints[j] >= 0 && size_t(skin.joints[j]) < scene.nodes.size())
          joints[j] = toMesh * worldOf(scene.nodes, skin.joints[j], world, done) * (j < skin.inverseBind.size() ? skin.inverseBind[j] : glm::mat4(1.0f));
      deform(scene.meshes[instance.bindPose], joints, scene.meshes[instance.mesh]);
      moved = true;
    }
    if (moved) changed.push_back(i);
  }
  return changed;
}

}  // namespace host
