#include "indirect/emitters.h"

#include <algorithm>
#include <cmath>

namespace dyngi::gi {
namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kTwoPi = 2.0f * kPi;

// The mean of an emissive texture, from a 16 x 16 grid of lookups: the triangles' power estimate only
// steers which one is sampled, the sample's own radiance is exact.
glm::vec3 textureMean(const scene::AssetStore& assets, scene::TextureId id) {
  if (id == scene::kNoTexture || id >= assets.textureCount()) return glm::vec3(1.0f);
  glm::dvec3 sum(0.0);
  constexpr int kGrid = 16;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x)
      sum += glm::dvec3(scene::sampleTexture(assets.texture(id), (glm::vec2(x, y) + 0.5f) / float(kGrid)));
  return glm::vec3(sum / double(kGrid * kGrid));
}
}  // namespace

EmitterSet::EmitterSet(const render::RenderSnapshot& snapshot, const scene::AssetStore& assets)
    : snap_(snapshot), assets_(assets) {
  for (size_t d = 0; d < snapshot.draws.size(); ++d) {
    const render::DrawItem& draw = snapshot.draws[d];
    const glm::vec3 factor = snapshot.materialOf(draw).emissive;
    if (!(emitterLuminance(factor) > 0.0f) || draw.mesh >= assets.meshCount()) continue;
    const scene::MeshData& m = assets.mesh(draw.mesh);
    if (!m.usable) continue;
    const float radiance = emitterLuminance(factor * textureMean(assets, snapshot.materialOf(draw).emissiveTexture));
    if (!(radiance > 0.0f) || !std::isfinite(radiance)) continue;
    float entityTotal = 0.0f;
    std::vector<float>& pdfs = pdfArea_[draw.entity];
    pdfs.assign(m.indices.size() / 3, 0.0f);
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const glm::vec3 p0 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t]], 1.0f));
      const glm::vec3 p1 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t + 1]], 1.0f));
      const glm::vec3 p2 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t + 2]], 1.0f));
      const float area = 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
      if (!(area > 0.0f) || !std::isfinite(area)) continue;  // degenerate: emits nothing
      const float power = kTwoPi * area * radiance;  // Lambertian, both sides: 2 pi A L
      total_ += power;
      entityTotal += power;
      triangles_.push_back({d, uint32_t(t / 3), area, total_});
      pdfs[t / 3] = power / area;  // divided by the total below: p(triangle) / A
    }
    if (entityTotal > 0.0f) sources_.push_back({draw.entity, entityTotal, factor});
  }
  for (auto& [entity, pdfs] : pdfArea_)
    for (float& p : pdfs) p = total_ > 0.0f ? p / total_ : 0.0f;
  if (!triangles_.empty()) surfaces_.emplace(snapshot, assets);
}

float EmitterSet::pdfArea(ecs::Entity entity, uint32_t primitive) const {
  const auto it = pdfArea_.find(entity);
  return it != pdfArea_.end() && primitive < it->second.size() ? it->second[primitive] : 0.0f;
}

float lightPower(const render::LightItem& l, const scene::Aabb& bounds) {
  if (!l.light.enabled) return 0.0f;
  const float i = l.light.intensity * emitterLuminance(l.light.color);
  switch (l.light.type) {
    case scene::LightType::Point: return i * 4.0f * kPi;
    case scene::LightType::Spot: return i * 2.0f * kPi * (1.0f - std::cos(std::clamp(l.light.outerConeAngle, 1e-3f, 1.5707f)));
    case scene::LightType::Directional: {
      const float r = bounds.valid() ? 0.5f * glm::length(bounds.extent()) : 1.0f;
      return i * kPi * r * r;
    }
  }
  return 0.0f;
}

float EmitterSet::power(ecs::Entity entity) const {
  for (const EmitterSource& s : sources_)
    if (s.entity == entity) return s.power;
  return 0.0f;
}

EmitterSample EmitterSet::sample(float u0, float u1, float u2, float u3) const {
  EmitterSample s;
  if (triangles_.empty()) return s;
  const float target = u0 * total_;
  size_t i = size_t(std::upper_bound(triangles_.begin(), triangles_.end(), target, [](float v, const Triangle& t) { return v < t.cdf; }) -
                    triangles_.begin());
  i = std::min(i, triangles_.size() - 1);
  const Triangle& tri = triangles_[i];
  const float before = i > 0 ? triangles_[i - 1].cdf : 0.0f;
  const float p = (tri.cdf - before) / total_;  // the chance of this triangle
  const render::DrawItem& draw = snap_.draws[tri.draw];
  const scene::MeshData& m = assets_.mesh(draw.mesh);
  // Uniform point: barycentrics from the square root warp.
  const float su = std::sqrt(u1);
  RayHit h;
  h.hit = true;
  h.entity = draw.entity;
  h.mesh = draw.mesh;
  h.primitive = tri.primitive;
  h.u = su * (1.0f - u2);
  h.v = su * u2;
  const size_t t = size_t(tri.primitive) * 3;
  const glm::vec3 p0 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t]], 1.0f));
  const glm::vec3 p1 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t + 1]], 1.0f));
  const glm::vec3 p2 = glm::vec3(draw.model * glm::vec4(m.positions[m.indices[t + 2]], 1.0f));
  const glm::vec3 point = (1.0f - h.u - h.v) * p0 + h.u * p1 + h.v * p2;
  glm::vec3 side = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  if (u3 >= 0.5f) side = -side;
  // The surface as the path tracer reads it (textured emission, shading normal) seen from that side.
  h.t = 1.0f;
  SurfaceHit sh;
  if (!surfaces_->at(h, point + side, -side, sh)) return s;
  s.position = point;
  s.normal = sh.shadingNormal;
  s.faceNormal = side;
  s.flux = sh.emission * (kTwoPi * tri.area / p);
  s.radiance = sh.emission;
  s.pdfArea = p / tri.area;
  s.entity = draw.entity;
  return s;
}

}  // namespace dyngi::gi
