#include "bvh/scene_surfaces.h"

#include <algorithm>
#include <cmath>

#include "shared/normal_map.h"
#include "shared/uv_transform.h"

namespace dyngi::gi {

SceneSurfaces::SceneSurfaces(const render::RenderSnapshot& s, const scene::AssetStore& assets) : snap_(s), assets_(assets) {
  normalMatrices_.reserve(s.draws.size());
  for (size_t i = 0; i < s.draws.size(); ++i) {
    drawOf_[s.draws[i].entity] = i;
    normalMatrices_.push_back(glm::transpose(glm::inverse(glm::mat3(s.draws[i].model))));
  }
  float extent = s.sceneBounds.valid() ? glm::length(s.sceneBounds.extent()) : 1.0f;
  sceneScale_ = std::max(extent, 1e-3f);
}

bool SceneSurfaces::at(const RayHit& h, const glm::vec3& origin, const glm::vec3& dir, SurfaceHit& out) const {
  auto it = drawOf_.find(h.entity);
  if (it == drawOf_.end()) return false;
  const render::DrawItem& d = snap_.draws[it->second];
  const scene::MeshData& m = assets_.mesh(h.mesh);
  size_t t = size_t(h.primitive) * 3;
  if (t + 2 >= m.indices.size()) return false;
  uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
  float w0 = 1.0f - h.u - h.v;
  const glm::mat3& normalMatrix = normalMatrices_[it->second];
  glm::vec3 p0 = m.positions[i0], p1 = m.positions[i1], p2 = m.positions[i2];
  out.position = origin + dir * h.t;
  out.entity = h.entity;
  glm::vec3 ng = glm::normalize(normalMatrix * glm::cross(p1 - p0, p2 - p0));
  glm::vec3 ns = m.normals.size() == m.positions.size()
                     ? glm::normalize(normalMatrix * (w0 * m.normals[i0] + h.u * m.normals[i1] + h.v * m.normals[i2]))
                     : ng;
  const scene::Material& mat = snap_.materialOf(d);
  glm::vec2 uv(0.0f);
  if (m.uvs.size() == m.positions.size()) uv = w0 * m.uvs[i0] + h.u * m.uvs[i1] + h.v * m.uvs[i2];
  uv = gpu::applyUvTransform(mat.uvTransform.linear(), mat.uvTransform.offset, uv);  // KHR_texture_transform
  // Lit on the side the ray arrives from (as the G-buffer does for the camera): decided on the
  // interpolated normal, applied to the normal texture's too.
  if (glm::dot(ng, dir) > 0.0f) ng = -ng;
  const bool back = glm::dot(ns, ng) < 0.0f;
  if (mat.normalTexture != scene::kNoTexture && mat.normalTexture < assets_.textureCount() && m.tangents.size() == m.positions.size()) {
    const glm::vec4 tangent = w0 * m.tangents[i0] + h.u * m.tangents[i1] + h.v * m.tangents[i2];
    const glm::vec4 worldTangent(glm::mat3(d.model) * glm::vec3(tangent), m.tangents[i0].w);
    ns = gpu::perturbNormal(ns, worldTangent, texel(mat.normalTexture, uv), mat.normalScale);
  }
  if (back) ns = -ns;
  out.geometricNormal = ng;
  out.shadingNormal = ns;
  glm::vec3 base(mat.baseColor);
  if (mat.baseColorTexture != scene::kNoTexture && mat.baseColorTexture < assets_.textureCount()) base *= texel(mat.baseColorTexture, uv);
  float metallic = mat.metallic;
  if (mat.metallicRoughnessTexture != scene::kNoTexture && mat.metallicRoughnessTexture < assets_.textureCount())
    metallic *= texel(mat.metallicRoughnessTexture, uv).b;  // glTF: metallic in B
  out.diffuseAlbedo = base * (1.0f - metallic);
  out.emission = mat.emissive;
  if (mat.emissiveTexture != scene::kNoTexture && mat.emissiveTexture < assets_.textureCount()) out.emission *= texel(mat.emissiveTexture, uv);
  return true;
}

glm::vec3 SceneSurfaces::texel(scene::TextureId id, glm::vec2 uv) const { return glm::vec3(scene::sampleTexture(assets_.texture(id), uv)); }

}  // namespace dyngi::gi
