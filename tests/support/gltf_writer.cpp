#include "support/gltf_writer.h"

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

std::string writeGltf(const GltfSpec& spec) {
  std::vector<uint8_t> buf;
  std::vector<std::string> views, accessors, meshes;
  auto addView = [&](size_t off, size_t len) {
    views.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(off) + ",\"byteLength\":" + std::to_string(len) + "}");
    return views.size() - 1;
  };
  for (const auto& prims : spec.meshes) {
    std::vector<std::string> primJson;
    for (const auto& p : prims) {
      std::ostringstream pj;
      size_t off = append(buf, p.positions);
      size_t v = addView(off, p.positions.size() * 12);
      glm::vec3 mn(1e30f), mx(-1e30f);
      for (auto& q : p.positions) mn = glm::min(mn, q), mx = glm::max(mx, q);
      if (p.positions.empty()) mn = mx = glm::vec3(0);
      size_t count = p.positionCountOverride >= 0 ? size_t(p.positionCountOverride) : p.positions.size();
      std::ostringstream acc;
      acc << "{\"bufferView\":" << v << ",\"componentType\":5126,\"count\":" << count << ",\"type\":\"VEC3\",\"min\":[" << mn.x
          << "," << mn.y << "," << mn.z << "],\"max\":[" << mx.x << "," << mx.y << "," << mx.z << "]}";
      accessors.push_back(acc.str());
      pj << "{\"attributes\":{\"POSITION\":" << accessors.size() - 1;
      if (!p.normals.empty()) {
        size_t noff = append(buf, p.normals);
        size_t nv = addView(noff, p.normals.size() * 12);
        accessors.push_back("{\"bufferView\":" + std::to_string(nv) + ",\"componentType\":5126,\"count\":" +
                            std::to_string(p.normals.size()) + ",\"type\":\"VEC3\"}");
        pj << ",\"NORMAL\":" << accessors.size() - 1;
      }
      pj << "}";
      if (!p.indices.empty()) {
        size_t ioff = append(buf, p.indices);
        size_t iv = addView(ioff, p.indices.size() * 4);
        accessors.push_back("{\"bufferView\":" + std::to_string(iv) + ",\"componentType\":5125,\"count\":" +
                            std::to_string(p.indices.size()) + ",\"type\":\"SCALAR\"}");
        pj << ",\"indices\":" << accessors.size() - 1;
      }
      pj << ",\"mode\":" << p.mode;
      if (p.material >= 0) pj << ",\"material\":" << p.material;
      pj << "}";
      primJson.push_back(pj.str());
    }
    meshes.push_back("{\"primitives\":[" + joinStrings(primJson) + "]}");
  }
  std::vector<std::string> nodes;
  for (const auto& n : spec.nodes) {
    std::ostringstream nj;
    nj << "{\"name\":\"" << n.name << "\"";
    if (n.mesh >= 0) nj << ",\"mesh\":" << n.mesh;
    if (n.camera >= 0) nj << ",\"camera\":" << n.camera;
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
  j << ",\"extensionsUsed\":[" << joinStrings(used) << "]";
  if (!spec.lightsJson.empty()) j << ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" << joinStrings(spec.lightsJson) << "]}}";
  j << ",\"scene\":0,\"scenes\":[{\"nodes\":[";
  for (size_t i = 0; i < roots.size(); ++i) j << (i ? "," : "") << roots[i];
  j << "]}]";
  j << ",\"nodes\":[" << joinStrings(nodes) << "]";
  if (!meshes.empty()) j << ",\"meshes\":[" << joinStrings(meshes) << "]";
  if (!spec.materialsJson.empty()) j << ",\"materials\":[" << joinStrings(spec.materialsJson) << "]";
  if (!spec.camerasJson.empty()) j << ",\"cameras\":[" << joinStrings(spec.camerasJson) << "]";
  if (!accessors.empty()) j << ",\"accessors\":[" << joinStrings(accessors) << "]";
  if (!views.empty()) j << ",\"bufferViews\":[" << joinStrings(views) << "]";
  if (!buf.empty())
    j << ",\"buffers\":[{\"byteLength\":" << buf.size() << ",\"uri\":\"data:application/octet-stream;base64," << base64(buf) << "\"}]";
  j << "}";
  return j.str();
}

}  // namespace dyngi::test
