#include "support/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace dyngi::test {
namespace {
std::string base64(const std::vector<uint8_t>& data) {
  static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < data.size(); i += 3) {
    uint32_t v = uint32_t(data[i]) << 16 | uint32_t(data[i + 1]) << 8 | data[i + 2];
    out += tbl[v >> 18 & 63];
    out += tbl[v >> 12 & 63];
    out += tbl[v >> 6 & 63];
    out += tbl[v & 63];
  }
  if (i + 1 == data.size()) {
    uint32_t v = uint32_t(data[i]) << 16;
    out += tbl[v >> 18 & 63];
    out += tbl[v >> 12 & 63];
    out += "==";
  } else if (i + 2 == data.size()) {
    uint32_t v = uint32_t(data[i]) << 16 | uint32_t(data[i + 1]) << 8;
    out += tbl[v >> 18 & 63];
    out += tbl[v >> 12 & 63];
    out += tbl[v >> 6 & 63];
    out += '=';
  }
  return out;
}

template <typename T>
size_t append(std::vector<uint8_t>& buf, const std::vector<T>& v) {
  while (buf.size() % 4) buf.push_back(0);
  size_t off = buf.size();
  buf.resize(off + v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(buf.data() + off, v.data(), v.size() * sizeof(T));
  return off;
}

std::string joinStrings(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
  return s;
}
}  // namespace

GltfPrimitiveSpec quadPrimitive(float h) {
  GltfPrimitiveSpec p;
  p.positions = {{-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}};
  p.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  p.indices = {0, 1, 2, 0, 2, 3};
  return p;
}

namespace {
// The document's JSON without its buffer, and the buffer's bytes; writeGltf / writeGlb wrap them.
struct Document {
  std::string jsonBeforeBuffers;  // everything up to (not including) "buffers"
  std::vector<uint8_t> bin;
};

std::string floatList(const float* v, size_t n) {
  std::ostringstream o;
  for (size_t i = 0; i < n; ++i) o << (i ? "," : "") << v[i];
  return o.str();
}

Document build(const GltfSpec& spec) {
  Document doc;
  std::vector<uint8_t>& buf = doc.bin;
  std::vector<std::string> views, accessors, meshes;
  auto addView = [&](size_t off, size_t len, const std::string& offsetRaw = {}) {
    views.push_back("{\"buffer\":0,\"byteOffset\":" + (offsetRaw.empty() ? std::to_string(off) : offsetRaw) +
                    ",\"byteLength\":" + std::to_string(len) + "}");
    return views.size() - 1;
  };
  // Appends `v` as one accessor of `type` / `componentType` and returns its index.
  auto addAccessor = [&](auto const& v, const char* type, int componentType, const std::string& extra = {}) {
    size_t off = append(buf, v);
    size_t view = addView(off, v.size() * sizeof(v[0]));
    accessors.push_back("{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" + std::to_string(componentType) +
                        ",\"count\":" + std::to_string(v.size()) + ",\"type\":\"" + type + "\"" + extra + "}");
    return accessors.size() - 1;
  };
  for (const auto& prims : spec.meshes) {
    std::vector<std::string> primJson;
    for (const auto& p : prims) {
      std::ostringstream pj;
      size_t off = append(buf, p.positions);
      size_t v = addView(off, p.positions.size() * 12, p.positionViewOffsetRaw);
      glm::vec3 mn(1e30f), mx(-1e30f);
      for (auto& q : p.positions) mn = glm::min(mn, q), mx = glm::max(mx, q);
      if (p.positions.empty()) mn = mx = glm::vec3(0);
      size_t count = p.positionCountOverride >= 0 ? size_t(p.positionCountOverride) : p.positions.size();
      std::ostringstream acc;
      acc << "{\"bufferView\":" << v << ",\"componentType\":5126,\"count\":"
          << (p.positionCountRaw.empty() ? std::to_string(count) : p.positionCountRaw) << ",\"type\":\"VEC3\"";
      if (glm::all(glm::lessThan(glm::abs(mn), glm::vec3(1e30f))) && glm::all(glm::lessThan(glm::abs(mx), glm::vec3(1e30f))))
        acc << ",\"min\":[" << mn.x << "," << mn.y << "," << mn.z << "],\"max\":[" << mx.x << "," << mx.y << "," << mx.z << "]";
      acc << "}";
      accessors.push_back(acc.str());
      pj << "{\"attributes\":{\"POSITION\":" << accessors.size() - 1;
      if (!p.normals.empty()) pj << ",\"NORMAL\":" << addAccessor(p.normals, "VEC3", 5126);
      if (!p.uvs.empty()) pj << ",\"TEXCOORD_0\":" << addAccessor(p.uvs, "VEC2", 5126);
      if (!p.joints.empty()) {
        std::vector<uint16_t> j16;
        for (auto& j : p.joints)
          for (int c = 0; c < 4; ++c) j16.push_back(uint16_t(j[c]));
        size_t joff = append(buf, j16);
        size_t jv = addView(joff, j16.size() * 2);
        accessors.push_back("{\"bufferView\":" + std::to_string(jv) + ",\"componentType\":5123,\"count\":" +
                            std::to_string(p.joints.size()) + ",\"type\":\"VEC4\"}");
        pj << ",\"JOINTS_0\":" << accessors.size() - 1;
        pj << ",\"WEIGHTS_0\":" << addAccessor(p.weights, "VEC4", 5126);
      }
      pj << "}";
      if (!p.indices.empty()) pj << ",\"indices\":" << addAccessor(p.indices, "SCALAR", 5125);
      pj << ",\"mode\":" << p.mode;
      if (p.material >= 0) pj << ",\"material\":" << p.material;
      pj << "}";
      primJson.push_back(pj.str());
    }
    meshes.push_back("{\"primitives\":[" + joinStrings(primJson) + "]}");
  }
  std::vector<std::string> skins;
  for (const auto& sk : spec.skins) {
    std::ostringstream sj;
    sj << "{\"joints\":[";
    for (size_t i = 0; i < sk.joints.size(); ++i) sj << (i ? "," : "") << sk.joints[i];
    sj << "]";
    if (!sk.inverseBind.empty()) sj << ",\"inverseBindMatrices\":" << addAccessor(sk.inverseBind, "MAT4", 5126);
    sj << "}";
    skins.push_back(sj.str());
  }
  std::vector<std::string> animations;
  for (const auto& an : spec.animations) {
    std::vector<std::string> channels, samplers;
    for (const auto& ch : an.channels) {
      // min/max only when they are numbers JSON can hold (a test may put NaN into the binary times).
      bool finiteTimes = !ch.times.empty() && std::all_of(ch.times.begin(), ch.times.end(), [](float t) { return std::isfinite(t); });
      size_t in = addAccessor(ch.times, "SCALAR", 5126,
                              finiteTimes ? ",\"min\":[" + floatList(ch.times.data(), 1) + "],\"max\":[" + floatList(&ch.times.back(), 1) + "]"
                                          : std::string());
      size_t out;
      if (ch.path == "rotation") out = addAccessor(ch.values, "VEC4", 5126);
      else {
        std::vector<glm::vec3> v3;
        for (auto& v : ch.values) v3.push_back(glm::vec3(v));
        out = addAccessor(v3, "VEC3", 5126);
      }
      samplers.push_back("{\"input\":" + std::to_string(in) + ",\"output\":" + std::to_string(out) + ",\"interpolation\":\"LINEAR\"}");
      channels.push_back("{\"sampler\":" + std::to_string(samplers.size() - 1) + ",\"target\":{\"node\":" +
                         std::to_string(ch.node) + ",\"path\":\"" + ch.path + "\"}}");
    }
    animations.push_back("{\"name\":\"" + an.name + "\",\"channels\":[" + joinStrings(channels) + "],\"samplers\":[" +
                         joinStrings(samplers) + "]}");
  }
  std::vector<std::string> nodes;
  for (const auto& n : spec.nodes) {
    std::ostringstream nj;
    nj << "{\"name\":\"" << n.name << "\"";
    if (n.mesh >= 0) nj << ",\"mesh\":" << n.mesh;
    if (n.camera >= 0) nj << ",\"camera\":" << n.camera;
    if (n.skin >= 0) nj << ",\"skin\":" << n.skin;
    if (n.light >= 0) nj << ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":" << n.light << "}}";
    if (!n.children.empty()) {
      nj << ",\"children\":[";
      for (size_t i = 0; i < n.children.size(); ++i) nj << (i ? "," : "") << n.children[i];
      nj << "]";
    }
    if (!n.transformJson.empty()) nj << "," << n.transformJson;
    nj << "}";
    nodes.push_back(nj.str());
  }
  std::vector<int> roots = spec.sceneNodes;
  if (roots.empty()) {
    std::vector<bool> child(spec.nodes.size(), false);
    for (auto& n : spec.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
    for (size_t i = 0; i < spec.nodes.size(); ++i)
      if (!child[i]) roots.push_back(int(i));
  }
  std::ostringstream j;
  j << "{\"asset\":{\"version\":\"2.0\"}";
  std::vector<std::string> used;
  if (!spec.lightsJson.empty()) used.push_back("\"KHR_lights_punctual\"");
  auto quoted = [](const std::vector<std::string>& names) {
    std::vector<std::string> q;
    for (const auto& n : names) q.push_back("\"" + n + "\"");
    return q;
  };
  for (const auto& q : quoted(spec.extensionsUsed)) used.push_back(q);
  j << ",\"extensionsUsed\":[" << joinStrings(used) << "]";
  if (!spec.extensionsRequired.empty()) j << ",\"extensionsRequired\":[" << joinStrings(quoted(spec.extensionsRequired)) << "]";
  if (!spec.lightsJson.empty()) j << ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" << joinStrings(spec.lightsJson) << "]}}";
  if (!spec.extraMembersJson.empty()) j << "," << spec.extraMembersJson;
  j << ",\"scene\":" << spec.sceneIndex << ",\"scenes\":[{\"nodes\":[";
  for (size_t i = 0; i < roots.size(); ++i) j << (i ? "," : "") << roots[i];
  j << "]}]";
  j << ",\"nodes\":[" << joinStrings(nodes) << "]";
  if (!meshes.empty()) j << ",\"meshes\":[" << joinStrings(meshes) << "]";
  if (!skins.empty()) j << ",\"skins\":[" << joinStrings(skins) << "]";
  if (!animations.empty()) j << ",\"animations\":[" << joinStrings(animations) << "]";
  if (!spec.materialsJson.empty()) j << ",\"materials\":[" << joinStrings(spec.materialsJson) << "]";
  if (!spec.camerasJson.empty()) j << ",\"cameras\":[" << joinStrings(spec.camerasJson) << "]";
  if (!spec.imagesJson.empty()) j << ",\"images\":[" << joinStrings(spec.imagesJson) << "]";
  if (!spec.texturesJson.empty()) j << ",\"textures\":[" << joinStrings(spec.texturesJson) << "]";
  if (!accessors.empty()) j << ",\"accessors\":[" << joinStrings(accessors) << "]";
  if (!views.empty()) j << ",\"bufferViews\":[" << joinStrings(views) << "]";
  doc.jsonBeforeBuffers = j.str();
  return doc;
}

void putU32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s += char((v >> (8 * i)) & 0xff);
}
}  // namespace

std::string dataUri(const std::string& mime, const std::vector<uint8_t>& bytes) { return "data:" + mime + ";base64," + base64(bytes); }

std::string writeGltf(const GltfSpec& spec) {
  Document doc = build(spec);
  std::string j = doc.jsonBeforeBuffers;
  if (!doc.bin.empty())
    j += ",\"buffers\":[{\"byteLength\":" + std::to_string(doc.bin.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
         base64(doc.bin) + "\"}]";
  return j + "}";
}

std::string writeGlb(const GltfSpec& spec) {
  Document doc = build(spec);
  while (doc.bin.size() % 4) doc.bin.push_back(0);
  std::string json = doc.jsonBeforeBuffers;
  if (!doc.bin.empty()) json += ",\"buffers\":[{\"byteLength\":" + std::to_string(doc.bin.size()) + "}]";
  json += "}";
  while (json.size() % 4) json += ' ';
  std::string out = "glTF";
  putU32(out, 2);
  putU32(out, uint32_t(12 + 8 + json.size() + (doc.bin.empty() ? 0 : 8 + doc.bin.size())));
  putU32(out, uint32_t(json.size()));
  putU32(out, 0x4E4F534Au);  // "JSON"
  out += json;
  if (!doc.bin.empty()) {
    putU32(out, uint32_t(doc.bin.size()));
    putU32(out, 0x004E4942u);  // "BIN\0"
    out.append(reinterpret_cast<const char*>(doc.bin.data()), doc.bin.size());
  }
  return out;
}

}  // namespace dyngi::test
