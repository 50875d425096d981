#include "dyngi/engine/scene/gltf_import.h"

#include "dyngi/engine/scene/animation.h"

#include <tiny_gltf.h>

#include "dyngi/engine/platform/files.h"
#include "gltf_content_rules.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>

namespace dyngi::scene {
namespace {

// Thrown inside the importer; caught at the top and turned into "<path>: <message>".
struct ImportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& msg) { throw ImportError(msg); }

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Checked size arithmetic: every offset, length and stride in a glTF file is attacker-controlled, so a
// sum or product that wraps around 2^64 must be an error, never a small number that passes a check.
bool addChecked(size_t a, size_t b, size_t& out) { return !__builtin_add_overflow(a, b, &out); }
bool mulChecked(size_t a, size_t b, size_t& out) { return !__builtin_mul_overflow(a, b, &out); }

// Reads accessor `index` as `comps` floats per element (or integers for indices), checking every
// offset against the buffer so a malformed file cannot make us read out of bounds.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, int index, const char* what) : what_(what) {
    const std::string name = std::string(what) + " accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.accessors.size()) fail(name + " does not exist");
    acc_ = &model.accessors[size_t(index)];
    if (acc_->sparse.isSparse) fail(name + " uses sparse storage (unsupported)");
    if (acc_->bufferView < 0 || size_t(acc_->bufferView) >= model.bufferViews.size())
      fail(name + " has no valid bufferView");
    const auto& view = model.bufferViews[size_t(acc_->bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      fail(name + ": its bufferView points at a missing buffer");
    const auto& buf = model.buffers[size_t(view.buffer)].data;
    comps_ = size_t(tinygltf::GetNumComponentsInType(uint32_t(acc_->type)));
    compSize_ = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(acc_->componentType)));
    if (comps_ == 0 || compSize_ == 0 || comps_ > 16) fail(name + " has an invalid type");
    const size_t elemSize = comps_ * compSize_;
    stride_ = view.byteStride ? view.byteStride : elemSize;
    if (stride_ < elemSize) fail(name + " has a byteStride smaller than its element");
    // The view must lie inside the buffer, and the accessor's last element inside the view; each sum
    // and product is checked for wrap-around before it is compared.
    size_t viewEnd = 0, begin = 0, span = 0, lastOffset = 0, end = 0;
    if (!addChecked(view.byteOffset, view.byteLength, viewEnd) || viewEnd > buf.size())
      fail(name + ": its bufferView lies outside its buffer");
    if (!addChecked(view.byteOffset, acc_->byteOffset, begin)) fail(name + " has an out-of-range byteOffset");
    if (acc_->count > 0) {
      if (!mulChecked(stride_, acc_->count - 1, lastOffset) || !addChecked(lastOffset, elemSize, span) ||
          !addChecked(begin, span, end) || end > viewEnd)
        fail(name + " (count " + std::to_string(acc_->count) + ") reads past the end of its bufferView");
    } else if (begin > viewEnd) {
      fail(name + " has an out-of-range byteOffset");
    }
    data_ = buf.data() + begin;
  }
  size_t count() const { return acc_->count; }
  size_t components() const { return comps_; }

  float readFloat(size_t i, size_t c) const {
    const uint8_t* p = data_ + i * stride_ + c * compSize_;
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return acc_->normalized ? float(*p) / 255.0f : float(*p);
      case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t v; std::memcpy(&v, p, 1); return acc_->normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? float(v) / 65535.0f : float(v); }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return float(v); }
      default: fail(std::string(what_) + " accessor has an unsupported component type");
    }
  }
  uint32_t readIndex(size_t i) const {
    const uint8_t* p = data_ + i * stride_;
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
      default: fail("index accessor must be unsigned byte, short or int");
    }
  }
  template <int N>
  std::vector<glm::vec<N, float>> readVec(size_t minComps = N) const {
    if (comps_ < minComps) fail(std::string(what_) + " accessor has too few components");
    std::vector<glm::vec<N, float>> out(count());
    for (size_t i = 0; i < count(); ++i)
      for (int c = 0; c < N && size_t(c) < comps_; ++c) out[i][c] = readFloat(i, size_t(c));
    return out;
  }

 private:
  const char* what_;
  const tinygltf::Accessor* acc_ = nullptr;
  const uint8_t* data_ = nullptr;
  size_t comps_ = 0, compSize_ = 0, stride_ = 0;
};

struct PendingPrimitive {
  MeshData mesh;
  int material = -1;
};

double numberOr(const tinygltf::Value& obj, const char* key, double fallback) {
  if (!obj.IsObject() || !obj.Has(key)) return fallback;
  const auto& v = obj.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

class Importer {
 public:
  Importer(const tinygltf::Model& model, ecs::World& world, AssetStore& assets, const ImportOptions& opts, const std::string& loaderWarnings)
      : model_(model), world_(world), assets_(assets), opts_(opts), loaderWarnings_(loaderWarnings) {}

  ImportReport run() {
    // Extensions: a required one the import cannot honour would render the file wrong; refuse it.
    for (const std::string& e : model_.extensionsRequired)
      if (!supported(e)) fail("requires the glTF extension " + e + ", which dyngi does not support");
    for (const std::string& e : model_.extensionsUsed)
      if (!supported(e)) report_.ignoredExtensions.push_back(e);
    // Phase 1: read and validate everything without touching the world.
    meshes_.resize(model_.meshes.size());
    for (size_t m = 0; m < model_.meshes.size(); ++m) meshes_[m] = readMesh(int(m));
    if (std::string bad = content::checkValues(model_); !bad.empty()) fail(bad);
    validateNodes();
    std::vector<int> roots;
    if (std::string bad = content::sceneRoots(model_, roots); !bad.empty()) fail(bad);
    size_t meshNodes = 0, nodes = 0, namedNodes = 0, extraPrimitives = 0;  // what the commit phase creates
    // Composes the world transforms the commit phase will write and checks them: finite local values
    // can still multiply into infinities (1e15 scale under a 1e15 scale).
    std::function<void(int, int, const glm::mat4&)> visit = [&](int n, int depth, const glm::mat4& parentWorld) {
      if (depth > 256) fail("node hierarchy deeper than 256 levels (cycle?)");
      const auto& node = model_.nodes[size_t(n)];
      const glm::mat4 world = parentWorld * localTransform(node).matrix();
      std::string where = "node " + std::to_string(n) + (node.name.empty() ? "" : " '" + node.name + "'");
      if (!withinCoordinateRange(world)) fail(where + " has a world transform that is not finite or beyond the coordinate range (1e18)");
      if (node.mesh >= 0) {
        for (const auto& p : meshes_[size_t(node.mesh)]) {
          Aabb b = p.mesh.bounds.transformed(world);
          if (!withinCoordinateRange(b.min) || !withinCoordinateRange(b.max))
            fail(where + " places its mesh beyond the coordinate range (1e18)");
        }
        meshNodes += meshes_[size_t(node.mesh)].size();
        if (!meshes_[size_t(node.mesh)].empty()) extraPrimitives += meshes_[size_t(node.mesh)].size() - 1;
      }
      ++nodes;
      namedNodes += node.name.empty() ? 0 : 1;
      for (int c : node.children) visit(c, depth + 1, world);
    };
    for (int r : roots) visit(r, 0, glm::mat4(1.0f));
    if (meshNodes == 0) fail("the scene has no triangle meshes (empty scene)");
    checkMaterials();
    skinInverseBind_.resize(model_.skins.size());
    for (size_t sk = 0; sk < model_.skins.size(); ++sk) skinInverseBind_[sk] = readSkin(sk);
    for (size_t a = 0; a < model_.animations.size(); ++a) clips_.push_back(readAnimation(a));

    // Phase 2: commit. Primitive meshes move into the asset store; keep their material indices.
    materialsByMesh_.resize(meshes_.size());
    for (size_t m = 0; m < meshes_.size(); ++m)
      for (auto& p : meshes_[m]) materialsByMesh_[m].push_back(p.material);
    // Colour textures (base colour, emission) are sRGB, data textures (metallic-roughness, occlusion)
    // linear; a texture used both ways is committed twice.
    std::vector<bool> colourUse(model_.textures.size(), false), dataUse(model_.textures.size(), false);
    for (const auto& m : model_.materials) {
      for (int t : {m.pbrMetallicRoughness.baseColorTexture.index, m.emissiveTexture.index})
        if (t >= 0) colourUse[size_t(t)] = true;
      for (int t : {m.pbrMetallicRoughness.metallicRoughnessTexture.index, m.occlusionTexture.index, m.normalTexture.index})
        if (t >= 0) dataUse[size_t(t)] = true;
    }
    for (size_t t = 0; t < model_.textures.size(); ++t) {
      // Only textures a material uses: those are the ones checked (an unused one may name no image).
      textureIds_.push_back(colourUse[t] ? commitTexture(t, /*srgb=*/true) : kNoTexture);
      linearTextureIds_.push_back(dataUse[t] ? commitTexture(t, /*srgb=*/false) : kNoTexture);
    }
    for (auto& prims : meshes_) {
      std::vector<MeshId> ids;
      for (auto& p : prims) ids.push_back(assets_.addMesh(std::move(p.mesh)));
      meshIds_.push_back(std::move(ids));
    }
    nodeEntities_.assign(model_.nodes.size(), ecs::kNullEntity);
    world_.reserveEntities(nodes + extraPrimitives);
    world_.reserve<Transform>(nodes + extraPrimitives);
    world_.reserve<WorldTransform>(nodes + extraPrimitives);
    world_.reserve<Name>(namedNodes);
    world_.reserve<MeshInstance>(meshNodes);
    world_.reserve<Material>(meshNodes);
    if (opts_.markStatic) world_.reserve<StaticTag>(meshNodes);
    else world_.reserve<DynamicTag>(meshNodes);
    for (int r : roots) commitNode(r, ecs::kNullEntity, glm::mat4(1.0f));
    commitSkins();
    commitAnimations();
    report_.textures = model_.textures.size();
    return report_;
  }

 private:
  std::vector<PendingPrimitive> readMesh(int meshIndex) {
    const auto& mesh = model_.meshes[size_t(meshIndex)];
    std::vector<PendingPrimitive> out;
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const auto& prim = mesh.primitives[pi];
      std::string where = "mesh '" + mesh.name + "' primitive " + std::to_string(pi);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
        fail(where + " has mode " + std::to_string(prim.mode) + "; only triangles (mode 4) are supported");
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) fail(where + " has no POSITION attribute");
      PendingPrimitive p;
      p.material = prim.material;
      p.mesh.name = mesh.name;
      p.mesh.positions = AccessorReader(model_, pos->second, "POSITION").readVec<3>();
      for (auto& v : p.mesh.positions) {
        if (!finite(v)) fail(where + " has a non-finite vertex position");
        if (!withinCoordinateRange(v)) fail(where + " has a vertex position beyond the coordinate range (1e18)");
      }
      size_t n = p.mesh.positions.size();
      if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        p.mesh.normals = AccessorReader(model_, it->second, "NORMAL").readVec<3>();
        if (p.mesh.normals.size() != n) fail(where + " NORMAL count differs from POSITION count");
      }
      if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        p.mesh.uvs = AccessorReader(model_, it->second, "TEXCOORD_0").readVec<2>();
        if (p.mesh.uvs.size() != n) fail(where + " TEXCOORD_0 count differs from POSITION count");
      }
      if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
        p.mesh.tangents = AccessorReader(model_, it->second, "TANGENT").readVec<4>();
        if (p.mesh.tangents.size() != n) fail(where + " TANGENT count differs from POSITION count");
        for (auto& t : p.mesh.tangents)
          if (!finite(glm::vec3(t)) || !std::isfinite(t.w)) fail(where + " has a non-finite tangent");
      }
      if (auto jt = prim.attributes.find("JOINTS_0"), wt = prim.attributes.find("WEIGHTS_0");
          jt != prim.attributes.end() && wt != prim.attributes.end()) {
        if (jt->second >= 0 && size_t(jt->second) < model_.accessors.size() &&
            model_.accessors[size_t(jt->second)].componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            model_.accessors[size_t(jt->second)].componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
          fail(where + " JOINTS_0 must be unsigned bytes or shorts");
        AccessorReader jr(model_, jt->second, "JOINTS_0");
        AccessorReader wr(model_, wt->second, "WEIGHTS_0");
        if (jr.count() != n || wr.count() != n) fail(where + " JOINTS_0/WEIGHTS_0 count differs from POSITION count");
        if (jr.components() != 4 || wr.components() != 4) fail(where + " JOINTS_0/WEIGHTS_0 must be VEC4");
        p.mesh.joints.resize(n);
        p.mesh.weights.resize(n);
        for (size_t i = 0; i < n; ++i)
          for (size_t c = 0; c < 4; ++c) {
            float j = jr.readFloat(i, c), w = wr.readFloat(i, c);
            if (!(j >= 0.0f) || !std::isfinite(w)) fail(where + " has invalid joint indices or weights");
            p.mesh.joints[i][int(c)] = uint32_t(j);
            p.mesh.weights[i][int(c)] = w;
          }
      }
      if (prim.indices >= 0) {
        AccessorReader idx(model_, prim.indices, "indices");
        p.mesh.indices.resize(idx.count());
        for (size_t i = 0; i < idx.count(); ++i) {
          p.mesh.indices[i] = idx.readIndex(i);
          if (p.mesh.indices[i] >= n) fail(where + " has an index out of range of its vertices");
        }
      } else {
        p.mesh.indices.resize(n);
        for (size_t i = 0; i < n; ++i) p.mesh.indices[i] = uint32_t(i);
      }
      if (p.mesh.indices.size() % 3 != 0) fail(where + " index count is not a multiple of 3");
      dropDegenerateTriangles(p.mesh);
      bool badNormals = p.mesh.normals.empty();
      for (auto& nrm : p.mesh.normals)
        if (!finite(nrm) || glm::dot(nrm, nrm) < 1e-12f) badNormals = true;
      if (badNormals) p.mesh.generateNormals();
      else for (auto& nrm : p.mesh.normals) nrm = glm::normalize(nrm);
      // A normal texture needs a tangent frame: the file's, else one from the uvs (glTF asks for
      // MikkTSpace; this per-vertex sum agrees on flat and smoothly mapped surfaces).
      const bool normalMapped = p.material >= 0 && size_t(p.material) < model_.materials.size() &&
                                model_.materials[size_t(p.material)].normalTexture.index >= 0;
      bool badTangents = p.mesh.tangents.size() != n || badNormals;
      for (const auto& t : p.mesh.tangents) badTangents |= !(glm::dot(glm::vec3(t), glm::vec3(t)) > 1e-12f);
      if (normalMapped && badTangents) p.mesh.computeTangents();
      else if (!normalMapped) p.mesh.tangents.clear();
      else for (auto& t : p.mesh.tangents) t = glm::vec4(glm::normalize(glm::vec3(t)), t.w < 0.0f ? -1.0f : 1.0f);
      p.mesh.computeBounds();
      if (p.mesh.indices.empty()) continue;  // only degenerate triangles: nothing to draw
      out.push_back(std::move(p));
    }
    return out;
  }

  static void dropDegenerateTriangles(MeshData& m) {
    std::vector<uint32_t> kept;
    kept.reserve(m.indices.size());
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const glm::vec3& a = m.positions[m.indices[t]];
      const glm::vec3& b = m.positions[m.indices[t + 1]];
      const glm::vec3& c = m.positions[m.indices[t + 2]];
      if (glm::length(glm::cross(b - a, c - a)) > 1e-12f)
        kept.insert(kept.end(), m.indices.begin() + long(t), m.indices.begin() + long(t) + 3);
    }
    m.indices = std::move(kept);
  }

  void validateNodes() {
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
      const auto& node = model_.nodes[i];
      std::string where = "node " + std::to_string(i) + (node.name.empty() ? "" : " '" + node.name + "'");
      if (node.mesh >= int(model_.meshes.size())) fail(where + " references a missing mesh");
      if (node.camera >= int(model_.cameras.size())) fail(where + " references a missing camera");
      if (node.skin >= int(model_.skins.size())) fail(where + " references a missing skin");
      for (int c : node.children)
        if (c < 0 || size_t(c) >= model_.nodes.size()) fail(where + " has a missing child node");
      // Checked as the floats they become: 1e39 is a finite double but an infinite float.
      auto inRange = [](const std::vector<double>& values) {
        for (double v : values)
          if (!(std::abs(v) <= double(kMaxCoordinate))) return false;
        return true;
      };
      if (!inRange(node.matrix)) fail(where + " has a matrix that is not finite or beyond the coordinate range (1e18)");
      if (!inRange(node.translation)) fail(where + " has a translation that is not finite or beyond the coordinate range (1e18)");
      if (!inRange(node.rotation)) fail(where + " has a rotation that is not finite");
      if (!inRange(node.scale)) fail(where + " has a scale that is not finite or beyond the coordinate range (1e18)");
      if (node.rotation.size() == 4) {
        double len2 = 0;
        for (double v : node.rotation) len2 += v * v;
        if (!(len2 > 1e-12)) fail(where + " has a zero rotation quaternion");
      }
      if (lightIndex(node) >= int(model_.lights.size())) fail(where + " references a missing light");
    }
  }

  static bool supported(const std::string& extension) {
    const auto& all = supportedGltfExtensions();
    return std::find(all.begin(), all.end(), extension) != all.end();
  }

  void checkMaterials() {
    auto checkTex = [&](int t, const std::string& where) {
      if (t < 0) return;
      if (size_t(t) >= model_.textures.size()) fail(where + " references a missing texture");
      int src = model_.textures[size_t(t)].source;
      if (src < 0 || size_t(src) >= model_.images.size()) fail(where + " texture has no valid image");
      const auto& img = model_.images[size_t(src)];
      if (img.image.empty() || img.width <= 0 || img.height <= 0) {
        // tinygltf only warns of an image it could not load: its first warning says why.
        const std::string why = loaderWarnings_.substr(0, loaderWarnings_.find('\n'));
        fail(where + " texture image could not be loaded" + (why.empty() ? "" : " (" + why + ")"));
      }
      if (img.image.size() < size_t(img.width) * size_t(img.height) * size_t(std::max(img.component, 1)) * (img.bits == 16 ? 2u : 1u))
        fail(where + " texture image data is truncated");
    };
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const auto& m = model_.materials[i];
      std::string where = "material " + std::to_string(i);
      checkTex(m.pbrMetallicRoughness.baseColorTexture.index, where);
      checkTex(m.emissiveTexture.index, where);
      checkTex(m.pbrMetallicRoughness.metallicRoughnessTexture.index, where);
      checkTex(m.occlusionTexture.index, where);
      checkTex(m.normalTexture.index, where);
    }
    for (auto& prims : meshes_)
      for (auto& p : prims)
        if (p.material >= int(model_.materials.size())) fail("a primitive references a missing material");
  }

  static int lightIndex(const tinygltf::Node& node) {
    auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) return -1;
    return int(numberOr(it->second, "light", -1));
  }

  TextureId commitTexture(size_t t, bool srgb) {
    const auto& img = model_.images[size_t(model_.textures[t].source)];
    TextureData tex;
    tex.name = img.name;
    tex.srgb = srgb;
    tex.width = uint32_t(img.width);
    tex.height = uint32_t(img.height);
    tex.rgba8.resize(size_t(tex.width) * tex.height * 4);
    size_t comps = size_t(img.component), bytes = img.bits == 16 ? 2 : 1;
    size_t texels = size_t(tex.width) * tex.height;
    if (img.image.size() < texels * comps * bytes) fail("texture image data is truncated");
    for (size_t i = 0; i < texels; ++i)
      for (size_t c = 0; c < 4; ++c) {
        uint8_t v = 255;
        if (c < comps) {
          size_t src = (i * comps + c) * bytes;
          v = bytes == 2 ? img.image[src + 1] : img.image[src];  // 16-bit little endian: take the high byte
        } else if (c < 3 && comps >= 1) {
          v = img.image[(i * comps) * bytes];  // grey -> replicate
        }
        tex.rgba8[i * 4 + c] = v;
      }
    return assets_.addTexture(std::move(tex));
  }

  // KHR_texture_transform on a texture reference; nullopt without one.
  static std::optional<TextureTransform> textureTransform(const tinygltf::ExtensionMap& extensions) {
    auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end() || !it->second.IsObject()) return std::nullopt;
    const tinygltf::Value& v = it->second;
    TextureTransform t;
    auto pair = [&](const char* key, glm::vec2& out) {
      if (!v.Has(key) || !v.Get(key).IsArray() || v.Get(key).ArrayLen() != 2) return;
      for (int i = 0; i < 2; ++i)
        if (v.Get(key).Get(i).IsNumber()) out[i] = float(v.Get(key).Get(i).GetNumberAsDouble());
    };
    pair("offset", t.offset);
    pair("scale", t.scale);
    t.rotation = float(numberOr(v, "rotation", 0.0));
    // Non-finite values would spread NaN through every lookup: such a transform is left out.
    if (!std::isfinite(t.offset.x) || !std::isfinite(t.offset.y) || !std::isfinite(t.scale.x) || !std::isfinite(t.scale.y) ||
        !std::isfinite(t.rotation))
      return std::nullopt;
    return t;
  }

  // Materials are read once per primitive instance: each note is written once.
  void noteOnce(const std::string& note) {
    if (std::find(report_.notes.begin(), report_.notes.end(), note) == report_.notes.end()) report_.notes.push_back(note);
  }

  Material materialFor(int index) {
    Material mat;
    if (index < 0) return mat;
    const auto& m = model_.materials[size_t(index)];
    // One texture transform per material (every texture of it uses it): the first texture's that has
    // one. Textures of one material with different transforms are rare; they are reported.
    std::optional<TextureTransform> transform;
    bool differ = false;
    auto consider = [&](int textureIndex, const tinygltf::ExtensionMap& ext) {
      if (textureIndex < 0) return;
      const TextureTransform t = textureTransform(ext).value_or(TextureTransform{});
      if (!transform) transform = t;
      else differ |= !(*transform == t);
    };
    consider(m.pbrMetallicRoughness.baseColorTexture.index, m.pbrMetallicRoughness.baseColorTexture.extensions);
    consider(m.pbrMetallicRoughness.metallicRoughnessTexture.index, m.pbrMetallicRoughness.metallicRoughnessTexture.extensions);
    consider(m.emissiveTexture.index, m.emissiveTexture.extensions);
    consider(m.occlusionTexture.index, m.occlusionTexture.extensions);
    consider(m.normalTexture.index, m.normalTexture.extensions);
    if (transform) mat.uvTransform = *transform;
    if (m.alphaMode == "MASK") {
      mat.alphaMask = true;
      mat.alphaCutoff = std::isfinite(m.alphaCutoff) ? float(std::max(m.alphaCutoff, 0.0)) : 0.5f;
    } else if (m.alphaMode == "BLEND") {
      noteOnce("material " + std::to_string(index) + " (" + m.name + ") is alphaMode BLEND; drawn opaque");
    }
    if (differ)
      noteOnce("material " + std::to_string(index) + " (" + m.name + ") gives its textures different KHR_texture_transform values; all use the first texture's");
    const auto& pbr = m.pbrMetallicRoughness;
    for (int i = 0; i < 4 && size_t(i) < pbr.baseColorFactor.size(); ++i) mat.baseColor[i] = float(pbr.baseColorFactor[size_t(i)]);
    if (pbr.baseColorTexture.index >= 0) mat.baseColorTexture = textureIds_[size_t(pbr.baseColorTexture.index)];
    mat.metallic = float(pbr.metallicFactor);
    mat.roughness = float(pbr.roughnessFactor);
    float strength = 1.0f;
    if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end())
      strength = float(numberOr(it->second, "emissiveStrength", 1.0));
    for (int i = 0; i < 3 && size_t(i) < m.emissiveFactor.size(); ++i) mat.emissive[i] = float(m.emissiveFactor[size_t(i)]) * strength;
    if (m.emissiveTexture.index >= 0) mat.emissiveTexture = textureIds_[size_t(m.emissiveTexture.index)];
    if (pbr.metallicRoughnessTexture.index >= 0) mat.metallicRoughnessTexture = linearTextureIds_[size_t(pbr.metallicRoughnessTexture.index)];
    if (m.normalTexture.index >= 0) {
      mat.normalTexture = linearTextureIds_[size_t(m.normalTexture.index)];
      mat.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
    }
    if (m.occlusionTexture.index >= 0) {
      mat.occlusionTexture = linearTextureIds_[size_t(m.occlusionTexture.index)];
      mat.occlusionStrength = std::clamp(float(m.occlusionTexture.strength), 0.0f, 1.0f);
    }
    return mat;
  }

  static Transform localTransform(const tinygltf::Node& node) {
    Transform t;
    if (node.matrix.size() == 16) {
      glm::mat4 m(1.0f);
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[size_t(i)]);
      t.translation = glm::vec3(m[3]);
      glm::vec3 sx(m[0]), sy(m[1]), sz(m[2]);
      t.scale = {glm::length(sx), glm::length(sy), glm::length(sz)};
      if (glm::determinant(glm::mat3(m)) < 0) t.scale.x = -t.scale.x;
      // A zero column (scale 0, legal: e.g. a hidden part) has no direction: keep the identity rotation.
      if (t.scale.x != 0.0f && t.scale.y != 0.0f && t.scale.z != 0.0f) {
        glm::mat3 r{sx / t.scale.x, sy / t.scale.y, sz / t.scale.z};
        t.rotation = glm::normalize(glm::quat_cast(r));
      }
    } else {
      if (node.translation.size() == 3) t.translation = {float(node.translation[0]), float(node.translation[1]), float(node.translation[2])};
      if (node.rotation.size() == 4) t.rotation = glm::normalize(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
      if (node.scale.size() == 3) t.scale = {float(node.scale[0]), float(node.scale[1]), float(node.scale[2])};
    }
    return t;
  }

  void commitNode(int n, Entity parent, const glm::mat4& parentWorld) {
    const auto& node = model_.nodes[size_t(n)];
    Entity e = world_.create();
    nodeEntities_[size_t(n)] = e;
    ++report_.nodes;
    Transform local = localTransform(node);
    local.parent = parent;
    glm::mat4 worldM = parentWorld * local.matrix();
    world_.add(e, local);
    world_.add(e, WorldTransform{worldM});
    if (!node.name.empty()) world_.add(e, Name{node.name});

    if (node.mesh >= 0) {
      const auto& ids = meshIds_[size_t(node.mesh)];
      // One entity per primitive: the node's entity carries the first, children carry the rest.
      for (size_t p = 0; p < ids.size(); ++p) {
        Entity target = e;
        if (p > 0) {
          target = world_.create();
          world_.add(target, Transform{.parent = e});
          world_.add(target, WorldTransform{worldM});
        }
        world_.add(target, MeshInstance{ids[p], true});
        if (node.skin >= 0) pendingSkins_.push_back({target, node.skin, ids[p]});
        world_.add(target, materialFor(primMaterial(node.mesh, p)));
        if (opts_.markStatic) world_.add(target, StaticTag{});
        else world_.add(target, DynamicTag{});
        ++report_.meshInstances;
        report_.triangles += assets_.mesh(ids[p]).triangleCount();
        report_.worldBounds.extend(assets_.mesh(ids[p]).bounds.transformed(worldM));
      }
    }
    if (node.camera >= 0) {
      const auto& cam = model_.cameras[size_t(node.camera)];
      Camera c;
      if (cam.type == "perspective") {
        c.yfov = float(cam.perspective.yfov);
        c.znear = float(cam.perspective.znear);
        c.zfar = cam.perspective.zfar > 0 ? float(cam.perspective.zfar) : 1000.0f;
        c.aspect = float(cam.perspective.aspectRatio);
      }
      world_.add(e, c);
      if (report_.activeCamera.isNull()) {
        world_.add(e, ActiveCamera{});
        report_.activeCamera = e;
      }
      ++report_.cameras;
    }
    if (int li = lightIndex(node); li >= 0) {
      const auto& l = model_.lights[size_t(li)];
      Light light;
      if (l.type == "directional") light.type = LightType::Directional;
      else if (l.type == "spot") light.type = LightType::Spot;
      else if (l.type == "point") light.type = LightType::Point;
      else fail("light " + std::to_string(li) + " has unknown type '" + l.type + "'");
      if (l.color.size() == 3) light.color = {float(l.color[0]), float(l.color[1]), float(l.color[2])};
      light.intensity = float(l.intensity);
      light.range = float(l.range);
      light.innerConeAngle = float(l.spot.innerConeAngle);
      light.outerConeAngle = float(l.spot.outerConeAngle);
      world_.add(e, light);
      ++report_.lights;
    }
    for (int c : node.children) commitNode(c, e, worldM);
  }

  std::vector<glm::mat4> readSkin(size_t index) {
    const auto& skin = model_.skins[index];
    std::string where = "skin " + std::to_string(index);
    for (int j : skin.joints)
      if (j < 0 || size_t(j) >= model_.nodes.size()) fail(where + " has a missing joint node");
    std::vector<glm::mat4> ibm(skin.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
      AccessorReader r(model_, skin.inverseBindMatrices, "inverseBindMatrices");
      if (r.components() != 16 || r.count() < skin.joints.size()) fail(where + " inverseBindMatrices must be MAT4, one per joint");
      for (size_t j = 0; j < skin.joints.size(); ++j)
        for (int c = 0; c < 16; ++c) {
          float v = r.readFloat(j, size_t(c));
          if (!std::isfinite(v)) fail(where + " has a non-finite inverse bind matrix");
          ibm[j][c / 4][c % 4] = v;
        }
    }
    return ibm;
  }

  AnimationClip readAnimation(size_t index) {
    const auto& anim = model_.animations[index];
    std::string where = "animation " + std::to_string(index) + (anim.name.empty() ? "" : " '" + anim.name + "'");
    AnimationClip clip;
    clip.name = anim.name.empty() ? "clip" + std::to_string(index) : anim.name;
    for (const auto& ch : anim.channels) {
      if (ch.target_path == "weights") continue;  // morph targets: not supported, ignored
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) fail(where + " channel has a missing sampler");
      if (ch.target_node < 0 || size_t(ch.target_node) >= model_.nodes.size()) fail(where + " channel targets a missing node");
      const auto& smp = anim.samplers[size_t(ch.sampler)];
      AnimationChannel out;
      out.node = uint32_t(ch.target_node);
      if (ch.target_path == "translation") out.path = AnimationPath::Translation;
      else if (ch.target_path == "rotation") out.path = AnimationPath::Rotation;
      else if (ch.target_path == "scale") out.path = AnimationPath::Scale;
      else fail(where + " has unknown target path '" + ch.target_path + "'");
      if (smp.interpolation == "STEP") out.interpolation = Interpolation::Step;
      else if (smp.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
      else out.interpolation = Interpolation::Linear;
      AccessorReader in(model_, smp.input, "animation input");
      AccessorReader val(model_, smp.output, "animation output");
      size_t keys = in.count(), perKey = out.interpolation == Interpolation::CubicSpline ? 3 : 1;
      size_t comps = out.path == AnimationPath::Rotation ? 4 : 3;
      if (in.components() != 1 || val.components() != comps) fail(where + " sampler has the wrong accessor types");
      if (val.count() != keys * perKey) fail(where + " sampler output count does not match its input");
      out.times.resize(keys);
      for (size_t k = 0; k < keys; ++k) {
        out.times[k] = in.readFloat(k, 0);
        if (!std::isfinite(out.times[k]) || out.times[k] < 0.0f) fail(where + " has a key time that is negative or not finite");
        if (k > 0 && !(out.times[k] > out.times[k - 1])) fail(where + " key times are not increasing");
      }
      out.values.resize(val.count(), glm::vec4(0.0f));
      for (size_t k = 0; k < val.count(); ++k)
        for (size_t c = 0; c < comps; ++c) {
          out.values[k][int(c)] = val.readFloat(k, c);
          if (!std::isfinite(out.values[k][int(c)])) fail(where + " has non-finite key values");
        }
      if (!out.times.empty()) clip.duration = std::max(clip.duration, out.times.back());
      clip.channels.push_back(std::move(out));
    }
    return clip;
  }

  void commitSkins() {
    for (const auto& ps : pendingSkins_) {
      const auto& skin = model_.skins[size_t(ps.skin)];
      const MeshData& bind = assets_.mesh(ps.bindPose);
      if (bind.joints.empty()) continue;  // skin on a mesh without JOINTS_0: draw it rigid
      SkinnedMesh sm;
      sm.bindPose = ps.bindPose;
      for (int j : skin.joints) sm.joints.push_back(nodeEntities_[size_t(j)]);
      sm.inverseBind = skinInverseBind_[size_t(ps.skin)];
      MeshData deformed = bind;
      deformed.name = bind.name + " (skinned)";
      sm.deformed = assets_.addMesh(std::move(deformed));
      world_.write<MeshInstance>(ps.entity).mesh = sm.deformed;
      if (world_.has<StaticTag>(ps.entity)) world_.remove<StaticTag>(ps.entity);
      if (!world_.has<DynamicTag>(ps.entity)) world_.add(ps.entity, DynamicTag{});
      world_.add(ps.entity, std::move(sm));
      ++report_.skinnedMeshes;
    }
  }

  void commitAnimations() {
    if (clips_.empty()) return;
    Entity e = world_.create();
    Animator a;
    a.nodes = nodeEntities_;
    a.clips = std::move(clips_);
    a.active = 0;
    if (!opts_.clip.empty()) {
      a.active = a.findClip(opts_.clip);
      if (a.active < 0) a.active = 0, report_.missingClip = true;
    }
    report_.clips.clear();
    for (auto& c : a.clips) report_.clips.push_back(c.name);
    world_.add(e, std::move(a));
    world_.add(e, Name{"animator"});
    report_.animator = e;
  }

  int primMaterial(int mesh, size_t committedIndex) const { return materialsByMesh_[size_t(mesh)][committedIndex]; }

 private:
  const tinygltf::Model& model_;
  ecs::World& world_;
  AssetStore& assets_;
  ImportOptions opts_;
  std::string loaderWarnings_;
  ImportReport report_;
  std::vector<std::vector<PendingPrimitive>> meshes_;
  std::vector<std::vector<int>> materialsByMesh_;
  std::vector<std::vector<MeshId>> meshIds_;
  std::vector<TextureId> textureIds_;        // per glTF texture: its sRGB copy (colour uses)
  std::vector<TextureId> linearTextureIds_;  // ... and its linear copy (data uses)
  std::vector<Entity> nodeEntities_;
  struct PendingSkin {
    Entity entity;
    int skin;
    MeshId bindPose;
  };
  std::vector<PendingSkin> pendingSkins_;
  std::vector<std::vector<glm::mat4>> skinInverseBind_;
  std::vector<AnimationClip> clips_;
};

}  // namespace

const std::vector<std::string>& supportedGltfExtensions() {
  static const std::vector<std::string> all = {"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform"};
  return all;
}

namespace {
// Runs the importer on a parsed model; turns every error into "<name>: <problem>".
std::string importModel(const tinygltf::Model& model, const std::string& warnings, const std::string& name, ecs::World& world,
                        AssetStore& assets, ImportReport* report, const ImportOptions& options) {
  try {
    ImportReport r = Importer(model, world, assets, options, warnings).run();
    if (report) *report = r;
  } catch (const ImportError& ex) {
    return name + ": " + ex.what();
  } catch (const std::exception& ex) {  // e.g. an allocation the file asked for and the machine cannot hold
    return name + ": could not be imported (" + ex.what() + ")";
  }
  return {};
}

std::string parseFailure(const std::string& name, const std::string& err) {
  std::string first = err.substr(0, err.find('\n'));
  return name + ": not a valid glTF file (" + (first.empty() ? "parse failed" : first) + ")";
}

// The error contract is one line: names and strings quoted from the file (a light type, a node name) or
// a path from the command line may hold control characters and any length.
std::string oneLine(const std::string& message) { return platform::oneLine(message, 1000); }

// Parses bytes under the content rules (docs/CONTENT.md) and imports them: the JSON's depth checked
// before tinygltf recurses through it, files read only inside `baseDir` and the allowed folders, images
// decoded by gltf_content_rules.
std::string importBytes(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir, ecs::World& world,
                        AssetStore& assets, ImportReport* report, const ImportOptions& options) {
  namespace fs = std::filesystem;
  if (std::string deep = content::checkJsonDepth(data, size); !deep.empty()) return name + ": " + deep;
  content::ReadRules rules;
  rules.maxImageDimension = options.maxImageDimension;
  rules.maxImageBytes = options.maxImageBytes;
  std::vector<std::string> folders = options.allowedFolders;
  if (!baseDir.empty()) folders.push_back(baseDir);
  for (const std::string& f : folders) {
    std::error_code ec;
    const fs::path canonical = fs::canonical(f, ec);
    if (!ec) rules.folders.push_back(canonical.string());
  }
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(content::containedFiles(rules));
  tinygltf::Model model;
  rules.loading = &model;
  loader.SetImageLoader(&content::decodeImage, &rules);
  std::string err, warn;
  bool ok = false;
  const unsigned length = unsigned(std::min<size_t>(size, 0xFFFFFFFFu));
  try {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, length, baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data), length, baseDir);
  } catch (const std::exception& ex) {
    err = ex.what();
  }
  if (!ok) return parseFailure(name, err);
  return importModel(model, warn, name, world, assets, report, options);
}

std::string importGltfFile(const std::string& path, ecs::World& world, AssetStore& assets, ImportReport* report,
                           const ImportOptions& options) {
  std::vector<uint8_t> bytes;
  if (std::string bad = platform::readInputFile(path, bytes); !bad.empty()) return bad;
  const std::string folder = std::filesystem::path(path).parent_path().string();
  return importBytes(bytes.data(), bytes.size(), path, folder.empty() ? "." : folder, world, assets, report, options);
}
}  // namespace

std::string importGltf(const std::string& path, ecs::World& world, AssetStore& assets, ImportReport* report,
                       const ImportOptions& options) {
  return oneLine(importGltfFile(path, world, assets, report, options));
}

std::string importGltfFromMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                                 ecs::World& world, AssetStore& assets, ImportReport* report, const ImportOptions& options) {
  return oneLine(importBytes(data, size, name, baseDir, world, assets, report, options));
}

}  // namespace dyngi::scene
