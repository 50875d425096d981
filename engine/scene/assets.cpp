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

void MeshData::computeTangents() {
  tangents.clear();
  if (uvs.size() != positions.size() || normals.size() != positions.size()) return;
  std::vector<glm::vec3> t(positions.size(), glm::vec3(0.0f)), b(positions.size(), glm::vec3(0.0f));
  for (size_t k = 0; k + 2 < indices.size(); k += 3) {
    const uint32_t i0 = indices[k], i1 = indices[k + 1], i2 = indices[k + 2];
    const glm::vec3 e1 = positions[i1] - positions[i0], e2 = positions[i2] - positions[i0];
    const glm::vec2 d1 = uvs[i1] - uvs[i0], d2 = uvs[i2] - uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-12f)) continue;  // no uv area: no frame from this triangle
    const glm::vec3 tu = (e1 * d2.y - e2 * d1.y) / det, tv = (e2 * d1.x - e1 * d2.x) / det;
    for (uint32_t i : {i0, i1, i2}) t[i] += tu, b[i] += tv;
  }
  tangents.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3 n = normals[i];
    glm::vec3 tt = t[i] - n * glm::dot(n, t[i]);
    if (!(glm::dot(tt, tt) > 1e-20f)) {  // no uv frame here: any direction across the normal
      tt = glm::cross(n, std::abs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    }
    tt = glm::normalize(tt);
    const float sign = glm::dot(glm::cross(n, tt), b[i]) < 0.0f ? -1.0f : 1.0f;
    tangents[i] = glm::vec4(tt, sign);
  }
}

namespace {
float srgbToLinear(uint8_t v) {
  const float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
}  // namespace

glm::vec4 sampleTexture(const TextureData& t, glm::vec2 uv) {
  if (t.width == 0 || t.height == 0 || t.rgba8.size() < size_t(t.width) * t.height * 4) return glm::vec4(1.0f);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
  const float x = (uv.x - std::floor(uv.x)) * float(t.width) - 0.5f, y = (uv.y - std::floor(uv.y)) * float(t.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](int xi, int yi) {
    const uint32_t xx = uint32_t((xi % int(t.width) + int(t.width)) % int(t.width));
    const uint32_t yy = uint32_t((yi % int(t.height) + int(t.height)) % int(t.height));
    const uint8_t* p = &t.rgba8[(size_t(yy) * t.width + xx) * 4];
    const glm::vec3 rgb = t.srgb ? glm::vec3(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2])) : glm::vec3(p[0], p[1], p[2]) / 255.0f;
    return glm::vec4(rgb, float(p[3]) / 255.0f);
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

}  // namespace dyngi::scene
