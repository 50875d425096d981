#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

#include <cmath>

namespace dyngi::scene {

Aabb Aabb::transformed(const glm::mat4& m) const {
  Aabb out;
  if (!valid()) return out;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
    out.extend(glm::vec3(m * glm::vec4(c, 1.0f)));
  }
  return out;
}

void MeshData::computeBounds() {
  bounds = Aabb{};
  usable = true;
  for (auto& p : positions) {
    usable = usable && withinCoordinateRange(p);  // glm::min/max would quietly drop a NaN
    bounds.extend(p);
  }
}

void MeshData::generateNormals() {
  normals.assign(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);  // |n| = 2 area
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (auto& n : normals) {
    float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

MeshId AssetStore::addMesh(MeshData mesh) {
  mesh.computeBounds();  // always: it also decides `usable`, which a host-built mesh must not skip
  meshes_.push_back(std::move(mesh));
  return MeshId(meshes_.size() - 1);
}

TextureId AssetStore::addTexture(TextureData texture) {
  textures_.push_back(std::move(texture));
  return TextureId(textures_.size() - 1);
}

namespace {
void appendQuad(MeshData& m, const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v) {
  uint32_t base = uint32_t(m.positions.size());
  glm::vec3 n = glm::normalize(glm::cross(u, v));
  const glm::vec3 ps[4] = {corner, corner + u, corner + u + v, corner + v};
  const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    m.positions.push_back(ps[i]);
    m.normals.push_back(n);
    m.uvs.push_back(uvs[i]);
  }
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}
}  // namespace

MeshData makeQuad(const glm::vec3& corner, const glm::vec3& edgeU, const glm::vec3& edgeV) {
  MeshData m;
  m.name = "quad";
  appendQuad(m, corner, edgeU, edgeV);
  m.computeBounds();
  return m;
}

MeshData makeBox(const glm::vec3& h) {
  MeshData m;
  m.name = "box";
  const glm::vec3 X(2 * h.x, 0, 0), Y(0, 2 * h.y, 0), Z(0, 0, 2 * h.z);
  appendQuad(m, {h.x, -h.y, h.z}, -Z, Y);     // +X
  appendQuad(m, {-h.x, -h.y, -h.z}, Z, Y);    // -X
  appendQuad(m, {-h.x, h.y, h.z}, X, -Z);     // +Y
  appendQuad(m, {-h.x, -h.y, -h.z}, X, Z);    // -Y
  appendQuad(m, {-h.x, -h.y, h.z}, X, Y);     // +Z
  appendQuad(m, {h.x, -h.y, -h.z}, -X, Y);    // -Z
  m.computeBounds();
  return m;
}

MeshData makeSphere(float radius, int segments, int rings) {
  MeshData m;
  m.name = "sphere";
  const float pi = 3.14159265358979f;
  for (int r = 0; r <= rings; ++r) {
    float phi = pi * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      float theta = 2.0f * pi * float(s) / float(segments);
      glm::vec3 n(std::sin(phi) * std::cos(theta), std::cos(phi), std::sin(phi) * std::sin(theta));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
      m.uvs.push_back({float(s) / float(segments), float(r) / float(rings)});
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
      for (uint32_t i : {a, a + 1, b, a + 1, b + 1, b}) m.indices.push_back(i);
    }
  m.computeBounds();
  return m;
}

}  // namespace dyngi::scene
